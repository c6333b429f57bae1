#!/usr/bin/env bash
# The memory side of the number formats (docs/memory-image.md, "Packed
# formats"): for each scene and preset format, the image bytes, and from
# `kdrt sim` the memory bytes per ray, the cache hit rates and the cycles per
# ray, at the default memory and at a memory-bound one (2 bytes/cycle,
# latency 100). Prints a Markdown table.
#   scripts/packed-images.sh [KDRT] [RES] SCENE... [-- SIM OPTIONS]   (default build/bin/kdrt, 128x128)
set -euo pipefail
kdrt=${1:-build/bin/kdrt}
res=${2:-128x128}
shift $(($# < 2 ? $# : 2))
. "$(dirname "${BASH_SOURCE[0]}")/scene-args.sh"
read_scenes "gen:balls:10000 gen:rings:10000 gen:tetra:10000" "$@"
presets=$(sed -n 's/^set(KDRT_PRESETS \(.*\))$/\1/p' "$(dirname "$0")/../cmake/presets.cmake")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "| scene | format | image bytes | bytes/ray | node / list / tri hit rate | cycles/ray | bytes/ray, cycles/ray at 2 B/cycle, latency 100 |"
echo "|---|---|---:|---:|---|---:|---:|"
for scene in "${scenes[@]}"; do
  "$kdrt" info "$scene" --json "$tmp/info.json" > /dev/null
  for p in $presets; do
    fmt=${p%%:*}
    # A format whose image cannot hold the scene (kdrt info says why): a row
    # that says so, no run.
    why=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["images"][sys.argv[2]].get("error", ""))' \
      "$tmp/info.json" "$fmt")
    if [ -n "$why" ]; then
      echo "packed-images: $scene $fmt: $why" >&2
      echo "| $scene | $fmt | no image: ${why#memory image: } | | | | |"
      continue
    fi
    echo "packed-images: $scene $fmt ${extra[*]:-}" >&2
    "$kdrt" sim "$scene" --format "$fmt" --res "$res" -q -o "$tmp/a.png" --json "$tmp/a.json" "${extra[@]}" \
      2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    "$kdrt" sim "$scene" --format "$fmt" --res "$res" -q -o "$tmp/b.png" --json "$tmp/b.json" \
      --mem-bw 2 --mem-latency 100 "${extra[@]}" 2> "$tmp/err" || { cat "$tmp/err" >&2; exit 1; }
    python3 - "$scene" "$fmt" "$tmp/info.json" "$tmp/a.json" "$tmp/b.json" <<'PY'
import json, sys
scene, fmt, info, a, b = sys.argv[1:]
info, a, b = (json.load(open(f)) for f in (info, a, b))
c = a["cache_hit_rate"]
rates = " / ".join("%.1f %%" % (100 * c[k]) for k in ("node", "list", "tri"))
assert a["requirements"]["image_bytes"] == info["images"][fmt]["bytes"], "the core read another image"
print("| %s | %s | %d | %.1f | %s | %.2f | %.1f, %.2f |" % (
    scene, fmt, info["images"][fmt]["bytes"], a["memory"]["bytes_per_ray"], rates, a["cycles_per_ray"],
    b["memory"]["bytes_per_ray"], b["cycles_per_ray"]))
PY
  done
done
