#!/usr/bin/env bash
# scripts/sram_model.py: area grows with the words and the width, access
# time does not fall with either and is longer at 4,096 words than at 64; every macro says "source": "model"; bad arguments are refused.
# scripts/sram_model.txt is what scripts/sram_fit.py makes of the published
# macros, and no published macro (scaled to 180 nm) is faster than the model.
# Usage: sram_model_test.sh SOURCE_DIR
set -euo pipefail
model="$1/scripts/sram_model.py"
fail() { echo "FAIL: $*" >&2; exit 1; }
get() { sed -n "s/.*\"$2\": \([0-9.]*\).*/\1/p" <<< "$1"; }

prev_area=0 prev_access=0
for words in 16 64 128 256 1024 4096 8192; do
  out=$("$model" "$words" 128)
  grep -q '"source": "model"' <<< "$out" || fail "$words x 128: no source model in $out"
  area=$(get "$out" area_um2) access=$(get "$out" access_ns)
  awk -v a="$area" -v pa="$prev_area" -v t="$access" -v pt="$prev_access" 'BEGIN { exit !(a > pa && t >= pt) }' \
    || fail "$words x 128: area $area, access $access below $prev_area, $prev_access"
  prev_area=$area prev_access=$access
done
prev_area=0 prev_access=0
for width in 8 32 128 512; do
  out=$("$model" 256 "$width")
  area=$(get "$out" area_um2) access=$(get "$out" access_ns)
  awk -v a="$area" -v pa="$prev_area" -v t="$access" -v pt="$prev_access" 'BEGIN { exit !(a > pa && t >= pt) }' \
    || fail "256 x $width: area $area, access $access below $prev_area, $prev_access"
  prev_area=$area prev_access=$access
done
small=$(get "$("$model" 64 128)" access_ns) large=$(get "$("$model" 4096 128)" access_ns)
awk -v s="$small" -v l="$large" 'BEGIN { exit !(l > s) }' || fail "access $large ns at 4096 words, $small ns at 64"
rc=0
"$model" 0 8 2> /dev/null || rc=$?
[ "$rc" = 2 ] || fail "0 words: exit status $rc, expected 2"
"$1/scripts/sram_fit.py" --check || fail "scripts/sram_model.txt is not the fit of scripts/sram_macros.tsv"
python3 - "$1/scripts" <<'PY' || fail "a published macro is faster than the model"
import math, sys
sys.path.insert(0, sys.argv[1])
import sram_fit, sram_model
c = sram_model.load()
for r in sram_fit.read_macros():
    model = sram_model.macro(r["words"], r["width"], c)["access_ns"]
    scaled = r["access"] * sram_fit.DELAY_180_FROM_130
    if scaled > model + 1e-3:
        sys.exit(f"{r['name']}: {scaled:.3f} ns at 180 nm, the model {model:.3f} ns")
PY
echo "sram_model_test: ok"
