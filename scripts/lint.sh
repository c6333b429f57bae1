#!/usr/bin/env bash
# Lints every top-level RTL unit with Verilator -Wall, once per number-format
# preset (and the narrow/wide edge formats); exits non-zero on any warning.
# Usage: scripts/lint.sh   (from anywhere)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RTL="$ROOT/rtl"
VERILATOR="${VERILATOR:-verilator}"

# Files that every unit may use; passed before the unit itself.
COMMON=("$RTL/kdrt_fp_pkg.sv" "$RTL/fp_round.sv")
# name:E:M
# The preset formats: the one list in cmake/presets.cmake.
read -r -a PRESETS <<< "$(sed -n 's/^set(KDRT_PRESETS \(.*\))$/\1/p' "$(dirname "$0")/../cmake/presets.cmake")"
# The fp_* units must also hold at the edges of the accepted range.
FP_FORMATS=("${PRESETS[@]}" e4m3:4:3 e2m1:2:1 e2m23:2:23)
# A traversal wider than the triangle test: units with a TravE parameter are
# also linted, per preset, with every other preset at least as wide in both
# fields as the traversal (fp24, bf16 and fp16 beside fp32, fp16 beside fp24).
# The widening helpers (fp_widen, fp_round_out; defaults WE = 8, WM = 23,
# at least every accepted format) are also linted with fp24's fields as the
# wide format, for every format that fits in it.
IFS=: read -r _ FP24_E FP24_M <<< "$(printf '%s\n' "${PRESETS[@]}" | grep '^fp24:')"

# The unroll limits of every model build (cmake/core_elaborates.cmake,
# KDRT_CORE_ELAB_ARGS): Verilator 5.006 refuses a delayed array assignment in
# a per-thread loop it does not unroll (BLKLOOPINIT), which the default 96
# threads exceed at its default --unroll-count of 64.
read -r -a UNROLL_ARGS <<< "$(sed -n 's/^set(KDRT_CORE_ELAB_ARGS \(.*\))$/\1/p' "$ROOT/cmake/core_elaborates.cmake")"
[ "${#UNROLL_ARGS[@]}" -gt 0 ] || { echo "lint: no KDRT_CORE_ELAB_ARGS in cmake/core_elaborates.cmake" >&2; exit 1; }

fail=0
count=0
lint() {  # lint <top> <label> <extra verilator args...>
  local top="$1" label="$2"
  shift 2
  local log
  if ! log=$("$VERILATOR" --lint-only -Wall "${UNROLL_ARGS[@]}" --top-module "$top" "$@" 2>&1); then
    echo "lint: FAIL $top $label"
    echo "$log"
    fail=1
  elif [ -n "$log" ]; then
    echo "lint: FAIL $top $label (output)"
    echo "$log"
    fail=1
  fi
  count=$((count + 1))
}

# lint_format_pairs <top> <file> <name> <E> <M> <Prefix> <wider|narrower>:
# if the unit has a <Prefix>E parameter, lints it in (E, M) with every other
# preset at least as wide (Trav: a traversal wider than the test) or at most
# as wide (Img: a narrower memory image) in both fields as <Prefix>E, <Prefix>M.
lint_format_pairs() {
  local top="$1" file="$2" name="$3" e="$4" m="$5" prefix="$6" dir="$7" other oname oe om
  grep -qE "^\s*parameter\s+int\s+unsigned\s+${prefix}E\b" "$file" || return 0
  for other in "${PRESETS[@]}"; do
    IFS=: read -r oname oe om <<< "$other"
    [ "$oname" != "$name" ] || continue
    if [ "$dir" = wider ]; then
      [ "$oe" -ge "$e" ] && [ "$om" -ge "$m" ] || continue
    else
      [ "$oe" -le "$e" ] && [ "$om" -le "$m" ] || continue
    fi
    lint "$top" "$name $prefix $oname" "${srcs[@]}" -y "$RTL" "$file" -GE="$e" -GM="$m" \
      -G"${prefix}E=$oe" -G"${prefix}M=$om"
  done
}

for file in "$RTL"/*.sv; do
  top="$(basename "$file" .sv)"
  case "$top" in
    *_pkg) continue ;;  # packages are linted with every unit
  esac
  # Units whose modules take E and M are linted per format; other modules
  # (written by other engineers) once with their default parameters, with
  # every rtl/*.sv file available for the submodules they instantiate.
  srcs=()
  for f in "$RTL"/*pkg.sv; do srcs+=("$f"); done
  if grep -qE '^\s*parameter\s+int\s+unsigned\s+E\s*=' "$file" &&
     grep -qE '^\s*parameter\s+int\s+unsigned\s+M\s*=' "$file"; then
    formats=("${PRESETS[@]}")
    case "$top" in fp_*) formats=("${FP_FORMATS[@]}") ;; esac
    for fmt in "${formats[@]}"; do
      IFS=: read -r name e m <<< "$fmt"
      if [ "$top" = fp_cmp ]; then
        lint "$top" "$name Stages=0" "${srcs[@]}" -y "$RTL" "$file" -GE="$e" -GM="$m" -GStages=0
      fi
      lint "$top" "$name" "${srcs[@]}" -y "$RTL" "$file" -GE="$e" -GM="$m"
      case "$top" in
        fp_widen|fp_round_out)
          if [ -n "$FP24_E" ] && [ "$e" -le "$FP24_E" ] && [ "$m" -le "$FP24_M" ] && { [ "$e" -ne "$FP24_E" ] || [ "$m" -ne "$FP24_M" ]; }; then
            lint "$top" "$name WE=$FP24_E WM=$FP24_M" "${srcs[@]}" -y "$RTL" "$file" -GE="$e" -GM="$m" \
              -GWE="$FP24_E" -GWM="$FP24_M"
          fi
          ;;
      esac
      lint_format_pairs "$top" "$file" "$name" "$e" "$m" Trav wider
    done
  else
    lint "$top" "defaults" "${srcs[@]}" -y "$RTL" "$file"
    # A unit with a traversal and an image format (rt_core: its E and M carry
    # /*verilator public*/) is linted with each wider traversal and each
    # narrower image too.
    for fmt in "${PRESETS[@]}"; do
      IFS=: read -r name e m <<< "$fmt"
      lint_format_pairs "$top" "$file" "$name" "$e" "$m" Trav wider
      lint_format_pairs "$top" "$file" "$name" "$e" "$m" Img narrower
    done
  fi
  # The list path of one request per entry (ListStream 0; the default is
  # the streaming 1) of the list unit, the memory side and the core.
  case "$top" in
    rt_list_unit|rt_mem_system|rt_core)
      lint "$top" "ListStream=0" "${srcs[@]}" -y "$RTL" "$file" -GListStream=0 ;;
  esac
  # rt_cache's sets and pseudo-LRU exist only with Ways > 1 (the default is 1).
  if [ "$top" = rt_cache ]; then
    for ways in 2 8:Lines=8; do
      IFS=: read -r w lines <<< "$ways"
      lint "$top" "Ways=$w ${lines:-}" "${srcs[@]}" -y "$RTL" "$file" -GWays="$w" ${lines:+-G$lines}
    done
    lint "$top" "PrefetchPort=1" "${srcs[@]}" -y "$RTL" "$file" -GPrefetchPort=1\'b1 -GWays=4 -GLines=16
  fi
  # rt_prio_enc describes its function twice: the word form Verilator takes
  # by default, and the tree synthesis takes.
  if [ "$top" = rt_prio_enc ]; then
    lint "$top" "Words=0 N=128" "${srcs[@]}" -y "$RTL" "$file" -GWords=1\'b0 -GN=128
  fi
  # The list prefetcher: the units' default is 0 (none), the core's 16, so
  # each is linted with the other as well.
  case "$top" in
    rt_list_unit|rt_mem_system)
      lint "$top" "ListPrefetch=4" "${srcs[@]}" -y "$RTL" "$file" -GListPrefetch=4 ;;
    rt_core)
      lint "$top" "ListPrefetch=0" "${srcs[@]}" -y "$RTL" "$file" -GListPrefetch=0 ;;
  esac
done

if [ "$fail" -ne 0 ]; then
  echo "lint: FAILED"
  exit 1
fi
echo "lint: clean ($count configurations of $(ls "$RTL"/*.sv | wc -l) files)"
