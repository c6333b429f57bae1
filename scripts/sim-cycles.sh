#!/usr/bin/env bash
# Runs `kdrt sim` on every generator in every preset format and prints one line
# per run: scene, format, cycles, hits and the SHA-256 of the hit buffer. Two
# runs of this script (before and after a change to the core or the simulator)
# must print the same lines when the change is meant to keep behaviour.
#   scripts/sim-cycles.sh [KDRT] [RES]      (default build/bin/kdrt, 64x64)
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
res=${2:-64x64}
presets=$(sed -n 's/^set(KDRT_PRESETS \(.*\))$/\1/p' "$(dirname "$0")/../cmake/presets.cmake")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in gen:room:600 gen:balls:800 gen:rings:800 gen:tetra:1000 gen:tree:2000 gen:balls:10000; do
  for p in $presets; do
    fmt=${p%%:*}
    "$kdrt" sim "$scene" --format "$fmt" --res "$res" -q -o "$tmp/img.png" --hits "$tmp/hits.exr" \
      --json "$tmp/s.json"
    cycles=$(grep -m1 '"cycles":' "$tmp/s.json" | tr -dc '0-9')
    hits=$(grep -m1 '"hits":' "$tmp/s.json" | tr -dc '0-9')
    printf '%-18s %-5s cycles %-9s hits %-6s %s\n' "$scene" "$fmt" "$cycles" "$hits" \
      "$(sha256sum "$tmp/hits.exr" | cut -c1-16)"
  done
done
