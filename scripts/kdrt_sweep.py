#!/usr/bin/python3
"""kdrt sweep: design-space sweeps of `kdrt sim` (docs/sweep.md).

Started by `kdrt sweep SPEC` (which passes --kdrt, its own path). A sweep is
scenes x formats x model parameters x model, from a YAML spec; each point is
one `kdrt sim ... --json` run. Points run on a local pool of processes, or
with --scheduler tcp://HOST:PORT as tasks on an existing Dask distributed
cluster (each task runs the kdrt binary and returns its JSON; the workers
must see the same file system). Results: OUT/points/<id>.json per point
(points already there are not run again), OUT/sweep.csv, OUT/sweep.json and
OUT/plots/<scene>_<parameter>.svg. RTL models that the points need are built
once, before any point is dispatched.
"""

import argparse
import concurrent.futures
import csv
import hashlib
import itertools
import json
import os
import re
import subprocess
import sys
import time

# Spec parameter -> kdrt sim option. The order is the CSV's column order.
PARAMS = {
    "threads": "--threads",
    "stack_depth": "--stack-depth",
    "node_cache_lines": "--node-cache-lines",
    "list_cache_lines": "--list-cache-lines",
    "tri_cache_lines": "--tri-cache-lines",
    "cache_mshrs": "--cache-mshrs",
    "cache_targets": "--cache-targets",
    "cache_ways": "--cache-ways",
    "mem_latency": "--mem-latency",
    "mem_bw": "--mem-bw",
    "cores": "--cores",
    "l2_kb": "--l2-kb",
    "trav_format": "--trav-format",
    "image_format": "--image-format",
    "min_split_gain": "--min-split-gain",
    "ray_order": "--ray-order",
    "list_stream": "--list-stream",
}
SPEC_KEYS = {"scenes", "formats", "res", "params", "model", "shade", "allow_overflow"}
# What each point reports, from `kdrt sim --json`.
RESULTS = ["rays", "cycles", "cycles_per_ray", "bound_cycles_per_ray", "efficiency", "window_bound_cycles_per_ray",
           "rays_per_cycle", "overflows",
           "bytes_per_ray", "node_hit_rate", "tri_hit_rate", "sim_seconds",
           "fast_cycles_per_ray", "fast_error", "fast_speedup"]  # the last three: model both


class SpecError(Exception):
    pass


def fail(msg):
    print("kdrt sweep: error: " + msg, file=sys.stderr)
    sys.exit(1)


def as_list(value, what, path):
    values = value if isinstance(value, list) else [value]
    if not values:
        raise SpecError("%s: '%s' is an empty list" % (path, what))
    for v in values:
        if isinstance(v, (dict, list)) or v is None:
            raise SpecError("%s: '%s' must be a value or a list of values, got %r" % (path, what, v))
    return values


def load_spec(path):
    import yaml  # Debian: python3-yaml

    try:
        with open(path) as f:
            spec = yaml.safe_load(f)
    except OSError as e:
        raise SpecError("%s: cannot read: %s" % (path, e.strerror))
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = "%s:%d" % (path, mark.line + 1) if mark else path
        raise SpecError("%s: not valid YAML: %s" % (where, getattr(e, "problem", e)))
    if not isinstance(spec, dict):
        raise SpecError("%s: expected a mapping with scenes, formats, params" % path)
    unknown = set(spec) - SPEC_KEYS
    if unknown:
        raise SpecError("%s: unknown key '%s' (known: %s)" % (path, sorted(unknown)[0], ", ".join(sorted(SPEC_KEYS))))
    if "scenes" not in spec:
        raise SpecError("%s: 'scenes' is required" % path)
    params = spec.get("params") or {}
    if not isinstance(params, dict):
        raise SpecError("%s: 'params' must map parameter names to lists" % path)
    for name in params:
        if name not in PARAMS:
            raise SpecError("%s: unknown parameter '%s' (known: %s)" % (path, name, ", ".join(PARAMS)))
    models = as_list(spec.get("model", "rtl"), "model", path)
    for m in models:
        if m not in ("rtl", "fast", "both"):
            raise SpecError("%s: model '%s': expected rtl, fast or both" % (path, m))
    return {
        "scenes": [str(s) for s in as_list(spec["scenes"], "scenes", path)],
        "formats": [str(f) for f in as_list(spec.get("formats", "fp32"), "formats", path)],
        "res": str(spec.get("res", "64x64")),
        "params": {k: as_list(v, "params." + k, path) for k, v in params.items()},
        "models": models,
        "shade": bool(spec.get("shade", False)),
        "allow_overflow": bool(spec.get("allow_overflow", False)),
    }


def expand(spec):
    names = [p for p in PARAMS if p in spec["params"]]
    points = []
    for scene, fmt, model, values in itertools.product(spec["scenes"], spec["formats"], spec["models"],
                                                       itertools.product(*[spec["params"][n] for n in names])):
        p = {"scene": scene, "format": fmt, "model": model, "res": spec["res"], "shade": spec["shade"]}
        if spec["allow_overflow"]:  # only then part of the id: earlier sweeps keep theirs
            p["allow_overflow"] = True
        p.update(dict(zip(names, values)))
        key = json.dumps(p, sort_keys=True)
        p["id"] = hashlib.sha1(key.encode()).hexdigest()[:16]
        points.append(p)
    return names, points


def sim_args(point):
    a = ["sim", point["scene"], "--res", point["res"], "--format", point["format"], "--model", point["model"], "-q"]
    for name, flag in PARAMS.items():
        if name in point:
            a += [flag, str(point[name])]
    if point["shade"]:
        a.append("--shade")
    if point.get("allow_overflow"):
        a.append("--allow-overflow")
    return a


def run_point(kdrt, args, workdir):
    """One point: runs kdrt sim; returns (exit code, JSON text, stderr, where it ran). On a Dask worker or
    locally."""
    import os as _os
    import subprocess as _sp
    import tempfile as _tf

    where = "local"
    try:
        from distributed import get_worker

        where = str(get_worker().name)
    except (ImportError, ValueError):
        pass
    with _tf.TemporaryDirectory(dir=workdir) as tmp:
        out = _os.path.join(tmp, "point.json")
        img = _os.path.join(tmp, "point.png")
        r = _sp.run([kdrt] + args + ["-o", img, "--json", out], capture_output=True, text=True)
        text = open(out).read() if r.returncode == 0 and _os.path.exists(out) else ""
        return r.returncode, text, r.stderr[-4000:], where


def build_models(kdrt, points):
    """Builds every RTL model the points need, once each, before dispatch."""
    seen = {}
    for p in points:
        if p["model"] == "fast":
            continue
        r = subprocess.run([kdrt] + sim_args(p) + ["--which-model"], capture_output=True, text=True)
        if r.returncode != 0:
            fail("point %s (%s): %s" % (p["id"], " ".join(sim_args(p)), r.stderr.strip()))
        model = exe = ""
        for line in r.stdout.splitlines():
            if line.startswith("model"):
                model = line.split()[1]
            if line.startswith("executable"):
                exe = line
        if model not in seen:
            seen[model] = (p, "(built)" not in exe)
    todo = [(m, p) for m, (p, need) in seen.items() if need]
    print("kdrt sweep: %d model(s), %d to build" % (len(seen), len(todo)), file=sys.stderr)
    for model, p in todo:
        print("kdrt sweep: building %s" % model, file=sys.stderr)
        r = subprocess.run([kdrt] + sim_args(p) + ["--build-model"], capture_output=True, text=True)
        if r.returncode != 0:
            fail("building %s: %s" % (model, r.stderr.strip()))


def row_of(point, names, report):
    mem = report.get("memory", {})
    hit = report.get("cache_hit_rate", {})
    frame = report.get("frame")  # shaded frames: the frame's totals
    row = {"id": point["id"], "scene": point["scene"], "format": point["format"], "model": point["model"],
           "res": point["res"]}
    row.update({n: point[n] for n in names})
    row.update({
        "rays": frame["rays"] if frame else report["rays"],
        "cycles": frame["cycles"] if frame else report["cycles"],
        "cycles_per_ray": frame["cycles_per_ray"] if frame else report["cycles_per_ray"],
        "bound_cycles_per_ray": frame["bound_cycles_per_ray"] if frame else report["bound_cycles_per_ray"],
        "efficiency": frame["efficiency"] if frame else report["efficiency"],
        # The bound of the rays in flight (kdrt sim's window bound; not summed over a shaded frame's passes).
        "window_bound_cycles_per_ray": None if frame else report.get("window_bound", {}).get("cycles_per_ray"),
        "rays_per_cycle": report["rays_per_cycle"],
        "overflows": report.get("overflows", 0),
        "bytes_per_ray": mem.get("bytes_per_ray"),
        "node_hit_rate": hit.get("node"),
        "tri_hit_rate": hit.get("tri"),
        "sim_seconds": report.get("sim_seconds"),
        "fast_cycles_per_ray": report.get("fast", {}).get("cycles_per_ray"),
        "fast_error": report.get("fast", {}).get("error"),
        "fast_speedup": report.get("fast", {}).get("speedup"),
    })
    return row


def value_key(v):
    """Numbers in numeric order, before other values; those in natural order (morton:2 before morton:16)."""
    try:
        return (0, float(v), [])
    except (TypeError, ValueError):
        parts = re.split(r"(\d+)", str(v))
        return (1, 0.0, [(0, int(p), "") if p.isdigit() else (1, 0, p) for p in parts])


def plot(path, title, xs_label, series, y_label="cycles per ray"):
    """A plain SVG line plot: series = [(label, [(x, y), ...])], in legend order; x values are categories,
    equally spaced in value_key order (scripts/scaling.sh uses it too)."""
    W, H, L, R, T, B = 560, 340, 60, 170, 30, 45
    xs = sorted({x for _, pts in series for x, _ in pts}, key=value_key)
    ys = [y for _, pts in series for _, y in pts]
    ymax = max(ys) * 1.1 if ys and max(ys) > 0 else 1.0
    xi = {x: i for i, x in enumerate(xs)}  # categorical x: parameter values in order
    lx = lambda x: L + (W - L - R) * (xi[x] + 0.5) / len(xs)
    ly = lambda y: H - B - (H - T - B) * y / ymax
    colors = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"]
    o = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" '
         'font-size="12">' % (W, H), '<rect width="100%" height="100%" fill="white"/>',
         '<text x="%d" y="18" font-weight="bold">%s</text>' % (L, title),
         '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - R, H - B),
         '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, T, L, H - B)]
    for x in xs:
        o.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (lx(x), H - B + 16, x))
    for k in range(6):
        y = ymax * k / 5
        o.append('<text x="%d" y="%.1f" text-anchor="end">%.3g</text>' % (L - 6, ly(y) + 4, y))
        o.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (L, ly(y), W - R, ly(y)))
    o.append('<text x="%d" y="%d" text-anchor="middle">%s</text>' % ((L + W - R) / 2, H - 10, xs_label))
    o.append('<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">%s</text>' %
             ((T + H - B) / 2, (T + H - B) / 2, y_label))
    for i, (label, pts) in enumerate(series):
        c = colors[i % len(colors)]
        pts = sorted(pts, key=lambda p: xi[p[0]])
        o.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' %
                 (c, " ".join("%.1f,%.1f" % (lx(x), ly(y)) for x, y in pts)))
        for x, y in pts:
            o.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (lx(x), ly(y), c))
        o.append('<text x="%d" y="%d" fill="%s">%s</text>' % (W - R + 10, T + 16 * (i + 1), c, label))
    o.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(o) + "\n")


def write_outputs(out, names, points, rows):
    """sweep.csv, sweep.json and the plots, each written whole (temporary file, then rename)."""
    cols = ["id", "scene", "format", "model", "res"] + names + RESULTS
    tmp = os.path.join(out, ".sweep.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k) for k in cols})
    os.replace(tmp, os.path.join(out, "sweep.csv"))
    tmp = os.path.join(out, ".sweep.json.tmp")
    with open(tmp, "w") as f:
        json.dump({"parameters": names, "points": rows}, f, indent=1)
    os.replace(tmp, os.path.join(out, "sweep.json"))
    os.makedirs(os.path.join(out, "plots"), exist_ok=True)
    made = 0
    for scene in sorted({r["scene"] for r in rows}):
        mine = [r for r in rows if r["scene"] == scene]
        varying = [n for n in names + ["format", "model"] if len({str(r[n]) for r in mine}) > 1]
        for name in varying:
            # One line per combination of the other columns that vary.
            others = [n for n in varying if n != name]
            lines = {}
            for r in mine:
                key = tuple(r[n] for n in others)
                lines.setdefault(key, []).append((str(r[name]), float(r["cycles_per_ray"])))
            series = [(", ".join("%s %s" % (n, v) for n, v in zip(others, key)) or scene, lines[key])
                      for key in sorted(lines, key=lambda k: [value_key(v) for v in k])]
            safe = scene.replace(":", "_").replace("/", "_")
            plot(os.path.join(out, "plots", "%s_%s.svg" % (safe, name)), "%s: cycles per ray" % scene, name, series)
            made += 1
    return made


def main():
    ap = argparse.ArgumentParser(prog="kdrt sweep", description=__doc__.split("\n\n")[0])
    ap.add_argument("spec", help="sweep specification (YAML)")
    ap.add_argument("-o", "--out", help="output directory (default: <spec name>.sweep)")
    ap.add_argument("--scheduler", help="run the points on this Dask cluster (tcp://HOST:PORT)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="local processes (default: cores)")
    ap.add_argument("--kdrt", required=True, help=argparse.SUPPRESS)
    a = ap.parse_args()
    try:
        spec = load_spec(a.spec)
    except SpecError as e:
        fail(str(e))
    if a.jobs < 1:
        fail("--jobs must be at least 1")
    out = a.out or os.path.splitext(a.spec)[0] + ".sweep"
    os.makedirs(os.path.join(out, "points"), exist_ok=True)
    names, points = expand(spec)
    kdrt = os.path.abspath(a.kdrt)

    done = {p["id"] for p in points if os.path.exists(os.path.join(out, "points", p["id"] + ".json"))}
    todo = [p for p in points if p["id"] not in done]
    print("kdrt sweep: %d points, %d done already, %d to run (%s)" %
          (len(points), len(done), len(todo), a.scheduler or "%d local processes" % a.jobs), file=sys.stderr)
    if todo:
        build_models(kdrt, todo)
    workdir = os.path.abspath(out)

    failures = []

    def finish(p, result):
        code, text, err, where = result
        if code != 0:
            failures.append((p, code, err))
            print("kdrt sweep: point %s failed (exit %d): %s" % (p["id"], code, err.strip()[-500:]), file=sys.stderr)
            return
        path = os.path.join(out, "points", p["id"] + ".json")
        with open(path + ".tmp", "w") as f:
            json.dump({"point": p, "ran_on": where, "report": json.loads(text)}, f)
        os.replace(path + ".tmp", path)

    start = time.time()
    if todo and a.scheduler:
        try:
            from distributed import Client, as_completed  # Debian: python3-distributed
        except ImportError:
            fail("--scheduler needs Dask distributed (apt install python3-distributed)")
        try:
            client = Client(a.scheduler, timeout=20)
        except Exception as e:  # noqa: BLE001 - any connection failure is the user's to see
            fail("cannot reach the Dask scheduler at %s: %s" % (a.scheduler, e))
        futures = {client.submit(run_point, kdrt, sim_args(p), workdir, pure=False, key="kdrt-" + p["id"]): p
                   for p in todo}
        for k, fut in enumerate(as_completed(futures), 1):
            finish(futures[fut], fut.result())
            print("kdrt sweep: %d/%d points (%.0f s)" % (k, len(todo), time.time() - start), file=sys.stderr)
        client.close()
    elif todo:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = {pool.submit(run_point, kdrt, sim_args(p), workdir): p for p in todo}
            for k, fut in enumerate(concurrent.futures.as_completed(futures), 1):
                finish(futures[fut], fut.result())
                print("kdrt sweep: %d/%d points (%.0f s)" % (k, len(todo), time.time() - start), file=sys.stderr)

    rows = []
    for p in points:
        path = os.path.join(out, "points", p["id"] + ".json")
        if os.path.exists(path):
            with open(path) as f:
                rows.append(row_of(p, names, json.load(f)["report"]))
    plots = write_outputs(out, names, points, rows)
    print("kdrt sweep: %d of %d points in %s/sweep.csv, sweep.json; %d plots in %s/plots" %
          (len(rows), len(points), out, plots, out))
    if failures:
        print("kdrt sweep: %d points failed; run the sweep again to retry them" % len(failures), file=sys.stderr)
        sys.exit(3)


if __name__ == "__main__":
    main()
