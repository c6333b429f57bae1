#!/usr/bin/env bash
# The core's efficiency: for each scene and memory latency, `kdrt
# sim` cycles per ray against the per-core bound and the window bound (the
# same taken the rays in flight at a time), the stall breakdown, the
# cache hit rates, the misses in flight and (when the core reports them) the
# waits per cache, the unit stalls and the thread-state histogram. Prints a
# Markdown table, and with JSONL=FILE appends each run's JSON to FILE.
#   scripts/efficiency.sh [KDRT] [RES] [LATENCIES] SCENE... [-- SIM OPTIONS]
#   (defaults: build/bin/kdrt, 128x128, "20 200", the generators at 10k)
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
res=${2:-128x128}
lats=${3:-20 200}
shift $(($# < 3 ? $# : 3))
. "$(dirname "${BASH_SOURCE[0]}")/scene-args.sh"
read_scenes "gen:room:10000 gen:balls:10000 gen:rings:10000 gen:tetra:10000 gen:tree:10000 gen:gears:10000 gen:hoops:10000" "$@"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | latency | cycles/ray | bound | efficiency | window bound (efficiency) | stall mem / stack / backpressure | node / list / tri hit | max misses out | waits node / list / tri (in flight, no MSHR) | threads fetch / wait node / trav / leaf / exit / other |"
echo "|---|---:|---:|---:|---:|---:|---|---|---:|---|---|"
for scene in "${scenes[@]}"; do
  for lat in $lats; do
    echo "efficiency: $scene latency $lat ${extra[*]:-}" >&2
    "$kdrt" sim "$scene" --res "$res" --mem-latency "$lat" -q -o "$tmp/a.png" --json "$tmp/a.json" \
      "${extra[@]}" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    [ -z "${JSONL:-}" ] || { tr -d '\n' < "$tmp/a.json"; echo; } >> "$JSONL"
    python3 - "$scene" "$lat" "$tmp/a.json" <<'PY'
import json, sys
scene, lat, path = sys.argv[1:]
a = json.load(open(path))
pc = lambda x: "%.1f %%" % (100 * x)
s, c, p = a["stalls"], a["cache_hit_rate"], a["perf_counts"]
cyc = a["cycles"]
waits = "–"
if "node_wait" in p:
    waits = " / ".join("%s (%s, %s)" % (pc(p[k + "_wait"] / cyc), pc(p[k + "_wait_inflight"] / cyc),
                                       pc(p[k + "_wait_mshr"] / cyc)) for k in ("node", "list", "tri"))
threads = "–"
if "thread_states" in a:
    t = a["thread_states"]
    other = 1 - sum(t[k] for k in ("fetch", "wait_node", "trav", "leaf", "exit"))
    threads = " / ".join(pc(x) for x in (t["fetch"], t["wait_node"], t["trav"], t["leaf"], t["exit"], other))
w = a.get("window_bound")
window = "%.2f (%s)" % (w["cycles_per_ray"], pc(w["efficiency"])) if w and w["rays"] else "–"
print("| %s | %s | %.2f | %.2f | %s | %s | %s / %s / %s | %s / %s / %s | %d | %s | %s |" % (
    scene, lat, a["cycles_per_ray"], a["bound_cycles_per_ray"], pc(a["efficiency"]), window, pc(s["memory"]),
    pc(s["stack"]), pc(s["backpressure"]), pc(c["node"]), pc(c["list"]), pc(c["tri"]),
    a["memory"]["max_outstanding"], waits, threads))
PY
  done
done
