#!/usr/bin/env python3
"""Physical cost of one rt_core configuration on the OSU 0.18 um library.

Yosys elaborates rt_core with the given parameters and lists the units it
instantiates with their parameters (rt_core derives them: the script does not
repeat that). Each distinct unit (module and parameters) is synthesized once
by scripts/synth-phys.sh (identical instances are counted), rt_mem_system and
rt_leaf_exit with --sram (the caches' line arrays and the stacks' memory are
SRAM macros, area and access time from scripts/sram_model.txt), and rt_core's own logic (thread table, ...) with its
units cut out as unit "rt_core" (--glue). A unit that fails or exceeds the
memory or time cap is estimated: synthesized at two smaller sizes (Threads,
Jobs, N or CacheMshrs divided by 8 and 16, then 16 and 32, ...) and extrapolated,
linearly in the size for area, cells and flip-flops and linearly in its log2
for the critical path; stderr, the unit ("estimated", "method") and "notes"
say so.

Results are cached under DIR/units, one JSON per unit, module, parameters,
period, RTL, library and flow: a second run of the same configuration only
reads them. Every file is written beside its name and renamed, so an
interrupted run leaves no half-written entry. Writes DIR/core.json:
  {"library", "period_target_ns", "scope": "per_unit", "params",
   "clock_ns", "critical_unit", "area_um2": {"logic", "sram", "total"},
   "units": [{"unit", "instances", "count", "params", "area_um2", "cells",
              "flip_flops", "crit_ns", "crit_path", "srams", "estimated",
              ["method"]}], "notes"}
area_um2 of a unit is one instance's logic; the core's sums are over units
times count. clock_ns is the largest crit_ns of a unit or access_ns of an SRAM
macro; crit_ns has ideal ports and no wires (scripts/synth-phys.sh).
On failure (a unit neither synthesized nor estimated, a tool missing): exit
status 1, the reason on stderr, no DIR/core.json."""
import argparse
import concurrent.futures as cf
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import sram_model  # noqa: E402

RTL = os.path.join(ROOT, "rtl")
SYNTH_PHYS = os.path.join(ROOT, "scripts", "synth-phys.sh")
DEFAULT_LIB = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib"
# Changes when scripts/synth-phys.sh's flow gives other numbers for the same
# RTL (part of every cache key).
FLOW_VERSION = "2"
# Units whose memories are SRAM macros: the caches' line arrays (as in
# scripts/synth.sh), the memories of rt_ram_1r1w: the stacks' (in
# rt_leaf_exit, 360,448 bits in the default core, far beyond what flip-flops
# can hold), the miss registers' line buffers and requests (in rt_cache) and
# the thread table's ray and ray-id memories (instances of rt_core's own),
# the hit records' u, v (in rt_hit_merge) and the leaf-job queue and its
# prefetcher's copy (in rt_list_unit).
SRAM_UNITS = {"rt_mem_system", "rt_cache", "rt_leaf_exit", "rt_thread_stack", "rt_ram_1r1w", "rt_hit_merge",
              "rt_list_unit", "rt_fifo"}
# The size parameters an estimate scales, in this order of preference.
SCALE_PARAMS = ("Threads", "Jobs", "N", "CacheMshrs")

RUNNING = set()  # Popen objects of running syntheses (killed on interrupt)
RUNNING_LOCK = threading.Lock()
STOP = threading.Event()


def log(msg):
    print(f"synth-core: {msg}", file=sys.stderr, flush=True)


def die(msg):
    log(msg)
    sys.exit(1)


def atomic_write(path, text):
    """Writes TEXT to PATH through a file beside it, then renames it."""
    d = os.path.dirname(path)
    fd, tmp = tempfile.mkstemp(prefix=os.path.basename(path) + ".tmp.", dir=d)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def sha(text):
    return hashlib.sha1(text.encode()).hexdigest()


def sources_hash():
    """FNV-1a (64 bits) of rtl/*.sv in name order and scripts/sram_model.txt,
    each as its name, a 0 byte, its bytes and a 0 byte: what core.json was
    made from. kdrt sim (sim/phys.cpp SourcesHash) computes the same and
    reports no physical figures when it differs."""
    paths = [os.path.join(RTL, f) for f in sorted(os.listdir(RTL)) if f.endswith(".sv")]
    paths.append(sram_model.COEFFS)
    h = 0xCBF29CE484222325
    for p in paths:
        with open(p, "rb") as f:
            data = os.path.basename(p).encode() + b"\0" + f.read() + b"\0"
        for b in data:
            h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def file_hash(paths):
    h = hashlib.sha1()
    for p in paths:
        with open(p, "rb") as f:
            h.update(f.read())
    return h.hexdigest()


def unit_rtl_files(unit, rtl_files):
    """The RTL files UNIT's synthesis reads: its own module's file, those of
    the modules it instantiates (transitively) and the packages, so that a
    change to one unit's RTL synthesizes that unit and its users again, not
    every unit. rt_core's own logic (--glue) reads every unit's ports: all."""
    by_module = {os.path.basename(f)[:-3]: f for f in rtl_files}
    if unit not in by_module or unit == "rt_core":
        return rtl_files
    seen, todo = {unit}, [unit]
    while todo:
        text = open(by_module[todo.pop()]).read()
        for m in re.finditer(r"^\s*(\w+)\s*(?:#|\w+\s*\()", text, re.M):
            name = m.group(1)
            if name in by_module and name not in seen:
                seen.add(name)
                todo.append(name)
    return sorted(f for f in rtl_files if f.endswith("_pkg.sv") or os.path.basename(f)[:-3] in seen)


def core_param_defaults():
    """rt_core's parameters and their defaults (None when not a number)."""
    text = open(os.path.join(RTL, "rt_core.sv")).read()
    start = text.index("module rt_core")
    header = text[start:start + re.search(r"^\)\s*\(", text[start:], re.M).start()]
    out = {}
    for m in re.finditer(r"^\s*parameter\s+int\s+unsigned\s+(\w+)[^=]*=\s*([^,\n]+)", header, re.M):
        v = m.group(2).strip()
        out[m.group(1)] = int(v) if v.isdigit() else None
    return out


def run_tool(cmd, log_path, timeout_s):
    """Runs CMD in its own process group with output to LOG_PATH. Returns
    (exit status, seconds); status None when the time cap ended it."""
    start = time.time()
    with open(log_path, "w") as logf:
        p = subprocess.Popen(cmd, stdout=logf, stderr=subprocess.STDOUT, start_new_session=True)
        with RUNNING_LOCK:
            RUNNING.add(p)
        try:
            rc = p.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            kill_group(p)
            rc = None
        finally:
            with RUNNING_LOCK:
                RUNNING.discard(p)
    return rc, time.time() - start


def kill_group(p):
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(p.pid, sig)
        except ProcessLookupError:
            return
        try:
            p.wait(timeout=10)
            return
        except subprocess.TimeoutExpired:
            pass


class Flow:
    def __init__(self, args):
        self.args = args
        self.out = args.out
        self.units_dir = os.path.join(args.out, "units")
        self.logs_dir = os.path.join(args.out, "logs")
        os.makedirs(self.units_dir, exist_ok=True)
        os.makedirs(self.logs_dir, exist_ok=True)
        self.lib = os.environ.get("LIBERTY", DEFAULT_LIB)
        rtl_files = sorted(os.path.join(RTL, f) for f in os.listdir(RTL) if f.endswith(".sv"))
        self.rtl_files = rtl_files
        self.rtl_hash = file_hash(rtl_files)
        self.unit_hashes = {}
        self.lib_hash = file_hash([self.lib])
        # The macros' access times are input delays of the units that hold
        # them (and of rt_core's own logic at its memories' outputs).
        self.model_hash = file_hash([sram_model.COEFFS])
        self.glue_delays = []  # ["<instance>.rdata_o=<ns>"] for rt_core's own logic
        self.mem_bytes = int(args.mem_gb * 1e9)
        self.timeout_s = args.time_min * 60

    def unit_hash(self, unit):
        if unit not in self.unit_hashes:
            self.unit_hashes[unit] = file_hash(unit_rtl_files(unit, self.rtl_files))
        return self.unit_hashes[unit]

    def key(self, unit, params, glue, sram):
        p = " ".join(f"{k}={v}" for k, v in sorted(params.items()))
        rtl = self.rtl_hash if glue else self.unit_hash(unit)
        model = self.model_hash if (sram or glue) else "-"
        delays = " ".join(self.glue_delays) if glue else ""
        return sha(f"flow={FLOW_VERSION} unit={unit} glue={glue} sram={sram} period={self.args.period} "
                   f"params={p} rtl={rtl} lib={self.lib_hash} sram_model={model} delays={delays}")[:16]

    def instances(self, params):
        """rt_core's unit instances for PARAMS: [(instance, module, {param: value})]."""
        key = sha(f"instances {sorted(params.items())} rtl={self.rtl_hash}")[:16]
        path = os.path.join(self.out, f"instances-{key}.json")
        if os.path.exists(path):
            return json.load(open(path))
        dump = os.path.join(self.logs_dir, f"rt_core-{key}.dump")
        files = " ".join([os.path.join(RTL, "kdrt_fp_pkg.sv"), os.path.join(RTL, "kdrt_pkg.sv")] + sorted(
            os.path.join(RTL, f) for f in os.listdir(RTL) if f.endswith(".sv") and not f.endswith("_pkg.sv")))
        chp = " ".join(f"-set {k} {v}" for k, v in params.items())
        script = f"read_verilog -sv {files}\n"
        if chp:
            script += f"chparam {chp} rt_core\n"
        script += f"tee -q -o {dump} dump rt_core\n"
        yosys = os.environ.get("YOSYS", "yosys")
        logp = os.path.join(self.logs_dir, f"rt_core-{key}.instances.log")
        rc, _ = run_tool(["prlimit", f"--as={self.mem_bytes}", yosys, "-q", "-p", script], logp, self.timeout_s)
        if rc != 0:
            tail = "".join(open(logp).readlines()[-15:])
            die(f"rt_core {params}: Yosys could not elaborate it; the end of its log:\n{tail}")
        insts = []
        cur = None
        for line in open(dump):
            m = re.match(r"^\s*cell \\(\S+) \\(\S+)\s*$", line)
            if m:
                cur = [m.group(2), m.group(1), {}]
                insts.append(cur)
                continue
            if cur is None:
                continue
            m = re.match(r"^\s*parameter (?:signed )?\\(\w+) (.*)$", line)
            if m:
                name, val = m.group(1), m.group(2).strip()
                if re.fullmatch(r"-?\d+", val):
                    cur[2][name] = int(val)
                elif re.fullmatch(r"\d+'[01]+", val):
                    cur[2][name] = int(val.split("'")[1], 2)
                else:
                    cur[2][name] = val  # a string (a message text), not hardware
            elif re.match(r"^\s*end\s*$", line):
                cur = None
        os.unlink(dump)
        atomic_write(path, json.dumps(insts) + "\n")
        return insts

    def synth(self, unit, params, glue, sram, label):
        """One synthesis (or its cached result): the unit JSON, or
        {"failed": reason}."""
        k = self.key(unit, params, glue, sram)
        path = os.path.join(self.units_dir, f"{unit}-{k}.json")
        if os.path.exists(path):
            r = json.load(open(path))
            log(f"{label}: cached ({r['seconds']:.0f} s when synthesized)")
            return r
        capkey = f"{self.args.mem_gb:g}GB-{self.args.time_min:g}min"
        fail_path = os.path.join(self.units_dir, f"{unit}-{k}.failed-{capkey}")
        if os.path.exists(fail_path):
            reason = open(fail_path).read().strip()
            log(f"{label}: failed before with these caps ({reason}), not retried")
            return {"failed": reason}
        if STOP.is_set():
            return {"failed": "interrupted"}
        cmd = ["prlimit", f"--as={self.mem_bytes}", "nice", "-n", "10", SYNTH_PHYS,
               "--period", str(self.args.period), "--json", path + ".run"]
        if sram:
            cmd.append("--sram")
        if glue:
            cmd.append("--glue")
            for d in self.glue_delays:
                cmd += ["--input-delay", d]
        cmd += [unit] + [f"{k2}={v}" for k2, v in params.items()]
        logp = os.path.join(self.logs_dir, f"{unit}-{k}.log")
        log(f"{label}: synthesizing")
        rc, secs = run_tool(cmd, logp, self.timeout_s)
        if rc == 0 and os.path.exists(path + ".run"):
            r = json.load(open(path + ".run"))
            os.unlink(path + ".run")
            r["seconds"] = round(secs, 1)
            atomic_write(path, json.dumps(r) + "\n")
            log(f"{label}: done in {secs:.0f} s ({r['area_um2']} um2, {r['flip_flops']} flip-flops, "
                f"{r['crit_ns']} ns)")
            return r
        if os.path.exists(path + ".run"):
            os.unlink(path + ".run")
        text = open(logp, errors="replace").read()
        if rc is None:
            reason = f"exceeded the time cap of {self.args.time_min:g} min"
        elif re.search(r"bad_alloc|out of memory|Cannot allocate|MemoryError", text, re.I) or rc in (134, 137, -9, -6):
            reason = f"exceeded the memory cap of {self.args.mem_gb:g} GB"
        else:
            last = [l for l in text.splitlines() if l.strip()][-1:] or ["no output"]
            reason = f"synthesis failed (exit status {rc}: {last[0].strip()})"
        if not STOP.is_set():
            atomic_write(fail_path, reason + "\n")
        log(f"{label}: FAILED after {secs:.0f} s: {reason}; log {logp}")
        return {"failed": reason}


def extrapolate(v, v1, r1, v2, r2):
    """Values at size V from results at sizes V1 > V2."""
    out = {}
    for f in ("area_um2", "cells", "flip_flops"):
        slope = (r1[f] - r2[f]) / (v1 - v2)
        out[f] = int(round(max(r1[f], r1[f] + slope * (v - v1))))
    slope = (r1["crit_ns"] - r2["crit_ns"]) / (math.log2(v1) - math.log2(v2))
    out["crit_ns"] = round(max(r1["crit_ns"], r1["crit_ns"] + slope * (math.log2(v) - math.log2(v1))), 3)
    # An SRAM macro's words grow with the size as well (a miss register's
    # buffers, a thread's stack): each macro of V1 is matched by name and
    # width with V2's, and its words extrapolated linearly like the area.
    by_name = {(m["name"], m["width"]): m["words"] for m in r2.get("srams", [])}
    srams = []
    for m in r1.get("srams", []):
        w2 = by_name.get((m["name"], m["width"]), m["words"])
        slope = (m["words"] - w2) / (v1 - v2)
        srams.append(dict(m, words=int(round(max(m["words"], m["words"] + slope * (v - v1))))))
    out["srams"] = srams
    return out


def main():
    ap = argparse.ArgumentParser(
        prog="synth-core.sh", formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__,
        usage="scripts/synth-core.sh --out DIR [--period NS] [--jobs N] [--mem-gb G] [--time-min M] [--table] "
              "NAME=VALUE...")
    ap.add_argument("--out", required=True, help="the result directory (DIR/core.json, the cache DIR/units)")
    ap.add_argument("--period", type=float, default=5.0, help="clock period and delay target in ns (default 5)")
    ap.add_argument("--jobs", type=int, default=1, help="syntheses at once (default 1)")
    ap.add_argument("--mem-gb", type=float, default=10.0,
                    help="address-space cap of each synthesis in GB (default 10)")
    ap.add_argument("--time-min", type=float, default=60.0,
                    help="time cap of each synthesis in minutes (default 60)")
    ap.add_argument("--table", action="store_true",
                    help="also print the result as Markdown tables on standard output")
    ap.add_argument("params", nargs="*", metavar="NAME=VALUE", help="rt_core parameters, e.g. Threads=32")
    args = ap.parse_args()
    if args.period <= 0 or args.jobs < 1 or args.mem_gb <= 0 or args.time_min <= 0:
        ap.error("--period, --jobs, --mem-gb and --time-min must be positive")
    defaults = core_param_defaults()
    params = {}
    for kv in args.params:
        m = re.fullmatch(r"([A-Za-z]\w*)=(\d+)", kv)
        if not m:
            ap.error(f"{kv}: expected NAME=VALUE (an rt_core parameter and a number)")
        if m.group(1) not in defaults:
            ap.error(f"{m.group(1)}: not a parameter of rt_core (rtl/rt_core.sv): {', '.join(defaults)}")
        params[m.group(1)] = int(m.group(2))

    lib = os.environ.get("LIBERTY", DEFAULT_LIB)
    if not os.access(lib, os.R_OK):
        die(f"{lib}: Liberty file not found (apt-get install qflow-tech-osu018, or set LIBERTY=path)")
    for tool, pkg in ((os.environ.get("YOSYS", "yosys"), "yosys"), (os.environ.get("STA", "sta"), "opensta"),
                      ("prlimit", "util-linux")):
        if not shutil.which(tool):
            die(f"{tool}: command not found (apt-get install {pkg})")
    coeffs = sram_model.load()
    # Taken before the first synthesis: an edit during the run leaves core.json stale, not mislabelled.
    sources = sources_hash()

    os.makedirs(args.out, exist_ok=True)
    core_json = os.path.join(args.out, "core.json")
    if os.path.exists(core_json):
        os.unlink(core_json)
    flow = Flow(args)
    t0 = time.time()

    insts = flow.instances(params)
    # rt_core's own memories (rt_ram_1r1w instances: macros and nothing else)
    # deliver their words at the macro's access time to the logic around them.
    flow.glue_delays = sorted(
        f"{name}.rdata_o={sram_model.macro(p['Words'], p['Width'], coeffs)['access_ns']}"
        for name, module, p in insts if module == "rt_ram_1r1w")
    notes = []
    groups = {}  # (module, params) -> {"instances": [...], "params": {...}}
    dropped = set()
    for name, module, p in insts:
        num = {k: v for k, v in p.items() if isinstance(v, int)}
        for k, v in p.items():
            if not isinstance(v, int):
                dropped.add(f"{module}.{k}")
        g = groups.setdefault((module, tuple(sorted(num.items()))), {"module": module, "params": num,
                                                                     "instances": []})
        g["instances"].append(name)
    if dropped:
        notes.append(f"string parameters left at their defaults (message texts, no hardware): "
                     f"{', '.join(sorted(dropped))}")
    # rt_core's own logic first, then the units in instantiation order.
    todo = [{"unit": "rt_core", "params": dict(params), "glue": True, "sram": False, "instances": ["rt_core"]}]
    for g in groups.values():
        todo.append({"unit": g["module"], "params": g["params"], "glue": False,
                     "sram": g["module"] in SRAM_UNITS, "instances": g["instances"]})
    n = len(todo)
    log(f"rt_core {' '.join(args.params) or '(defaults)'}: {n} units ({len(insts)} instances), "
        f"{args.jobs} at once, caps {args.mem_gb:g} GB and {args.time_min:g} min per synthesis")

    def desc(t, p=None):
        p = t["params"] if p is None else p
        return f"{t['unit']}{' (own logic)' if t['glue'] else ''} " + " ".join(f"{k}={v}" for k, v in p.items())

    def run_all(jobs):  # jobs: [(label, unit, params, glue, sram)] -> results in order
        with cf.ThreadPoolExecutor(max_workers=args.jobs) as ex:
            futs = [ex.submit(flow.synth, u, p, g, s, label) for label, u, p, g, s in jobs]
            return [f.result() for f in futs]

    # The largest first (rt_core's own logic, then by their size parameter),
    # so that they do not start last.
    def size(t):
        return 10**9 if t["glue"] else max([v for k, v in t["params"].items() if k in SCALE_PARAMS] or [0])
    order = sorted(range(n), key=lambda i: -size(todo[i]))
    results = run_all([(f"[{i + 1}/{n}] {desc(todo[i])}", todo[i]["unit"], todo[i]["params"], todo[i]["glue"],
                        todo[i]["sram"]) for i in order])
    for i, r in zip(order, results):
        todo[i]["result"] = r

    # Estimates for the units that failed.
    failed = [t for t in todo if "failed" in t["result"]]
    for t in failed:
        full = dict(t["params"])
        if t["glue"]:
            full = {k: v for k, v in defaults.items() if v is not None} | full
        t["scale"] = next((s for s in SCALE_PARAMS if isinstance(full.get(s), int) and full[s] >= 8), None)
        t["full"] = full
    d = 8
    while not STOP.is_set():
        pending = [t for t in failed if t.get("scale") and "estimate" not in t
                   and t["full"][t["scale"]] // (2 * d) >= 2]
        if not pending:
            break
        jobs = []
        for t in pending:
            s, v = t["scale"], t["full"][t["scale"]]
            for vv in (v // d, v // (2 * d)):
                p = dict(t["params"])
                p[s] = vv
                jobs.append((f"estimate of {desc(t)}: {s}={vv}", t["unit"], p, t["glue"], t["sram"]))
        rs = run_all(jobs)
        for i, t in enumerate(pending):
            r1, r2 = rs[2 * i], rs[2 * i + 1]
            if "failed" in r1 or "failed" in r2:
                continue
            s, v = t["scale"], t["full"][t["scale"]]
            v1, v2 = v // d, v // (2 * d)
            est = dict(r1)
            est.update(extrapolate(v, v1, r1, v2, r2))
            est["params"] = t["params"]
            method = (f"{t['result']['failed']} at {s}={v}; synthesized at {s}={v1} and {s}={v2}, area, cells "
                      f"and flip-flops and the SRAM macros' words extrapolated linearly in {s}, crit_ns "
                      f"linearly in log2({s}), the path of {s}={v1}")
            t["estimate"] = (est, method)
            log(f"{desc(t)}: ESTIMATED: {method}")
        d *= 2

    missing = [t for t in failed if "estimate" not in t]
    if missing:
        for t in missing:
            log(f"{desc(t)}: neither synthesized nor estimated ({t['result']['failed']}"
                f"{'' if t.get('scale') else '; no size parameter to scale'})")
        die("no core.json written")

    units = []
    clock, critical = 0.0, ""
    logic = sram_area = 0
    for t in todo:
        if "estimate" in t:
            r, method = t["estimate"]
        else:
            r, method = t["result"], None
        srams = []
        for m in r.get("srams", []):
            s = sram_model.macro(m["words"], m["width"], coeffs)
            srams.append({"name": m["name"], "words": m["words"], "width": m["width"], "count": 1,
                          "area_um2": s["area_um2"], "access_ns": s["access_ns"], "source": "model"})
        count = len(t["instances"])
        u = {"unit": t["unit"], "instances": t["instances"], "count": count, "params": t["params"],
             "area_um2": r["area_um2"], "cells": r["cells"], "flip_flops": r["flip_flops"],
             "crit_ns": r["crit_ns"], "crit_path": r["crit_path"], "srams": srams,
             "estimated": method is not None}
        if method:
            u["method"] = method
            notes.append(f"{t['unit']}: estimated: {method}")
        if r["cells"] == 0:
            notes.append(f"{t['unit']}: no logic under synthesis (a simulation-only check): 0 cells")
        units.append(u)
        logic += r["area_um2"] * count
        if r["crit_ns"] > clock:
            clock, critical = r["crit_ns"], t["unit"]
        for s in srams:
            sram_area += s["area_um2"] * s["count"] * count
            if s["access_ns"] > clock:
                clock, critical = s["access_ns"], t["unit"]
    worst = max(units, key=lambda u: u["crit_ns"])
    notes.append("scope per_unit: each unit timed alone, its ports ideal (input and output delay 0, no "
                 "driving cell, no load), no wires, except an SRAM macro's data output, which arrives at the "
                 "macro's access time (the logic after a macro is timed with it, in the unit that holds the "
                 "macro and in rt_core's own logic); clock_ns is the slowest unit or SRAM macro; the paths "
                 "between units are not timed")
    notes.append(f"slowest path in a unit: {worst['crit_ns']} ns ({worst['unit']}: {worst['crit_path']['from']} to "
                 f"{worst['crit_path']['to']}; a path from an SRAM macro includes its access time)")
    if sram_area:
        notes.append(f"SRAM macros: area and access time from the model in scripts/sram_model.txt "
                     f"({coeffs['model']}: IHP SG13G2 130 nm two-port macros scaled to 180 nm; docs/physical.md, "
                     f"'SRAM macros'), "
                     f"not synthesized; their area is not in logic")
    core = {"library": "osu018", "sources_fnv1a64": sources,
            "period_target_ns": args.period if args.period != int(args.period) else int(args.period),
            "scope": "per_unit", "params": params, "clock_ns": clock, "critical_unit": critical,
            "area_um2": {"logic": logic, "sram": sram_area, "total": logic + sram_area},
            "units": units, "notes": notes}
    lib_names = {t["result"].get("library") for t in todo if "library" in t["result"]}
    lib_names |= {t["estimate"][0].get("library") for t in todo if "estimate" in t}
    if len(lib_names) == 1:
        core["library"] = lib_names.pop()
    atomic_write(core_json, json.dumps(core, indent=1) + "\n")
    if args.table:
        print(markdown(core, todo))
    log(f"clock {clock} ns ({critical}), area {logic + sram_area} um2 (logic {logic}, SRAM {sram_area}); "
        f"{time.time() - t0:.0f} s; {core_json}")
    return 0


def markdown(core, todo):
    """The units, the SRAM macros and the totals of CORE as Markdown tables
    (TODO: the runs behind its units, for their synthesis times)."""
    def secs(t):
        if "estimate" in t:
            return "estimated"
        return f"{t['result'].get('seconds', 0):.0f}"
    lines = ["| unit | instances | parameters | cells | area (um^2, each) | flip-flops | critical (ns) | "
             "path start | path end | synthesis (s) |", "|---|---|---|---:|---:|---:|---:|---|---|---:|"]
    for u, t in zip(core["units"], todo):
        params = " ".join(f"{k}={v}" for k, v in sorted(u["params"].items())) or "-"
        name = u["unit"] + (" (own logic)" if u["unit"] == "rt_core" else "")
        est = " (estimated)" if u["estimated"] else ""
        lines.append(f"| {name}{est} | {u['count']} | {params} | {u['cells']} | {u['area_um2']} | "
                     f"{u['flip_flops']} | {u['crit_ns']} | {u['crit_path']['from']} | {u['crit_path']['to']} | "
                     f"{secs(t)} |")
    srams = [(u["unit"], s) for u in core["units"] for s in u["srams"]]
    if srams:
        lines += ["", "| SRAM macro | words x width | area (um^2) | access (ns) | source |", "|---|---|---:|---:|---|"]
        for unit, s in srams:
            lines.append(f"| {unit} {s['name']} | {s['words']} x {s['width']} | {s['area_um2']} | "
                         f"{s['access_ns']} | {s['source']} |")
    a = core["area_um2"]
    lines += ["", f"Clock: {core['clock_ns']} ns ({core['critical_unit']}); area: {a['total']} um^2 "
              f"({a['total'] / 1e6:.2f} mm^2) = logic {a['logic']} + SRAM {a['sram']}.", ""]
    lines += [f"- {n}" for n in core["notes"]]
    return "\n".join(lines)


def on_signal(signum, frame):
    STOP.set()
    with RUNNING_LOCK:
        procs = list(RUNNING)
    for p in procs:
        kill_group(p)
    log(f"interrupted (signal {signum}); finished units stay cached")
    os._exit(128 + signum)


if __name__ == "__main__":
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    sys.exit(main())
