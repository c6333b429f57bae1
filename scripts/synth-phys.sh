#!/usr/bin/env bash
# Physical cost of one unit in a real standard-cell library: Yosys maps the
# unit onto the OSU 0.18 um cells (qflow-tech-osu018) for a clock period, with
# fanout buffering and gate sizing, and OpenSTA times the netlist. Beside
# scripts/synth-unit.sh (the generic flow: cells, flip-flops, logic depth),
# with the same conventions: the RTL files, the parameters (NAME=VALUE, set by
# chparam on the top), --sram, the no-latch check and a JSON that appears
# complete or not at all. Writes
#   {"unit": .., "params": {..}, "library": "osu018", "area_um2": ..,
#    "cells": .., "flip_flops": .., "crit_ns": .., "crit_path": {"from": ..,
#    "to": ..}, "period_target_ns": .., "srams": [..]}
# area_um2: `stat -liberty` (cell area, no wiring); crit_ns: the data arrival
# time of OpenSTA's worst setup path (clock to Q of the launching flip-flop
# plus the logic, without the capturing flip-flop's setup time), between
# registers or ports, the ports ideal (input and output delays 0, no driving
# cell, no load, no wires); crit_path: its startpoint and endpoint, a
# register's name or a port's.
# Usage: scripts/synth-phys.sh [--period NS] [--json OUT.json] [--keep DIR]
#          [--sram] [--glue] UNIT [NAME=VALUE...]   (--help: this text)
#   --period NS  clock period and abc's delay target in ns (default 5)
#   --json OUT   write the JSON to OUT (beside it, then renamed) instead of
#                standard output
#   --keep DIR   keep the Yosys log, the netlist, the OpenSTA script and its
#                report in DIR
#   --sram       the arrays of rt_ram_1r1w (as in synth-unit.sh: the
#                caches' lines, the stacks) are kept as SRAM macros: cut out of the
#                netlist, their pins become ports of the timed netlist, and
#                "srams" lists them (name, words, width); their own area is
#                not in area_um2. A macro's data output arrives at its read
#                access time from scripts/sram_model.py (an input delay), so
#                a path through the logic it feeds carries the macro's
#                access; its inputs are ideal (no setup time)
#   --glue       UNIT's own logic only: its submodule instances are cut
#                out (their pins become ideal ports of the timed netlist),
#                e.g. rt_core's thread table without the units it feeds
#   --input-delay PORT=NS  the input port PORT (all its bits) arrives NS
#                after the clock (repeatable), e.g. with --glue an SRAM
#                instance's data output: u_ray_ram.rdata_o=7.424
#   NAME=VALUE   parameters of UNIT, e.g. E=8 M=23 (fp32), N=32
#   YOSYS=path, STA=path, LIBERTY=path: other tools or another Liberty file.
# On failure: exit status 1, one line saying what failed on stderr (then the
# end of the tool's log, if a tool failed), no JSON.
set -euo pipefail

usage() {
  sed -n '/^# Usage:/,/^# On failure/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
}
die() { echo "synth-phys: $*" >&2; exit 1; }
bad_usage() { echo "synth-phys: $*" >&2; echo "usage: $0 [--period NS] [--json OUT.json] [--keep DIR] [--sram] [--glue] UNIT [NAME=VALUE...]   (--help)" >&2; exit 2; }

period=5 out="" keep="" sram=0 glue=0 delays=()
while [ "$#" -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --period) [ "$#" -ge 2 ] || bad_usage "--period needs a value in ns"; period="$2"; shift 2 ;;
    --period=*) period="${1#*=}"; shift ;;
    --json) [ "$#" -ge 2 ] || bad_usage "--json needs a file name"; out="$2"; shift 2 ;;
    --json=*) out="${1#*=}"; shift ;;
    --keep) [ "$#" -ge 2 ] || bad_usage "--keep needs a directory"; keep="$2"; shift 2 ;;
    --keep=*) keep="${1#*=}"; shift ;;
    --sram) sram=1; shift ;;
    --glue) glue=1; shift ;;
    --input-delay) [ "$#" -ge 2 ] || bad_usage "--input-delay needs PORT=NS"; delays+=("$2"); shift 2 ;;
    --) shift; break ;;
    -*) bad_usage "$1: unknown option" ;;
    *) break ;;
  esac
done
[ "$#" -ge 1 ] || bad_usage "no unit given"
unit="$1"
shift
if ! [[ "$unit" =~ ^[A-Za-z_][A-Za-z0-9_]*$ ]]; then bad_usage "$unit: not a module name"; fi
if ! [[ "$period" =~ ^[0-9]+(\.[0-9]+)?$ ]] || ! awk -v p="$period" 'BEGIN { exit !(p > 0) }'; then
  bad_usage "--period $period: expected a positive number of ns, e.g. 5 or 2.5"
fi
period_ps=$(awk -v p="$period" 'BEGIN { printf "%d", p * 1000 + 0.5 }')
for d in ${delays[@]+"${delays[@]}"}; do
  if ! [[ "$d" =~ ^[A-Za-z_][A-Za-z0-9_.]*=[0-9]+(\.[0-9]+)?$ ]]; then
    bad_usage "--input-delay $d: expected PORT=NS, e.g. u_ray_ram.rdata_o=7.424"
  fi
done
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RTL="$ROOT/rtl"
# shellcheck source=synth-common.sh
. "$ROOT/scripts/synth-common.sh"
synth_parse_params synth-phys "$@"
chp_set="$SYNTH_CHP_SET" params_json="$SYNTH_PARAMS_JSON"
YOSYS="${YOSYS:-yosys}"
STA="${STA:-sta}"
LIB="${LIBERTY:-/usr/share/qflow/tech/osu018/osu018_stdcells.lib}"
[ -r "$LIB" ] || die "$LIB: Liberty file not found (apt-get install qflow-tech-osu018, or set LIBERTY=path)"
command -v "$YOSYS" > /dev/null || die "$YOSYS: command not found (apt-get install yosys, or set YOSYS=path)"
command -v "$STA" > /dev/null || die "$STA: command not found (OpenSTA: apt-get install opensta, or set STA=path)"
if ! grep -qE "^[[:space:]]*module[[:space:]]+$unit\b" "$RTL"/*.sv; then
  die "$unit: unknown unit (no module $unit in rtl/*.sv)"
fi
# The library's name ("osu018" for osu018_stdcells) and its flip-flops (the
# cells with an ff group), for the count.
library=$(sed -n 's/^[[:space:]]*library[[:space:]]*([[:space:]]*"\{0,1\}\([A-Za-z0-9_]*\).*/\1/p' "$LIB" | head -n 1)
library="${library%_stdcells}"
ff_cells=$(awk '
  /^[[:space:]]*cell[[:space:]]*\(/ { c = $0; sub(/.*\([[:space:]]*"?/, "", c); sub(/"?[[:space:]]*\).*/, "", c) }
  /^[[:space:]]*ff[[:space:]]*\(/ && c != "" { print c; c = "" }
' "$LIB" | tr '\n' ' ')
[ -n "$library" ] && [ -n "$ff_cells" ] || die "$LIB: no library name or no flip-flop cell in it (not a Liberty file?)"

WORK="$(mktemp -d)"
tmp_json=""
trap 'rm -rf "$WORK"; if [ -n "$tmp_json" ]; then rm -f "$tmp_json"; fi' EXIT
ylog="$WORK/yosys.log"
net="$WORK/$unit.v"

# abc's delay target is the period; -constr makes abc's liberty script end in
# `buffer; upsize; dnsize` (fanout buffering and gate sizing for that target).
# Every input of the mapped logic (ports and flip-flop outputs) is taken as
# driven by a BUFX2, every output (ports and flip-flop inputs) as loaded by
# 9 fF, about one flip-flop's D pin.
printf 'set_driving_cell BUFX2\nset_load 9\n' > "$WORK/abc.constr"
# With --sram, synth-unit.sh's flow: the line arrays are left out of
# memory_map; here they are then cut out (their data outputs become input
# ports, their address, data and enable inputs output ports) before mapping.
if [ "$sram" = 1 ]; then
  lines="$SYNTH_SRAM_LINES"
  flow="$(synth_sram_flow "$unit")
    select -assert-none t:\$*latch* t:\$_DLATCH* t:\$_SR_* t:\$sr
    select -assert-none t:\$mem_v2 $lines %d
    tee -q -o $WORK/unit.mem dump $lines
    expose -cut $lines %co:+[RD_DATA] $lines %d
    expose $lines %ci:+[RD_ADDR,RD_EN,RD_ARST,RD_SRST,WR_ADDR,WR_DATA,WR_EN] $lines %d w:* %i
    delete $lines
    opt -fast"
else
  flow="synth -flatten -top $unit
    select -assert-none t:\$*latch* t:\$_DLATCH* t:\$_SR_* t:\$sr"
fi
# The top keeps its name (a parameterized top is elaborated as $paramod...).
# With --glue, the submodule instances become ports (expose -evert), and the
# submodules are then no longer part of the design.
prep="hierarchy -top $unit
    rename -top $unit"
if [ "$glue" = 1 ]; then
  prep="$prep
    select -set subs $unit/c:* $unit/t:\$* %d $unit/t:\$paramod* %u
    expose -evert @subs
    hierarchy -top $unit"
fi
if ! "$YOSYS" -q -l "$ylog" -p "
    $(synth_read "$RTL" "$unit" "$chp_set")
    $prep
    $flow
    dfflibmap -liberty $LIB
    abc -liberty $LIB -D $period_ps -constr $WORK/abc.constr
    opt_clean
    insbuf -buf BUFX2 A Y
    opt_clean
    select -assert-none t:\$*
    read_liberty -lib $LIB
    rename -wire -suffix _reg t:$(echo "$ff_cells" | sed 's/ *$//; s/ / t:/g')
    tee -q -o $WORK/unit.stat stat -liberty $LIB
    write_verilog -noattr -noexpr $net
  " > /dev/null 2>&1; then
  if grep -q 'Assertion failed: selection is not empty: t:\$\*latch\*' "$ylog" 2> /dev/null; then
    echo "synth-phys: $unit: a latch is inferred; the end of the Yosys log:" >&2
  elif grep -q 'Assertion failed: selection is not empty: t:\$mem_v2' "$ylog" 2> /dev/null; then
    echo "synth-phys: $unit: --sram: a memory other than the line arrays is left unmapped; the end of the Yosys log:" >&2
  elif grep -q 'Assertion failed: selection is not empty: t:\$\*' "$ylog" 2> /dev/null; then
    echo "synth-phys: $unit: cells left that $LIB has no cell for (a flip-flop kind?); the end of the Yosys log:" >&2
  else
    echo "synth-phys: $unit: Yosys failed (synthesis error); the end of the Yosys log:" >&2
  fi
  tail -n 20 "$ylog" >&2 2> /dev/null || true
  exit 1
fi

# A port named after a generate block's instance (g_bank[0].u_ram.rdata_q.i)
# is an escaped identifier with brackets, which OpenSTA 2019 cannot take in
# its delay commands: such ports are renamed with _ for [ and ].
python3 - "$net" << 'PY'
import re, sys
path = sys.argv[1]
text = open(path).read()
ports = set(re.findall(r"^\s*(?:input|output|inout)\s+(?:\[[^\]]*\]\s*)?(\\\S*[\[\]]\S*)\s*;", text, re.M))
if ports:
    table = str.maketrans("[]", "__")
    text = re.sub(r"\\\S+", lambda m: m.group(0).translate(table) if m.group(0) in ports else m.group(0), text)
    open(path, "w").write(text)
PY

cells=$({ grep -m1 -E 'Number of cells:' "$WORK/unit.stat" || true; } | awk '{print $NF}')
area=$({ grep -m1 -E 'Chip area for module' "$WORK/unit.stat" || true; } | awk '{printf "%.0f", $NF}')
ffs=$(awk -v ff="$ff_cells" '
  BEGIN { n = split(ff, a, " "); for (i = 1; i <= n; i++) is_ff[a[i]] = 1 }
  /Chip area/ { exit }
  NF == 2 && ($1 in is_ff) { s += $2 }
  END { print s + 0 }' "$WORK/unit.stat")
# A unit with no logic under synthesis (a simulation-only checker): no cells,
# no area, no path; crit_ns 0 and the path's ends "-".
empty=0
if [ "${cells:-}" = 0 ]; then area=0 empty=1; fi
[ -n "$cells" ] && [ -n "$area" ] || die "$unit: no cell count or area in the Yosys output"

srams_json=""
if [ "$sram" = 1 ]; then
  # Each kept array: its name, words and width (and a check that it is what
  # an SRAM macro can be).
  srams=$(synth_sram_list synth-phys "$unit" "$WORK/unit.mem")
  srams_json=$(synth_sram_json "$srams")
  # Each macro's data output wires (its RD_DATA; expose -cut made them input
  # ports named <wire>.i) arrive at the macro's access time.
  outputs=$(synth_sram_outputs "$WORK/unit.mem")
  while read -r mem words width; do
    [ -n "$mem" ] || continue
    ports=$(echo "$outputs" | awk -v m="$mem" '$1 == m { print $2 }')
    [ -n "$ports" ] || die "$unit: --sram: the read data of $mem drives no named wire (its access time cannot be put on a port)"
    access=$(python3 "$ROOT/scripts/sram_model.py" "$words" "$width" | sed -n 's/.*"access_ns": \([0-9.]*\).*/\1/p')
    [ -n "$access" ] || die "$unit: no access time from scripts/sram_model.py for $mem ($words x $width)"
    for port in $ports; do delays+=("$port.i=$access"); done
  done <<< "$srams"
fi

if [ "$empty" = 1 ]; then
  crit=0 from=- to=-
else
# OpenSTA: the clock on clk_i (a virtual clock for a unit without one), every
# other port constrained to it with delay 0.
cat > "$WORK/sta.tcl" << EOF
read_liberty $LIB
read_verilog $net
link_design $unit
if {[llength [get_ports -quiet clk_i]] > 0} {
  create_clock -name clk -period $period [get_ports clk_i]
  set inputs [delete_from_list [all_inputs] [get_ports clk_i]]
} else {
  create_clock -name clk -period $period
  set inputs [all_inputs]
}
if {[llength \$inputs] > 0} { set_input_delay 0 -clock clk \$inputs }
if {[llength [all_outputs]] > 0} { set_output_delay 0 -clock clk [all_outputs] }
$(for d in ${delays[@]+"${delays[@]}"}; do
  # Brackets in a port's name became _ (above).
  esc=$(printf '%s' "${d%=*}" | tr '[]' '__')
  printf 'set p [get_ports -quiet {%s %s[*]}]\n' "$esc" "$esc"
  printf 'if {[llength $p] == 0} { puts "synth-phys: no input port %s"; set missing 1 }\n' "$esc"
  printf 'set_input_delay %s -clock clk $p\n' "${d#*=}"
done)
report_checks -path_delay max -path_group clk -digits 3 > $WORK/timing.rpt
if {![info exists missing]} { puts "synth-phys: sta done" }
EOF
if ! "$STA" -no_init -no_splash -exit "$WORK/sta.tcl" > "$WORK/sta.log" 2>&1 \
    || ! grep -q '^synth-phys: sta done' "$WORK/sta.log" || grep -q '^Error' "$WORK/sta.log"; then
  if grep -q '^synth-phys: no input port' "$WORK/sta.log"; then
    die "$unit: --input-delay: $(grep -m1 '^synth-phys: no input port' "$WORK/sta.log" | sed 's/^synth-phys: //') in the netlist"
  fi
  echo "synth-phys: $unit: OpenSTA failed; the end of its log:" >&2
  tail -n 20 "$WORK/sta.log" >&2
  exit 1
fi
# The worst path: its startpoint, endpoint and data arrival time. A register
# is named after the flip-flop's output wire (the cell is "<wire>_reg").
read -r from to crit <<< "$(awk '
  /^Startpoint: / && from == "" { from = $2 }
  /^Endpoint: / && to == "" { to = $2 }
  /data arrival time/ && crit == "" { crit = $1 }
  END { print from, to, crit }' "$WORK/timing.rpt")"
if [ -z "${crit:-}" ] || ! [[ "$crit" =~ ^-?[0-9.]+$ ]]; then
  die "$unit: no constrained path in the OpenSTA report (a unit without registers or ports?)"
fi
name_of() { local n="${1#\\}"; echo "${n%_reg}"; }
from=$(name_of "$from") to=$(name_of "$to")

fi
json=$(printf '{"unit": "%s", "params": {%s}, "library": "%s", "area_um2": %s, "cells": %s, "flip_flops": %s, "crit_ns": %s, "crit_path": {"from": "%s", "to": "%s"}, "period_target_ns": %s, "srams": [%s]}' \
  "$unit" "$params_json" "$library" "$area" "$cells" "$ffs" "$crit" "$from" "$to" "$period" "$srams_json")
if [ -n "$keep" ]; then
  mkdir -p "$keep"
  cp "$ylog" "$net" "$WORK/unit.stat" "$WORK/abc.constr" "$WORK/sta.log" "$WORK/timing.rpt" "$keep/"
  if [ -e "$WORK/unit.mem" ]; then cp "$WORK/unit.mem" "$keep/"; fi
  # The kept OpenSTA script reads the kept netlist: `sta DIR/sta.tcl` redoes it.
  keep_abs="$(cd "$keep" && pwd)"
  sed "s|$WORK|$keep_abs|g" "$WORK/sta.tcl" > "$keep/sta.tcl"
fi
if [ -n "$out" ]; then
  mkdir -p "$(dirname "$out")"
  tmp_json="$(mktemp "$out.tmp.XXXXXX")"
  echo "$json" > "$tmp_json"
  mv -f "$tmp_json" "$out"
  tmp_json=""
else
  echo "$json"
fi
