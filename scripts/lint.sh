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

fail=0
count=0
lint() {  # lint <top> <label> <extra verilator args...>
  local top="$1" label="$2"
  shift 2
  local log
  if ! log=$("$VERILATOR" --lint-only -Wall --top-module "$top" "$@" 2>&1); then
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
    done
  else
    lint "$top" "defaults" "${srcs[@]}" -y "$RTL" "$file"
  fi
  # rt_cache's sets and pseudo-LRU exist only with Ways > 1 (the default is 1).
  if [ "$top" = rt_cache ]; then
    for ways in 2 8:Lines=8; do
      IFS=: read -r w lines <<< "$ways"
      lint "$top" "Ways=$w ${lines:-}" "${srcs[@]}" -y "$RTL" "$file" -GWays="$w" ${lines:+-G$lines}
    done
  fi
done

if [ "$fail" -ne 0 ]; then
  echo "lint: FAILED"
  exit 1
fi
echo "lint: clean ($count configurations of $(ls "$RTL"/*.sv | wc -l) files)"
