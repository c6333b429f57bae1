#!/usr/bin/env bash
# The structure comparison of docs/compare-accel.md: `kdrt compare-accel` on
# every generator at 10k, 100k and 1M triangles, 256x256 camera rays, one
# thread, each structure traced twice and the faster run kept. The 1M scenes
# leave out the median kd-tree: its tree holds 280-940 references per
# triangle at 100k (every split duplicates the triangles straddling it) and
# would need several GB at 1M. Writes OUT.json and OUT.md (the tables).
#   scripts/compare-accel.sh [KDRT] [OUT] [SIZES]
#   (e.g. scripts/compare-accel.sh build/bin/kdrt docs/compare-accel "10000 100000 1000000")
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
out=${2:-compare-accel}
sizes=${3:-10000 100000 1000000}
generators="room balls rings tetra tree gears hoops"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
: > "$tmp/tables.md"
parts=()
for size in $sizes; do
  accel=sah,median,midpoint,grid,hgrid,octree,bvh
  [ "$size" -ge 1000000 ] && accel=sah,midpoint,grid,hgrid,octree,bvh
  scenes=()
  for g in $generators; do scenes+=("gen:$g:$size"); done
  echo "compare-accel: ${scenes[*]}" >&2
  "$kdrt" compare-accel "${scenes[@]}" --accel "$accel" --res 256x256 --threads 1 --repeat 2 --markdown \
    --json "$tmp/$size.json" >> "$tmp/tables.md"
  parts+=("$tmp/$size.json")
done
python3 - "$out.json" "${parts[@]}" <<'PY'
import json, sys
scenes = []
for p in sys.argv[2:]:
    scenes += json.load(open(p))["scenes"]
json.dump({"command": "scripts/compare-accel.sh", "scenes": scenes}, open(sys.argv[1], "w"), indent=1)
PY
grep -v -e '^(fp32' -e '^stats ' "$tmp/tables.md" > "$out.md"
echo "wrote $out.json and $out.md" >&2
