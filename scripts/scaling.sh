#!/usr/bin/env bash
# Multi-core scaling: `kdrt sim --cores N` for each scene,
# core count and memory bandwidth; prints a Markdown table (rays per cycle,
# speed-up over one core, efficiency against the per-core bound, L2 hit rate,
# memory bytes per cycle used) and writes OUT.csv and OUT.svg (rays per cycle
# versus cores, one line per scene and bandwidth).
#   scripts/scaling.sh [KDRT] [RES] [CORES] [BANDWIDTHS] OUT SCENE... [-- SIM OPTIONS]
#   (e.g. scripts/scaling.sh build/bin/kdrt 128x128 "1 2 4 8 16" "16 4" docs/scaling gen:balls:10000)
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
res=${2:-128x128}
cores_list=${3:-1 2 4 8}
bws=${4:-16 4}
out=${5:-scaling}
shift $(($# < 5 ? $# : 5))
. "$(dirname "${BASH_SOURCE[0]}")/scene-args.sh"
read_scenes "gen:balls:10000 gen:tree:10000" "$@"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "scene,res,bytes_per_cycle,cores,rays_per_cycle,cycles_per_ray,efficiency,l2_hit_rate,mem_bytes_per_cycle_used" > "$out.csv"
for scene in "${scenes[@]}"; do
  for bw in $bws; do
    for n in $cores_list; do
      echo "scaling: $scene --mem-bw $bw --cores $n ${extra[*]:-}" >&2
      "$kdrt" sim "$scene" --res "$res" --cores "$n" --mem-bw "$bw" -q -o "$tmp/a.png" --json "$tmp/a.json" \
        "${extra[@]}" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
      python3 - "$scene" "$res" "$bw" "$n" "$tmp/a.json" >> "$out.csv" <<'PY'
import json, sys
scene, res, bw, n, path = sys.argv[1:]
j = json.load(open(path))
print("%s,%s,%s,%s,%.6f,%.4f,%.4f,%.4f,%.4f" % (scene, res, bw, n, j["rays_per_cycle"], j["cycles_per_ray"],
      j["efficiency"], j["l2"]["hit_rate"], j["memory"]["bytes_per_cycle_used"]))
PY
    done
  done
done
python3 - "$out.csv" "$out.svg" "$(dirname "$0")" <<'PY'
import csv, sys
sys.path.insert(0, sys.argv[3])
from kdrt_sweep import plot  # the sweep's plain SVG plot, cores as equally spaced categories
rows = list(csv.DictReader(open(sys.argv[1])))
series = {}
for r in rows:
    series.setdefault((r["scene"], r["bytes_per_cycle"]), []).append((int(r["cores"]), float(r["rays_per_cycle"]),
                                                                      r))
print("| scene | B/cycle | cores | rays/cycle | speed-up | efficiency | L2 hits | memory B/cycle used |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for (scene, bw), pts in series.items():
    base = pts[0][1]
    for n, rpc, r in pts:
        print("| %s | %s | %d | %.4f | %.2fx | %.0f %% | %.1f %% | %.2f |" % (scene, bw, n, rpc, rpc / base,
              100 * float(r["efficiency"]), 100 * float(r["l2_hit_rate"]), float(r["mem_bytes_per_cycle_used"])))
plot(sys.argv[2], "rays per cycle against cores", "cores",
     [("%s, %s B/cycle" % (scene.replace("gen:", ""), bw), [(str(n), rpc) for n, rpc, _ in pts])
      for (scene, bw), pts in series.items()], y_label="rays per cycle")
PY
echo "scaling: wrote $out.csv and $out.svg" >&2
