#!/usr/bin/env bash
# Multi-core scaling (issue 13, part 3): `kdrt sim --cores N` for each scene,
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
shift 5 || true
scenes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do scenes+=("$1"); shift; done
[ "${1:-}" = "--" ] && shift
extra=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(gen:balls:10000 gen:tree:10000)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "scene,bytes_per_cycle,cores,rays_per_cycle,cycles_per_ray,efficiency,l2_hit_rate,mem_bytes_per_cycle_used" > "$out.csv"
for scene in "${scenes[@]}"; do
  for bw in $bws; do
    for n in $cores_list; do
      echo "scaling: $scene --mem-bw $bw --cores $n ${extra[*]:-}" >&2
      "$kdrt" sim "$scene" --res "$res" --cores "$n" --mem-bw "$bw" -q -o "$tmp/a.png" --json "$tmp/a.json" \
        "${extra[@]}" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
      python3 - "$scene" "$bw" "$n" "$tmp/a.json" >> "$out.csv" <<'PY'
import json, sys
scene, bw, n, path = sys.argv[1:]
j = json.load(open(path))
print("%s,%s,%s,%.6f,%.4f,%.4f,%.4f,%.4f" % (scene, bw, n, j["rays_per_cycle"], j["cycles_per_ray"],
      j["efficiency"], j["l2"]["hit_rate"], j["memory"]["bytes_per_cycle_used"]))
PY
    done
  done
done
python3 - "$out.csv" "$out.svg" <<'PY'
import csv, sys
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
# The plot: plain SVG, log2 x axis (cores), linear y (rays per cycle).
W, H, L, R, T, B = 640, 400, 60, 200, 20, 50
xs = sorted({n for pts in series.values() for n, _, _ in pts})
ymax = max(rpc for pts in series.values() for _, rpc, _ in pts) * 1.1
import math
lx = lambda n: L + (W - L - R) * (math.log2(n) - math.log2(xs[0])) / max(1e-9, math.log2(xs[-1]) - math.log2(xs[0]))
ly = lambda y: H - B - (H - T - B) * y / ymax
colors = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"]
o = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (W, H),
     '<rect width="100%" height="100%" fill="white"/>',
     '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - R, H - B),
     '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, T, L, H - B)]
for n in xs:
    o.append('<text x="%.1f" y="%d" text-anchor="middle">%d</text>' % (lx(n), H - B + 16, n))
for k in range(6):
    y = ymax * k / 5
    o.append('<text x="%d" y="%.1f" text-anchor="end">%.2f</text>' % (L - 6, ly(y) + 4, y))
    o.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (L, ly(y), W - R, ly(y)))
o.append('<text x="%d" y="%d" text-anchor="middle">cores</text>' % ((L + W - R) / 2, H - 12))
o.append('<text x="14" y="%d" transform="rotate(-90 14 %d)" text-anchor="middle">rays per cycle</text>' %
         ((T + H - B) / 2, (T + H - B) / 2))
for i, ((scene, bw), pts) in enumerate(series.items()):
    c = colors[i % len(colors)]
    dash = "" if float(bw) >= 16 else ' stroke-dasharray="5,3"'
    o.append('<polyline fill="none" stroke="%s" stroke-width="2"%s points="%s"/>' %
             (c, dash, " ".join("%.1f,%.1f" % (lx(n), ly(rpc)) for n, rpc, _ in pts)))
    for n, rpc, _ in pts:
        o.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (lx(n), ly(rpc), c))
    o.append('<text x="%d" y="%d" fill="%s">%s, %s B/cycle</text>' % (W - R + 10, T + 16 * (i + 1), c,
             scene.replace("gen:", ""), bw))
o.append("</svg>")
open(sys.argv[2], "w").write("\n".join(o) + "\n")
PY
echo "scaling: wrote $out.csv and $out.svg" >&2
