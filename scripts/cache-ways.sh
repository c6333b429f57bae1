#!/usr/bin/env bash
# What set-associative caches buy: for each scene, memory latency
# and number of ways, `kdrt sim` cycles per ray (efficiency against the
# per-core bound), memory bytes per ray and the node / list / triangle hit
# rates, at the same cache size. Prints one Markdown row per scene and
# latency; with JSONL=FILE appends each run's JSON to FILE.
#   scripts/cache-ways.sh [KDRT] [RES] [LATENCIES] [WAYS] SCENE... [-- SIM OPTIONS]
#   (defaults: build/bin/kdrt, 128x128, "20 200", "1 2 4 8", the generators at 10k)
# SIM OPTIONS go to every run, e.g. `--model fast` (cycle-exact against the
# RTL, tests/sim/sim_cli_test.cpp) or `--threads 32`.
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
res=${2:-128x128}
lats=${3:-20 200}
ways_list=${4:-1 2 4 8}
shift $(($# < 4 ? $# : 4))
. "$(dirname "${BASH_SOURCE[0]}")/scene-args.sh"
read_scenes "gen:room:10000 gen:balls:10000 gen:rings:10000 gen:tetra:10000 gen:tree:10000 gen:gears:10000" "$@"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
header="| scene | latency | bound |"
rule="|---|---:|---:|"
for w in $ways_list; do
  header+=" $w way(s): cycles/ray (eff.), B/ray, node / list / tri hit |"
  rule+="---|"
done
echo "$header"
echo "$rule"
for scene in "${scenes[@]}"; do
  for lat in $lats; do
    row=""
    bound=""
    for w in $ways_list; do
      echo "cache-ways: $scene latency $lat ways $w ${extra[*]:-}" >&2
      "$kdrt" sim "$scene" --res "$res" --mem-latency "$lat" --cache-ways "$w" -q -o "$tmp/a.png" \
        --json "$tmp/a.json" "${extra[@]}" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
      [ -z "${JSONL:-}" ] || { tr -d '\n' < "$tmp/a.json"; echo; } >> "$JSONL"
      cell=$(python3 - "$tmp/a.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[1]))
c = a["cache_hit_rate"]
pc = lambda x: "%.1f %%" % (100 * x)
print("%.2f\t%.2f (%s), %.1f, %s / %s / %s" % (
    a["bound_cycles_per_ray"], a["cycles_per_ray"], pc(a["efficiency"]),
    a["memory"]["bytes_read"] / a["rays"], pc(c["node"]), pc(c["list"]), pc(c["tri"])))
PY
)
      bound=${cell%%$'\t'*}
      row+=" ${cell#*$'\t'} |"
    done
    echo "| $scene | $lat | $bound |$row"
  done
done
