#!/usr/bin/env python3
"""Every reference from one document to another resolves: each Markdown link
`[text](file#anchor)` to a file of the tree names a file that exists and, for
a Markdown file, an anchor one of its headings makes (GitHub's rule); each
section named in words (`README, "Section"`, `docs/simulator.md, "Section"`,
`[docs/kdtree.md](kdtree.md), "Section"`, `"Section" above`) is a heading of
that file; each docs/FILE named by its path exists. Checks README.md, docs/*.md, docs/*.yaml and the comments of
scripts/ and the C++ sources.
  tests/docs/doc_links_test.py [SOURCE_DIR]"""
import glob
import os
import re
import sys

root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
    print(__doc__)
    sys.exit(0)


def plain(title):
    """A heading's text as a reader quotes it: no Markdown emphasis or code marks."""
    title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title)
    return re.sub(r"\s+", " ", title.replace("`", "").replace("*", "")).strip()


def slug(title):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    s = plain(title).lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


headings_of = {}


def headings(path):
    """(titles, anchors) of a Markdown file; code blocks are not headings."""
    if path not in headings_of:
        titles, anchors, seen, fence = set(), set(), {}, False
        for line in open(path, encoding="utf-8"):
            if line.startswith("```"):
                fence = not fence
            m = None if fence else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                titles.add(plain(m.group(1)).lower())
                a = slug(m.group(1))
                n = seen.get(a, 0)
                seen[a] = n + 1
                anchors.add(a if n == 0 else "%s-%d" % (a, n))
        # Explicit anchors (<a id="..."> or <a name="...">).
        for m in re.finditer(r'<a (?:id|name)="([^"]+)"', open(path, encoding="utf-8").read()):
            anchors.add(m.group(1))
        headings_of[path] = (titles, anchors)
    return headings_of[path]


def has_section(path, quoted):
    """A quoted title names a heading: the whole heading, or the heading before its
    parenthesised option ("Ray order" for "Ray order (`--ray-order ...`)")."""
    q = plain(quoted).lower()
    return any(t == q or t.startswith(q + " (") or t.startswith(q + ":") for t in headings(path)[0])


def text_of(path):
    """The file as one line of words: comment marks dropped, so a quoted title may wrap."""
    lines = []
    is_md = path.endswith(".md")
    for line in open(path, encoding="utf-8", errors="replace"):
        if not is_md:
            m = re.match(r"\s*(?:#|//|\*|;)\s?(.*)", line)
            if not m:
                continue  # only comments speak of documents
            line = m.group(1)
        lines.append(line.rstrip("\n"))
    return lines


def doc_path(name, here):
    """The file a reference's name means, relative to the referring file or the tree's root."""
    if name == "README":
        return os.path.join(root, "README.md")
    for base in (os.path.dirname(here), root):
        p = os.path.normpath(os.path.join(base, name))
        if os.path.exists(p):
            return p
    return None


errors = []
files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
files += sorted(glob.glob(os.path.join(root, "docs", "*.yaml")))
for pattern in ("scripts/*", "sim/*.h", "sim/*.cpp", "sw/**/*.h", "sw/**/*.cpp", "tests/**/*.cpp",
                "tests/**/*.h", "tests/**/*.sh", "bench/*.cpp", "rtl/**/*.sv", "Makefile"):
    files += sorted(f for f in glob.glob(os.path.join(root, pattern), recursive=True) if os.path.isfile(f))

link = re.compile(r"\]\(([^)\s]+)\)")
# A named document followed by a quoted section title (the title may wrap).
named = re.compile(r"(README(?:\.md)?|\[[^\]]*\]\(([\w./-]+\.md)\)|\b(?:docs/)?[\w-]+\.md)`?\)?,? \"([^\"]+)\"")
local = re.compile(r"\"([^\"]+)\" (?:above|below)")
checked = 0
for f in files:
    rel = os.path.relpath(f, root)
    lines = text_of(f)
    words = re.sub(r"\s+", " ", " ".join(lines))
    if f.endswith(".md"):
        # Code blocks hold commands, not links.
        body, fence = [], False
        for line in lines:
            if line.startswith("```"):
                fence = not fence
            elif not fence:
                body.append(line)
        for n, line in enumerate(body):
            for m in link.finditer(line):
                target = m.group(1)
                if re.match(r"[a-z]+:", target):
                    continue  # http:, mailto: ...
                checked += 1
                name, _, anchor = target.partition("#")
                path = f if name == "" else doc_path(name, f)
                if path is None:
                    errors.append("%s: link to %s: no such file" % (rel, target))
                elif anchor and path.endswith(".md") and anchor not in headings(path)[1]:
                    errors.append("%s: link to %s: %s has no heading with anchor #%s" %
                                  (rel, target, os.path.relpath(path, root), anchor))
    # A document named by its path (docs/x.md in a comment or between backticks) exists.
    for m in re.finditer(r"(?<![\w/.-])(docs/[\w.-]+\.(?:md|yaml|svg|csv|png|json))\b", words):
        checked += 1
        if not os.path.exists(os.path.join(root, m.group(1))):
            errors.append("%s: %s: no such file" % (rel, m.group(1)))
    for m in named.finditer(words):
        name = m.group(2) or m.group(1)
        if name == "README.md" and m.group(1).startswith("["):
            name = m.group(2)
        path = doc_path(name if name != "README.md" else "README", f)
        if name.startswith("[") or path is None or not path.endswith(".md"):
            if path is None:
                errors.append('%s: %s, "%s": no such file' % (rel, name, m.group(3)))
            continue
        checked += 1
        if not has_section(path, m.group(3)):
            errors.append('%s: %s, "%s": %s has no such section' % (rel, name, m.group(3), os.path.relpath(path, root)))
    if f.endswith(".md"):
        for m in local.finditer(words):
            checked += 1
            if not has_section(f, m.group(1)):
                errors.append('%s: "%s" %s: no such section in this file' % (rel, m.group(1), m.group(0).split()[-1]))

if errors:
    print("doc_links: %d references do not resolve:" % len(errors), file=sys.stderr)
    for e in errors:
        print("  " + e, file=sys.stderr)
    sys.exit(1)
print("doc_links: %d references in %d files resolve" % (checked, len(files)))
