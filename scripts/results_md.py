#!/usr/bin/env python3
"""Writes the measured tables of scripts/remeasure.sh's OUT into the docs.

  scripts/results_md.py OUT [--results FILE] [--readme FILE] [--check]

Each document holds blocks between `<!-- results:NAME begin -->` and
`<!-- results:NAME end -->`; every block is rewritten from the step outputs
in OUT it names (the text around the blocks stays as it is), and
OUT/scaling.svg and OUT/scaling.csv are copied beside the results file.
A block whose step outputs are missing from OUT (a --timed-only or
--no-timed run, a failed step) keeps its text; each such block is named on
stderr. --check writes nothing and exits 1 when a file would change.
Defaults: docs/results.md and README.md of the tree holding this script.
Python 3 standard library only.
"""
import csv
import glob
import json
import os
import re
import shutil
import statistics
import sys
import textwrap


class Missing(Exception):
    """A block's step outputs are not in OUT."""


class BadInput(Exception):
    """A step output that cannot be read as its step writes it."""


def failed_steps(out):
    """The steps OUT/times notes as failed: their outputs may be partial."""
    try:
        with open(os.path.join(out, "times")) as f:
            return {line.split()[0] for line in f if line.strip().endswith("FAILED")}
    except OSError:
        return set()


def need(out, *names):
    """The paths of a block's step outputs; the step is the name's first part (lat200/sweep.csv: lat200)."""
    paths = [os.path.join(out, n) for n in names]
    failed = failed_steps(out)
    bad = [n for n in names if re.split(r"[/.]", n)[0] in failed]
    if bad:
        raise Missing("%s: its step failed (OUT/times)" % ", ".join(bad))
    missing = [n for n, p in zip(names, paths) if not os.path.exists(p)]
    if missing:
        raise Missing(", ".join(missing))
    return paths


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise BadInput("%s: %s" % (path, e))


def read_jsonl(path):
    rows = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                rows.append(json.loads(line))
            except ValueError as e:
                raise BadInput("%s:%d: %s" % (path, n, e))
    if not rows:
        raise BadInput("%s: no runs" % path)
    return rows


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise BadInput("%s: no rows" % path)
    return rows


def read_text(path):
    with open(path) as f:
        text = f.read().strip()
    if not text:
        raise BadInput("%s: empty" % path)
    return text


def pc(x):
    return "%.1f %%" % (100 * x)


def size_name(n):
    n = int(n)
    if n >= 1000000 and n % 1000000 == 0:
        return "%dM" % (n // 1000000)
    if n >= 1000 and n % 1000 == 0:
        return "%dk" % (n // 1000)
    return str(n)


def scene_name(scene):
    """gen:balls:100000 -> balls 100k; a file keeps its name."""
    m = re.fullmatch(r"(?:gen:)?(\w+):(\d+)", scene)
    return "%s %s" % (m.group(1), size_name(m.group(2))) if m else scene


WORDS = {1: "one", 2: "two", 3: "three", 4: "four", 5: "five", 6: "six", 7: "seven", 8: "eight", 9: "nine"}


def and_list(items):
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def generators(scenes):
    """'the six generators at 10k, 100k and 1M' for the generator scenes of a run."""
    gens, sizes = [], []
    for s in scenes:
        m = re.fullmatch(r"(?:gen:)?(\w+):(\d+)", s)
        if m:
            gens += [m.group(1)] if m.group(1) not in gens else []
            sizes += [int(m.group(2))] if int(m.group(2)) not in sizes else []
    n = len(gens)
    return "%s generator%s at %s" % (WORDS.get(n, str(n)), "s" if n > 1 else "", and_list(map(size_name, sizes))), sizes


DOC_WIDTH, README_WIDTH = 116, 76  # the line lengths of docs/results.md and the README


def para(text, width, indent=""):
    """A paragraph wrapped as the documents are (code spans may wrap: Markdown joins the lines)."""
    text = re.sub(r"\s+", " ", text).strip().replace(" %", "\u00a0%")  # "90 %" stays on one line
    return textwrap.fill(text, width, subsequent_indent=indent, break_long_words=False,
                         break_on_hyphens=False).replace("\u00a0", " ")


def res_of(report):
    return "%dx%d" % (report["width"], report["height"])


def with_scene(report, path):
    if "scene" not in report:
        raise BadInput("%s: a run without its scene" % path)
    return report


def speedups(x):
    return "%.0fx" % x


def span(lo, hi, fmt):
    a, b = fmt % lo, fmt % hi
    return a if a == b else "%s-%s" % (a, b)


# --- primary rays: scripts/efficiency.sh's JSONL at two frame sizes ----------------------------------------------

def efficiency_runs(out):
    """{res: {scene: {latency: report}}}, scenes and latencies in run order."""
    runs = {}
    for path in need(out, "eff128.jsonl", "eff1024.jsonl"):
        for r in read_jsonl(path):
            with_scene(r, path)
            runs.setdefault(res_of(r), {}).setdefault(r["scene"], {})[r["memory"]["latency"]] = r
    return runs


def eff_cell(r, bold):
    """cycles per ray (efficiency; against the larger bound too where the memory's is the larger)."""
    e = pc(r["efficiency"])
    if r["memory_bound_cycles_per_ray"] > r["bound_cycles_per_ray"]:
        e += "; " + pc(r["efficiency_vs_both_bounds"])
    cell = "%.2f (%s)" % (r["cycles_per_ray"], e)
    return "**%s**" % cell if bold and r["efficiency_vs_both_bounds"] >= 0.9 else cell


def block_primary(out):
    runs = efficiency_runs(out)
    sizes = list(runs)
    lats = list(next(iter(runs[sizes[0]].values())))
    head = ["scene"]
    for res in sizes:
        head += ["bound, " + res, "latency %d" % lats[0]] + ["%d" % l for l in lats[1:]]
    lines = [para("`scripts/efficiency.sh build/bin/kdrt %s \"%s\" SCENES -- --model fast --timeout 50000000` and the "
                  "same at %s, SCENES the %s. Cycles per ray (efficiency against the per-core bound; where the memory "
                  "bound is the larger, also against that); bold: 90 %% or more of the larger bound."
                  % (sizes[0], " ".join(map(str, lats)), and_list(sizes[1:]), generators(runs[sizes[0]])[0]),
                  DOC_WIDTH), "",
             "| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    for scene in runs[sizes[0]]:
        row = [scene_name(scene)]
        for res in sizes:
            by_lat = runs[res].get(scene)
            if by_lat is None:
                raise BadInput("%s has no run at %s" % (scene, res))
            row.append("%.2f" % by_lat[lats[0]]["bound_cycles_per_ray"])
            row += [eff_cell(by_lat[l], True) for l in lats]
        lines.append("| " + " | ".join(row) + " |")
    # The points the per-core bound does not explain, and what holds them.
    low = [(scene, r) for scene, by_lat in runs[sizes[0]].items() for r in by_lat.values()
           if r["efficiency"] < 0.9]
    lines.append("")
    if not low:
        lines.append("Every point reaches 90 % of the per-core bound at %s." % sizes[0])
    else:
        groups = {}
        for scene, _ in low:
            m = re.fullmatch(r"(?:gen:)?(\w+):(\d+)", scene)
            key, size = (m.group(1), size_name(m.group(2))) if m else (scene, "")
            if size not in groups.setdefault(key, []):
                groups[key].append(size)
        names = ", ".join(k + (" " + (", ".join(v[:-1]) + " and " + v[-1] if len(v) > 1 else v[0]) if v[0] else "")
                          for k, v in groups.items())
        worst_scene, worst = min(low, key=lambda x: x[1]["efficiency"])
        mem_bound = all(r["memory_bound_cycles_per_ray"] > r["bound_cycles_per_ray"] for _, r in low)
        if mem_bound:
            text = ("The points below 90 %% of the per-core bound at %s (%s) are bound by the %g B/cycle port: %s reads "
                    "%.0f bytes a ray for %.1f triangle tests." % (
                        sizes[0], names, worst["memory"]["bytes_per_cycle_effective"], scene_name(worst_scene),
                        worst["memory"]["bytes_per_ray"], worst["reference_per_ray"]["tri_tests"]))
        else:
            text = ("The points below 90 %% of the per-core bound at %s: %s; the lowest, %s at latency %d (%s), reads "
                    "%.0f bytes a ray (memory bound %.2f cycles per ray) for %.1f triangle tests." % (
                        sizes[0], names, scene_name(worst_scene), worst["memory"]["latency"], pc(worst["efficiency"]),
                        worst["memory"]["bytes_per_ray"], worst["memory_bound_cycles_per_ray"],
                        worst["reference_per_ray"]["tri_tests"]))
        lines.append(para(text, DOC_WIDTH))
    return "\n".join(lines)


def block_readme_efficiency(out):
    """The middle size of the generators' (100k of 10k, 100k and 1M)."""
    runs = efficiency_runs(out)
    sizes = list(runs)
    lats = list(next(iter(runs[sizes[0]].values())))
    gens, tri_sizes = generators(runs[sizes[0]])
    size = sorted(tri_sizes)[len(tri_sizes) // 2]
    scenes = [s for s in runs[sizes[0]] if re.fullmatch(r"(?:gen:)?\w+:%d" % size, s)]
    head = ["scene"]
    for res in sizes:
        head += ["%s, latency %d" % (res, lats[0])] + ["latency %d" % l for l in lats[1:]]
    lines = [para("**Efficiency of the default core**, primary rays, fp32, at %s triangles (`scripts/efficiency.sh "
                  "build/bin/kdrt RES \"%s\" gen:NAME:%d -- --model fast`): cycles per ray (efficiency against the "
                  "per-core bound; where the memory bound is the larger, also against the larger of the two):"
                  % (size_name(size), " ".join(map(str, lats)), size), README_WIDTH), "",
             "| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    for scene in scenes:
        lines.append("| " + " | ".join([scene_name(scene)] + [eff_cell(runs[res][scene][l], False)
                                                             for res in sizes for l in lats]) + " |")
    every = [(scene, res, l, r) for res in sizes for scene, by_lat in runs[res].items() for l, r in by_lat.items()]
    n = len(runs[sizes[0]])
    below = [x for x in every if x[3]["efficiency_vs_both_bounds"] < 0.9]
    lowest = []
    for res in sizes:
        scene, _, l, r = min((x for x in every if x[1] == res), key=lambda x: x[3]["efficiency_vs_both_bounds"])
        lowest.append("%s at %s, latency %d, %s" % (scene_name(scene), res, l, pc(r["efficiency_vs_both_bounds"])))
    if not below:
        text = ("On all %d generator points (%s) the core reaches 90 %% of the larger bound at every latency and frame "
                "size (lowest: %s)." % (n, gens, "; ".join(lowest)))
    else:
        text = "%d of the %d runs (%s, every latency and frame size) stay below 90 %% of the larger bound: %s." % (
            len(below), len(every), gens, "; ".join("%s at %s, latency %d, %s" % (
                scene_name(sc), res, l, pc(r["efficiency_vs_both_bounds"])) for sc, res, l, r in below))
    lines += ["", para(text, README_WIDTH)]
    return "\n".join(lines)


# --- shaded frames: kdrt sim --shade --ao 2 --bounce, one JSON a generator ----------------------------------------

SHADE_SCENES = ["room", "balls", "rings", "tetra", "tree", "gears"]
PASSES = [("primary", "primary"), ("shadow", "shadow"), ("ao", "AO"), ("bounce", "bounce")]


def shaded_table(out):
    """(the command's scene and resolution, the table)."""
    paths = need(out, *["shade_%s.json" % s for s in SHADE_SCENES])
    lines = ["| scene | " + " | ".join(t for _, t in PASSES) + " | frame |", "|---|" + "---:|" * (len(PASSES) + 1)]
    args = None
    for path in paths:
        r = with_scene(read_json(path), path)
        if "passes" not in r or "frame" not in r:
            raise BadInput("%s: not a shaded frame's report" % path)
        m = re.fullmatch(r"(?:gen:)?\w+:(\d+)", r["scene"])
        args = "gen:NAME:%s --res %s" % (m.group(1) if m else "N", res_of(r))
        stats = {p["name"]: p["stats"] for p in r["passes"]}
        cells = []
        for name, _ in PASSES:
            st = stats.get(name)
            cells.append("–" if not st else eff_cell(st, False))
        f = r["frame"]
        cells.append("%.2f (%s)" % (f["cycles_per_ray"], pc(f["efficiency"])))
        lines.append("| %s | %s |" % (scene_name(r["scene"]), " | ".join(cells)))
    return args, "\n".join(lines)


def block_shaded(out):
    args, table = shaded_table(out)
    return para("`kdrt sim %s --shade --ao 2 --bounce --model fast`: cycles per ray (efficiency against the per-core "
                "bound; where the memory bound is the larger, also against that) per pass." % args,
                DOC_WIDTH) + "\n\n" + table


def block_readme_shaded(out):
    args, table = shaded_table(out)
    return para("**Shaded frames** (`kdrt sim %s --shade --ao 2 --bounce --model fast`), cycles per ray (efficiency "
                "against the per-core bound; where the memory bound is the larger, also against that) per pass:"
                % args, README_WIDTH) + "\n\n" + table


# --- the simulators' speed: three RTL runs and the fast-versus-RTL sweeps -----------------------------------------

SPEED_SWEEPS = ["sweep-fast-generators", "sweep-fast-generators-128", "sweep-fast-vs-rtl", "sweep-fast-cores"]


def rtl_speed(out):
    """(cycles per second, rays per second, runs, the runs' kdrt sim arguments)."""
    paths = need(out, "speed1.json", "speed2.json", "speed3.json")
    runs = [read_json(p) for p in paths]
    for p, r in zip(paths, runs):
        if r.get("cycle_model", "fast") != "rtl":
            raise BadInput("%s: not an RTL run (cycle_model %s)" % (p, r.get("cycle_model", "fast")))
    cps = [r["sim_cycles_per_second"] / 1000 for r in runs]
    rps = statistics.mean(r["sim_rays_per_second"] for r in runs)
    scene = runs[0]["scene"]
    args = "%s%s --res %s" % ("" if scene.startswith("gen:") or ":" not in scene else "gen:", scene, res_of(runs[0]))
    return span(min(cps), max(cps), "%.1f") + "k", rps, len(runs), args


def sweep_speed(out, spec):
    rows = read_csv(need(out, spec + "/sweep.csv")[0])
    ups = [float(r["fast_speedup"]) for r in rows if r.get("fast_speedup")]
    if len(ups) != len(rows):
        raise BadInput("%s/sweep.csv: points without the fast model's speed-up (not model: both)" % spec)
    differ = sum(1 for r in rows if float(r["fast_error"] or 0) != 0)
    return {"n": len(rows), "range": span(min(ups), max(ups), "%.0f") + "x", "median": speedups(statistics.median(ups)),
            "res": rows[0]["res"], "differ": differ}


def exact(s):
    return "every point cycle-exact" if s["differ"] == 0 else "%d of %d points NOT cycle-exact" % (s["differ"], s["n"])


def block_speed(out):
    cps, _, runs, args = rtl_speed(out)
    s = [sweep_speed(out, spec) for spec in SPEED_SWEEPS]
    others = sum(x["differ"] for x in s[1:])
    rtl = "- RTL: %s cycles per second on one host thread (`kdrt sim %s`, %s runs)." % (
        cps, args, WORDS.get(runs, str(runs)))
    fast = ("- The fast model against the RTL, %d generator x format points at %s (`kdrt sweep docs/%s.yaml --jobs 1`): "
            "%s, median %s, %s; at %s (`docs/%s.yaml`) %s (median %s); the %d-point sweep (`docs/%s.yaml`) %s "
            "(median %s); several cores (`docs/%s.yaml`) %s (median %s)%s." % (
                s[0]["n"], s[0]["res"], SPEED_SWEEPS[0], s[0]["range"], s[0]["median"], exact(s[0]), s[1]["res"],
                SPEED_SWEEPS[1], s[1]["range"], s[1]["median"], s[2]["n"], SPEED_SWEEPS[2], s[2]["range"],
                s[2]["median"], SPEED_SWEEPS[3], s[3]["range"], s[3]["median"],
                "" if not others else "; %d points of these three sweeps NOT cycle-exact" % others))
    return para(rtl, DOC_WIDTH, "  ") + "\n" + para(fast, DOC_WIDTH, "  ")


def block_readme_speed(out):
    cps, rps, _, args = rtl_speed(out)
    s = sweep_speed(out, SPEED_SWEEPS[0])
    same = "cycle for cycle the same" if s["differ"] == 0 else "NOT cycle-exact on %d points" % s["differ"]
    return para("**Simulation speed**: the Verilated default core runs %s cycles per second on one host thread (`kdrt "
                "sim %s`, about %d rays/s); the fast model runs %s faster on the %d generator x format points at %s "
                "(median %s, `kdrt sweep docs/%s.yaml --jobs 1`), %s." % (
                    cps, args, round(rps, -1), s["range"], s["n"], s["res"], s["median"], SPEED_SWEEPS[0], same),
                README_WIDTH)


# --- several cores: scripts/scaling.sh's CSV and table ------------------------------------------------------------

def scaling(out):
    rows = read_csv(need(out, "scaling.csv")[0])
    series = {}
    for r in rows:
        series.setdefault(r["scene"], {}).setdefault(int(r["bytes_per_cycle"]), []).append(r)
    for by_bw in series.values():
        for pts in by_bw.values():
            base = float(pts[0]["rays_per_cycle"])
            for p in pts:
                p["speedup"] = float(p["rays_per_cycle"]) / base
                p["cores"] = int(p["cores"])
    return series


def plateau(pts, bw):
    """The points the memory holds: 90 % or more of the bandwidth used."""
    return [p for p in pts if float(p["mem_bytes_per_cycle_used"]) >= 0.9 * bw]


def block_cores(out):
    series = scaling(out)
    scale, fill = [], []
    bws = sorted({bw for by_bw in series.values() for bw in by_bw}, reverse=True)
    top = bws[0]
    for scene, by_bw in series.items():
        pts = by_bw[top]
        if plateau(pts[:1], top):
            fill.append("%s fills %.1f of %d B/cycle on one core"
                        % (scene_name(scene), float(pts[0]["mem_bytes_per_cycle_used"]), top))
            continue
        mid = [p for p in pts if p["cores"] <= 8][-1]
        last = pts[-1]
        text = "%s %.2fx at %d%s" % (scene_name(scene), mid["speedup"], mid["cores"], "" if scale else " cores")
        if last["cores"] > mid["cores"] and last["speedup"] > 1.1 * mid["speedup"]:
            text += " and %.1fx at %d (%.0f %% per core)" % (last["speedup"], last["cores"],
                                                            100 * last["speedup"] / last["cores"])
        scale.append(text)
    low = []
    for bw in bws[1:]:
        held = []
        for scene, by_bw in series.items():
            if plateau(by_bw[top][:1], top):
                continue
            p = plateau(by_bw[bw], bw)
            if p:
                name = scene_name(scene).split()[0]
                held.append("%s%s at %s" % (name + " stops" if not held else name, "",
                                            span(min(x["speedup"] for x in p), max(x["speedup"] for x in p), "%.1f")
                                            + "x"))
        if held:
            low.append("at %d B/cycle %s" % (bw, ", ".join(held)))
    table = read_text(need(out, "scaling.md")[0])
    first = next(iter(series.values()))[top]
    res = first[0].get("res") or "128x128"  # a CSV without the column: remeasure.sh's resolution
    return para("`scripts/scaling.sh build/bin/kdrt %s \"%s\" \"%s\" OUT %s -- --model fast`: %s ([scaling.svg]"
                "(scaling.svg), [scaling.csv](scaling.csv))." % (
                    res, " ".join(str(p["cores"]) for p in first), " ".join(map(str, bws)), " ".join(series),
                    "; ".join([", ".join(scale)] + fill + low)), DOC_WIDTH) + "\n\n" + table


def block_readme_cores(out):
    series = scaling(out)
    bws = sorted({bw for by_bw in series.values() for bw in by_bw}, reverse=True)
    scene, by_bw = next(iter(series.items()))
    pts = by_bw[bws[0]]
    mid = [p for p in pts if p["cores"] <= 8][-1]
    text = "**Several cores** behind a shared L2 (`scripts/scaling.sh`): %s %.2fx at %d cores" % (
        scene_name(scene), mid["speedup"], mid["cores"])
    if pts[-1]["cores"] > mid["cores"]:
        text += " and %.1fx at %d" % (pts[-1]["speedup"], pts[-1]["cores"])
    if len(bws) > 1:
        p = plateau(by_bw[bws[-1]], bws[-1])
        if p:
            text += "; at %d B/cycle of memory %s stops at %sx" % (
                bws[-1], scene_name(scene).split()[0],
                span(min(x["speedup"] for x in p), max(x["speedup"] for x in p), "%.1f"))
    return para(text + " ([docs/scaling.svg](docs/scaling.svg)).", README_WIDTH)


# --- the steps whose output is a table already --------------------------------------------------------------------

def block_packed(name, options, says):
    """scripts/packed-images.sh's table as it wrote it, under the command with the scenes the table has."""
    def render(out):
        table = read_text(need(out, name)[0])
        scenes = []
        for line in table.splitlines()[2:]:
            cells = [c.strip() for c in line.strip("|").split("|")]
            if len(cells) < 2 or not cells[0]:
                raise BadInput("%s: not a packed-images.sh table row: %s" % (name, line))
            scenes += [cells[0]] if cells[0] not in scenes else []
        if not scenes:
            raise BadInput("%s: a table without rows" % name)
        return para("`scripts/packed-images.sh build/bin/kdrt 128x128 %s -- %s`: %s" % (" ".join(scenes), options, says),
                    DOC_WIDTH) + "\n\n" + table
    return render


BLOCKS = {
    "primary": block_primary,
    "shaded": block_shaded,
    "speed": block_speed,
    "cores": block_cores,
    "packed": block_packed("packed.md", "--model fast", "each format traverses in itself."),
    "wider": block_packed("travfmt.md", "--model fast --trav-format fp32 --stack-depth 32 --node-idx-width 24 "
                          "--tri-idx-width 24 --addr-width 28", "every format traverses in fp32."),
    "readme-efficiency": block_readme_efficiency,
    "readme-shaded": block_readme_shaded,
    "readme-speed": block_readme_speed,
    "readme-cores": block_readme_cores,
}

MARK = re.compile(r"<!-- results:([\w-]+) begin -->\n(.*?)<!-- results:\1 end -->", re.S)


def fill(path, out, kept):
    with open(path) as f:
        text = f.read()
    names = [m.group(1) for m in MARK.finditer(text)]
    opened = re.findall(r"<!-- results:([\w-]+) begin -->", text)
    if sorted(names) != sorted(opened):
        raise BadInput("%s: a results block without its end marker: %s" % (
            path, ", ".join(sorted(set(opened) - set(names)))))
    unknown = [n for n in names if n not in BLOCKS]
    if unknown:
        raise BadInput("%s: unknown results blocks: %s (known: %s)" % (path, ", ".join(unknown), ", ".join(BLOCKS)))

    def replace(m):
        try:
            body = BLOCKS[m.group(1)](out).rstrip("\n") + "\n"
        except Missing as e:
            kept.append("%s: %s (%s)" % (os.path.basename(path), m.group(1), e))
            return m.group(0)
        except (KeyError, IndexError, TypeError, ValueError) as e:
            raise BadInput("%s, block %s: the step outputs lack %r" % (path, m.group(1), e))
        return "<!-- results:%s begin -->\n%s<!-- results:%s end -->" % (m.group(1), body, m.group(1))

    return text, MARK.sub(replace, text), names


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    args, results, readme, check = [], os.path.join(root, "docs", "results.md"), os.path.join(root, "README.md"), False
    it = iter(argv)
    for a in it:
        if a in ("-h", "--help"):
            print(__doc__.strip())
            return 0
        if a in ("--results", "--readme"):
            v = next(it, None)
            if v is None:
                print("results_md: %s needs a file" % a, file=sys.stderr)
                return 2
            results, readme = (v, readme) if a == "--results" else (results, v)
        elif a == "--check":
            check = True
        elif a.startswith("-"):
            print("results_md: unknown option %s (see --help)" % a, file=sys.stderr)
            return 2
        else:
            args.append(a)
    if len(args) != 1:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out = args[0]
    if not os.path.isdir(out):
        print("results_md: %s: no such directory" % out, file=sys.stderr)
        return 1
    kept, updates = [], []
    try:
        for path in (results, readme):
            old, new, names = fill(path, out, kept)
            if not names:
                raise BadInput("%s: no <!-- results:NAME begin --> blocks" % path)
            updates.append((path, old, new))
    except (BadInput, OSError) as e:
        print("results_md: error: %s" % e, file=sys.stderr)
        return 1
    for k in kept:
        print("results_md: kept as it was: %s" % k, file=sys.stderr)
    changed = [p for p, old, new in updates if old != new]
    if check:
        for p in changed:
            print("results_md: %s would change" % p, file=sys.stderr)
        return 1 if changed else 0
    # Every file written whole: a temporary file, then rename.
    for path, old, new in updates:
        if old != new:
            with open(path + ".tmp", "w") as f:
                f.write(new)
            os.replace(path + ".tmp", path)
    for ext in ("svg", "csv"):
        src = os.path.join(out, "scaling." + ext)
        if os.path.exists(src):
            shutil.copyfile(src, os.path.join(os.path.dirname(os.path.abspath(results)), "scaling." + ext))
    print("results_md: %s" % ("; ".join("%s %s" % (p, "rewritten" if p in changed else "unchanged")
                                        for p, _, _ in updates)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
