#!/usr/bin/env bash
# Generic Yosys synthesis of one unit: the one definition of how a unit is
# synthesized (scripts/synth.sh runs it for every row of docs/synth-table.md;
# `kdrt trade` runs it for the formats that have no row). Fails if a latch is
# inferred. Writes
#   {"unit": ..., "E": .., "M": .., "cells": .., "flip_flops": .., "depth": ..}
# to OUT_JSON (E and M null for "-"); depth = gates on the longest path between
# registers/ports (`ltp -noff`). OUT_JSON appears complete or not at all
# (written beside it, then renamed), so concurrent readers never see half a
# file. On failure: exit status 1, the end of the Yosys log on stderr, no
# OUT_JSON.
# Usage: scripts/synth-unit.sh UNIT E M OUT_JSON [NAME=VALUE...]   (E M "- -":
#        the unit's default parameters; NAME=VALUE: more parameters, e.g.
#        TravE=8 TravM=23, listed in the JSON's "params"; YOSYS=path to use
#        another yosys)
set -euo pipefail

if [ "$#" -lt 4 ]; then
  echo "usage: $0 UNIT E M OUT_JSON [NAME=VALUE...]   (E M: '- -' for the unit's defaults)" >&2
  exit 2
fi
unit="$1" e="$2" m="$3" out="$4"
shift 4
extra_set="" extra_json=""
for kv in "$@"; do
  if ! [[ "$kv" =~ ^[A-Za-z][A-Za-z0-9]*=[0-9]+$ ]]; then
    echo "$0: $kv: expected NAME=VALUE (a parameter and a number)" >&2
    exit 2
  fi
  extra_set="$extra_set -set ${kv%%=*} ${kv#*=}"
  extra_json="$extra_json${extra_json:+, }\"${kv%%=*}\": ${kv#*=}"
done
if { [ "$e" = - ] && [ "$m" != - ]; } || { [ "$e" != - ] && [ "$m" = - ]; }; then
  echo "$0: E and M must both be numbers or both be '-'" >&2
  exit 2
fi

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RTL="$ROOT/rtl"
YOSYS="${YOSYS:-yosys}"
if ! command -v "$YOSYS" > /dev/null; then
  echo "synth-unit: $YOSYS: command not found (install Yosys, or set YOSYS=path)" >&2
  exit 1
fi
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
log="$WORK/yosys.log"

chp=""
if [ "$e" != - ]; then chp="chparam -set E $e -set M $m$extra_set $unit";
elif [ -n "$extra_set" ]; then chp="chparam$extra_set $unit"; fi
if ! "$YOSYS" -q -l "$log" -p "
    read_verilog -sv $RTL/kdrt_fp_pkg.sv $RTL/kdrt_pkg.sv $(ls $RTL/*.sv | grep -v _pkg.sv | tr '\n' ' ')
    $chp
    synth -flatten -top $unit
    select -assert-none t:\$*latch* t:\$_DLATCH* t:\$_SR_* t:\$sr
    tee -o $WORK/unit.stat stat
    tee -o $WORK/unit.ltp ltp -noff
  " > /dev/null 2>&1; then
  echo "synth-unit: $unit E=$e M=$m failed (synthesis error or latch); the end of the Yosys log:" >&2
  tail -n 20 "$log" >&2 2> /dev/null || true
  exit 1
fi

# (grep finds nothing for a unit without flip-flops: not an error.)
cells=$({ grep -m1 -E 'Number of cells:' "$WORK/unit.stat" || true; } | awk '{print $NF}')
ffs=$({ grep -E '\$_[A-Z]*DFF[A-Z0-9]*_' "$WORK/unit.stat" || true; } | awk '{s += $NF} END {print s + 0}')
depth=$({ grep -m1 -o 'length=[0-9]*' "$WORK/unit.ltp" || true; } | cut -d= -f2)
if [ -z "$cells" ] || [ -z "$depth" ]; then
  echo "synth-unit: $unit E=$e M=$m: no cell count or logic depth in the Yosys output" >&2
  tail -n 20 "$log" >&2 2> /dev/null || true
  exit 1
fi

json_e=null json_m=null
if [ "$e" != - ]; then json_e="$e" json_m="$m"; fi
mkdir -p "$(dirname "$out")"
tmp="$(mktemp "$out.tmp.XXXXXX")"
params=""
if [ -n "$extra_json" ]; then params=", \"params\": {$extra_json}"; fi
printf '{"unit": "%s", "E": %s, "M": %s, "cells": %s, "flip_flops": %s, "depth": %s%s}\n' \
  "$unit" "$json_e" "$json_m" "$cells" "$ffs" "$depth" "$params" > "$tmp"
mv -f "$tmp" "$out"
