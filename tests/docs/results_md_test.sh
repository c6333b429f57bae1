#!/usr/bin/env bash
# scripts/results_md.py writes what the remeasure steps measured: the steps'
# own scripts run on tiny scenes (gen:NAME:1000, 32x32, the fast model) into
# a fixture OUT, the generator rewrites copies of docs/results.md and the
# README, and every table must carry the numbers of those runs while the
# text outside the results blocks stays byte for byte. The blocks of the
# RTL-timed steps (no RTL run here) keep their text and are named on stderr.
#   tests/docs/results_md_test.sh KDRT [SOURCE_DIR]
set -euo pipefail
kdrt=$1
root=${2:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$tmp/out
mkdir -p "$out"
cd "$root"
fail() { echo "results_md_test: $*" >&2; exit 1; }

fast=(--model fast)
JSONL=$out/eff128.jsonl scripts/efficiency.sh "$kdrt" 32x32 "20 200" gen:balls:1000 gen:rings:1000 -- "${fast[@]}" \
  > "$out/eff128.md" 2> "$tmp/err"
JSONL=$out/eff1024.jsonl scripts/efficiency.sh "$kdrt" 48x48 "20 200" gen:balls:1000 gen:rings:1000 -- "${fast[@]}" \
  > "$out/eff1024.md" 2> "$tmp/err"
for s in room balls rings tetra tree gears; do
  "$kdrt" sim "gen:$s:1000" --res 32x32 --shade --ao 2 --bounce "${fast[@]}" -q -o "$tmp/s.png" \
    --json "$out/shade_$s.json"
done
scripts/scaling.sh "$kdrt" 32x32 "1 2" "16 2" "$out/scaling" gen:balls:1000 -- "${fast[@]}" > "$out/scaling.md" \
  2> "$tmp/err"
scripts/packed-images.sh "$kdrt" 32x32 gen:balls:1000 -- "${fast[@]}" > "$out/packed.md" 2> "$tmp/err"
scripts/packed-images.sh "$kdrt" 32x32 gen:balls:1000 -- "${fast[@]}" --trav-format fp32 > "$out/travfmt.md" \
  2> "$tmp/err"

cp README.md "$tmp/README.md"
mkdir -p "$tmp/docs"
cp docs/results.md "$tmp/docs/results.md"
gen=(python3 scripts/results_md.py "$out" --results "$tmp/docs/results.md" --readme "$tmp/README.md")

# Before writing, --check sees the change; after it, nothing is left to change.
if "${gen[@]}" --check 2> /dev/null; then fail "--check found nothing to change before the first write"; fi
"${gen[@]}" 2> "$tmp/gen.err" || { cat "$tmp/gen.err" >&2; fail "the generator failed"; }
"${gen[@]}" --check 2> /dev/null || fail "a second run would change the files again"
for block in speed readme-speed; do
  grep -q "kept as it was: .*: $block (.*speed1.json" "$tmp/gen.err" || fail "block $block not named as kept"
done
[ -f "$tmp/docs/scaling.svg" ] && [ -f "$tmp/docs/scaling.csv" ] || fail "scaling.svg/csv not copied beside results.md"

python3 - "$out" "$tmp" "$root" <<'PY'
import csv, json, os, re, sys
out, tmp, root = sys.argv[1:]
MARK = re.compile(r"<!-- results:([\w-]+) begin -->\n(.*?)<!-- results:\1 end -->", re.S)
errors = []

def blocks(text):
    return {m.group(1): m.group(2) for m in MARK.finditer(text)}

def outside(text):
    return MARK.sub(lambda m: m.group(1), text)

for name in ("README.md", "docs/results.md"):
    old, new = open(os.path.join(root, name)).read(), open(os.path.join(tmp, name)).read()
    if outside(old) != outside(new):
        errors.append("%s: text outside the results blocks changed" % name)
    if blocks(old).keys() != blocks(new).keys():
        errors.append("%s: the blocks changed: %s -> %s" % (name, list(blocks(old)), list(blocks(new))))
    for kept in ("speed", "readme-speed"):
        if kept in blocks(old) and blocks(old)[kept] != blocks(new)[kept]:
            errors.append("%s: block %s changed without its step outputs" % (name, kept))
res = blocks(open(os.path.join(tmp, "docs/results.md")).read())
readme = blocks(open(os.path.join(tmp, "README.md")).read())

def expect(where, block, text):
    if " ".join(text.split()) not in " ".join(block.split()):
        errors.append("%s lacks %r" % (where, text))

def scene(s):
    g, n = s.split(":")[-2:]
    return "%s %dk" % (g, int(n) // 1000)

# Primary rays: every run's cycles per ray and efficiency, in results.md; both sizes in the README.
for f in ("eff128.jsonl", "eff1024.jsonl"):
    for line in open(os.path.join(out, f)):
        r = json.loads(line)
        cell = "%.2f (%.1f %%" % (r["cycles_per_ray"], 100 * r["efficiency"])
        row = [l for l in res["primary"].splitlines() if l.startswith("| %s |" % scene(r["scene"]))]
        if len(row) != 1 or cell not in row[0] or "%.2f" % r["bound_cycles_per_ray"] not in row[0]:
            errors.append("results.md primary: row of %s lacks %s" % (r["scene"], cell))
        expect("README efficiency", readme["readme-efficiency"], cell)
expect("results.md primary", res["primary"], "32x32")
expect("results.md primary", res["primary"], "bound, 48x48")
# Shaded frames: each pass and the frame.
for s in ("room", "balls", "rings", "tetra", "tree", "gears"):
    r = json.load(open(os.path.join(out, "shade_%s.json" % s)))
    row = "| %s 1k | " % s + " | ".join(
        "%.2f (%.1f %%)" % (p["stats"]["cycles_per_ray"], 100 * p["stats"]["efficiency"]) for p in r["passes"]) + \
        " | %.2f (%.1f %%) |" % (r["frame"]["cycles_per_ray"], 100 * r["frame"]["efficiency"])
    expect("results.md shaded", res["shaded"], row)
    expect("README shaded", readme["readme-shaded"], row)
# Several cores: the 2-core speed-up over one core, and scaling.sh's own table.
rows = list(csv.DictReader(open(os.path.join(out, "scaling.csv"))))
up = float(rows[1]["rays_per_cycle"]) / float(rows[0]["rays_per_cycle"])
expect("results.md cores", res["cores"], "balls 1k %.2fx at 2 cores" % up)
expect("results.md cores", res["cores"], "scaling.sh build/bin/kdrt 32x32 \"1 2\" \"16 2\"")
expect("README cores", readme["readme-cores"], "balls 1k %.2fx at 2 cores" % up)
expect("results.md cores", res["cores"], open(os.path.join(out, "scaling.md")).read().strip())
# Packed images: the step's table as it wrote it.
expect("results.md packed", res["packed"], open(os.path.join(out, "packed.md")).read().strip())
expect("results.md packed", res["packed"], "packed-images.sh build/bin/kdrt 128x128 gen:balls:1000 -- --model fast`")
expect("results.md wider", res["wider"], open(os.path.join(out, "travfmt.md")).read().strip())
if errors:
    print("results_md_test: " + "\nresults_md_test: ".join(errors), file=sys.stderr)
    sys.exit(1)
PY

# A truncated step output is an error naming the file, and nothing is written.
cp "$tmp/README.md" "$tmp/README.before"
head -c 100 "$out/shade_room.json" > "$tmp/x" && mv "$tmp/x" "$out/shade_room.json"
if "${gen[@]}" 2> "$tmp/gen.err"; then fail "a truncated shade_room.json was accepted"; fi
grep -q "shade_room.json" "$tmp/gen.err" || fail "the error does not name shade_room.json: $(cat "$tmp/gen.err")"
cmp -s "$tmp/README.md" "$tmp/README.before" || fail "a failed run changed the README"
# A failed step (OUT/times) keeps its blocks.
"$kdrt" sim gen:room:1000 --res 32x32 --shade --ao 2 --bounce "${fast[@]}" -q -o "$tmp/s.png" \
  --json "$out/shade_room.json"
echo "scaling FAILED" > "$out/times"
"${gen[@]}" 2> "$tmp/gen.err"
grep -q "readme-cores (scaling.csv: its step failed" "$tmp/gen.err" || fail "a failed step's block was not kept"
echo "results_md_test: every table carries its step's numbers; the text around the blocks is unchanged"
