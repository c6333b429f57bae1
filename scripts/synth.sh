#!/usr/bin/env bash
# Synthesis of the (E, M) floating-point units and the core's units for each
# preset (units without E and M once, default parameters): generic Yosys by
# scripts/synth-unit.sh (fails if any latch is inferred; cells, flip-flops,
# logic depth = longest path in gates between registers/ports from
# `ltp -noff`) and the OSU 0.18 um cells by scripts/synth-phys.sh (area,
# critical path); then the default core, every unit at the parameters rt_core
# gives it, by scripts/synth-core.sh (cached in build/synth-core/default, so
# a second run only reads it). Prints the tables and writes them to
# docs/synth-table.md.
# Usage: scripts/synth.sh   (from anywhere; JOBS=n to change parallelism;
#        SYNTH_CORE_DIR=dir for the core's cache; CORE_MEM_GB, CORE_TIME_MIN:
#        synth-core.sh's caps per synthesis)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
YOSYS="${YOSYS:-yosys}"
JOBS="${JOBS:-2}"
OUT_MD="$ROOT/docs/synth-table.md"
WORK="$(mktemp -d)"
core_pid=""
trap 'if [ -n "$core_pid" ]; then kill "$core_pid" 2> /dev/null || true; fi; rm -rf "$WORK"' EXIT

UNITS=(fp_add fp_mul fp_div fp_cmp fp_from_f32 fp_to_f32 fp_nudge fp_ldexp rt_trav_unit rt_clip_unit
       rt_ray_setup rt_isect_unit rt_hit_out rt_leaf_exit rt_hit_merge)
# Units without E and M: one row each, default parameters.
PLAIN_UNITS=(rt_fifo rt_list_unit rt_thread_stack rt_mem_system rt_thread_fsm rt_perf_events)
# Units synthesized with --sram: their memories (rt_ram_1r1w: the caches'
# lines, the stacks, the hit records' u and v, the leaf-job queue) as SRAM
# macros, their bits in the SRAM column and not in the cells (sw/trade/area.h KeepsSram names
# the same units; AreaSramUnits.TheScriptTheModelAndTheTableAgree checks it).
SRAM_UNITS=" rt_mem_system rt_leaf_exit rt_hit_merge rt_list_unit rt_thread_stack "
# The preset formats: the one list in cmake/presets.cmake.
read -r -a FORMATS <<< "$(sed -n 's/^set(KDRT_PRESETS \(.*\))$/\1/p' "$(dirname "$0")/../cmake/presets.cmake")"

run_one() {  # run_one <unit> <name> <E> <M>: writes $WORK/<unit>_<name>.{log,row}; E "-": defaults
  local unit="$1" name="$2" e="$3" m="$4"
  local json="$WORK/${unit}_${name}.json" phys="$WORK/${unit}_${name}.phys.json"
  local sram=()
  if [[ "$SRAM_UNITS" == *" $unit "* ]]; then sram=(--sram); fi
  # synth-unit.sh says why it failed (the end of the Yosys log) on stderr.
  if ! "$SYNTH_UNIT" "${sram[@]}" "$unit" "$e" "$m" "$json" > "$WORK/${unit}_${name}.log" 2>&1; then
    echo "FAIL" > "$WORK/${unit}_${name}.row"
    return 0
  fi
  local em=()
  if [ "$e" != - ]; then em=("E=$e" "M=$m"); fi
  if ! nice -n 10 "$SYNTH_PHYS" "${sram[@]}" --json "$phys" "$unit" "${em[@]}" >> "$WORK/${unit}_${name}.log" 2>&1; then
    echo "FAIL" > "$WORK/${unit}_${name}.row"
    return 0
  fi
  local cells ffs depth bits area crit
  cells=$(sed -n 's/.*"cells": \([0-9]*\).*/\1/p' "$json")
  ffs=$(sed -n 's/.*"flip_flops": \([0-9]*\).*/\1/p' "$json")
  depth=$(sed -n 's/.*"depth": \([0-9]*\).*/\1/p' "$json")
  bits=$(sed -n 's/.*"sram_bits": \([0-9]*\).*/\1/p' "$json")
  area=$(sed -n 's/.*"area_um2": \([0-9]*\).*/\1/p' "$phys")
  crit=$(sed -n 's/.*"crit_ns": \([0-9.]*\).*/\1/p' "$phys")
  echo "$cells $ffs $depth ${bits:-0} $area $crit" > "$WORK/${unit}_${name}.row"
}
export -f run_one
SYNTH_UNIT="$ROOT/scripts/synth-unit.sh"
SYNTH_PHYS="$ROOT/scripts/synth-phys.sh"
export SYNTH_UNIT SYNTH_PHYS YOSYS WORK SRAM_UNITS

# The default core: in the background from the start (its largest units take
# the longest), one synthesis at a time beside the unit table's jobs.
CORE_DIR="${SYNTH_CORE_DIR:-$ROOT/build/synth-core/default}"
"$ROOT/scripts/synth-core.sh" --out "$CORE_DIR" --table --mem-gb "${CORE_MEM_GB:-10}" \
  --time-min "${CORE_TIME_MIN:-60}" > "$WORK/core.md" 2> "$WORK/core.log" &
core_pid=$!

jobs_list=()
for unit in "${UNITS[@]}"; do
  for fmt in "${FORMATS[@]}"; do
    IFS=: read -r name e m <<< "$fmt"
    jobs_list+=("$unit $name $e $m")
  done
done
for unit in "${PLAIN_UNITS[@]}"; do
  jobs_list+=("$unit default - -")
done
printf '%s\n' "${jobs_list[@]}" | xargs -P "$JOBS" -L 1 bash -c 'run_one "$@"' _

latency() {  # documented latency of <unit> for mantissa bits <m>
  case "$1" in
    fp_add) echo 4 ;;
    fp_mul) echo 3 ;;
    fp_div) echo $(($2 + 4)) ;;
    fp_cmp) echo 1 ;;
    fp_from_f32) echo 1 ;;
    fp_to_f32) echo 0 ;;
    fp_nudge) echo 0 ;;
    fp_ldexp) echo 0 ;;
    rt_trav_unit) echo 8 ;;
    rt_clip_unit) echo 11 ;;
    rt_ray_setup) echo $(($2 + 8)) ;;
    rt_isect_unit) echo $(($2 + 34)) ;;
    rt_hit_out) echo 1 ;;
    rt_leaf_exit) echo 0 ;;
    rt_hit_merge) echo 0 ;;
    rt_perf_events) echo 0 ;;
    rt_fifo) echo 1 ;;
    rt_thread_stack) echo 0 ;;
    *) echo - ;;
  esac
}

fail=0
{
  echo "| unit | preset | latency (cycles) | cells | flip-flops | logic depth (gates) | SRAM bits | area (um^2) | critical (ns) |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
  for unit in "${UNITS[@]}"; do
    for fmt in "${FORMATS[@]}"; do
      IFS=: read -r name e m <<< "$fmt"
      row=$(cat "$WORK/${unit}_${name}.row")
      if [ "$row" = FAIL ]; then
        echo "| $unit | $name | - | FAILED (latch or synthesis error) | | | | | |"
        fail=1
        continue
      fi
      read -r cells ffs depth bits area crit <<< "$row"
      echo "| $unit | $name | $(latency "$unit" "$m") | $cells | $ffs | $depth | $bits | $area | $crit |"
    done
  done
  for unit in "${PLAIN_UNITS[@]}"; do
    row=$(cat "$WORK/${unit}_default.row")
    if [ "$row" = FAIL ]; then
      echo "| $unit | defaults | - | FAILED (latch or synthesis error) | | | | | |"
      fail=1
      continue
    fi
    read -r cells ffs depth bits area crit <<< "$row"
    echo "| $unit | defaults | $(latency "$unit" 0) | $cells | $ffs | $depth | $bits | $area | $crit |"
  done
} > "$WORK/table.md"

cat "$WORK/table.md"
echo "synth: waiting for the default core (scripts/synth-core.sh, log in $CORE_DIR/logs)"
if ! wait "$core_pid"; then
  cat "$WORK/core.log"
  echo "synth: FAILED: the default core (scripts/synth-core.sh)"
  exit 1
fi
grep -E 'ESTIMATED|done in|cached' "$WORK/core.log" | sed 's/^/  /' || true
cat "$WORK/core.md"
{
  echo "<!-- Generated by scripts/synth.sh. Units: Yosys generic synth -flatten (cells,"
  echo "     flip-flops; depth from ltp -noff: gates on the longest register-to-register"
  echo "     path) and scripts/synth-phys.sh (OSU 0.18 um cells, 5 ns target: cell area,"
  echo "     critical path by OpenSTA, ideal ports, no wires); the units with memories"
  echo "     ($(echo $SRAM_UNITS | sed 's/ /, /g'))"
  echo "     with --sram: their memories are SRAM macros, counted in the SRAM bits column"
  echo "     and not in the cells or the area. Every unit at its module defaults; the"
  echo "     default core: below, scripts/synth-core.sh. -->"
  cat "$WORK/table.md"
  echo
  echo "## The default core"
  echo
  echo "Every unit rt_core instantiates at its default parameters, as rt_core gives them"
  echo "(scripts/synth-core.sh; docs/physical.md explains the columns):"
  echo
  cat "$WORK/core.md"
} > "$OUT_MD"

if [ "$fail" -ne 0 ]; then
  for f in "$WORK"/*.log; do
    if grep -qiE 'error|assert' "$f"; then echo "== $f"; grep -iE 'error|assert' "$f" | head -5; fi
  done
  echo "synth: FAILED"
  exit 1
fi
echo "synth: ok, no latches; table written to ${OUT_MD#$ROOT/}"
