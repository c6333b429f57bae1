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
# Usage: scripts/synth-unit.sh [--sram] UNIT E M OUT_JSON [NAME=VALUE...]
#        (E M "- -": the unit's default parameters; NAME=VALUE: more
#        parameters, e.g. TravE=8 TravM=23, listed in the JSON's "params";
#        YOSYS=path to use another yosys; LTP_OUT=path to keep Yosys' longest
#        path, the nets from start to end, as `ltp -noff` prints it)
# --sram: rt_ram_1r1w's arrays (the caches' lines, the stacks; one write
#        port, one read port registered inside the array, as an SRAM macro
#        reads) are
#        kept as memories instead of being built from flip-flops and
#        multiplexers; "cells", "flip_flops" and "depth" are then the logic
#        around them, and the JSON adds "sram_bits" and "srams" (name, words,
#        width of each). Every other memory (tags, thread tables: read in
#        the cycle they are addressed) is still flip-flops. The macros' own area is not
#        a Yosys figure (docs/trade.md, "Area").
set -euo pipefail

sram=0
if [ "${1:-}" = --sram ]; then
  sram=1
  shift
fi
if [ "$#" -lt 4 ]; then
  echo "usage: $0 [--sram] UNIT E M OUT_JSON [NAME=VALUE...]   (E M: '- -' for the unit's defaults)" >&2
  exit 2
fi
unit="$1" e="$2" m="$3" out="$4"
shift 4
if { [ "$e" = - ] && [ "$m" != - ]; } || { [ "$e" != - ] && [ "$m" = - ]; }; then
  echo "$0: E and M must both be numbers or both be '-'" >&2
  exit 2
fi

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
RTL="$ROOT/rtl"
# shellcheck source=synth-common.sh
. "$ROOT/scripts/synth-common.sh"
synth_parse_params synth-unit "$@"
extra_set="$SYNTH_CHP_SET" extra_json="$SYNTH_PARAMS_JSON"
YOSYS="${YOSYS:-yosys}"
if ! command -v "$YOSYS" > /dev/null; then
  echo "synth-unit: $YOSYS: command not found (install Yosys, or set YOSYS=path)" >&2
  exit 1
fi
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
log="$WORK/yosys.log"

chp_set="$extra_set"
if [ "$e" != - ]; then chp_set=" -set E $e -set M $m$extra_set"; fi
# The synthesis: Yosys' generic `synth`, or with --sram the same script with
# the line arrays left out of its memory_map step (Yosys 0.23's fine stage
# otherwise: opt, techmap, abc).
if [ "$sram" = 1 ]; then
  flow="$(synth_sram_flow "$unit")
    abc -fast
    opt -fast
    hierarchy -check
    check
    tee -q -o $WORK/unit.mem dump t:\$mem_v2"
else
  flow="synth -flatten -top $unit"
fi
if ! "$YOSYS" -q -l "$log" -p "
    $(synth_read "$RTL" "$unit" "$chp_set")
    $flow
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
sram_json=""
if [ "$sram" = 1 ]; then
  # Each kept array: its name, words and width (and a check that it is what
  # an SRAM macro can be).
  srams=$(synth_sram_list synth-unit "$unit" "$WORK/unit.mem")
  macros=$(echo "$srams" | awk 'NF { n++ } END { print n + 0 }')
  bits=$(echo "$srams" | awk 'NF { s += $2 * $3 } END { print s + 0 }')
  list=$(synth_sram_json "$srams")
  cells=$((cells - macros))
  sram_json=", \"sram_bits\": $bits, \"srams\": [$list]"
fi
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
printf '{"unit": "%s", "E": %s, "M": %s, "cells": %s, "flip_flops": %s, "depth": %s%s%s}\n' \
  "$unit" "$json_e" "$json_m" "$cells" "$ffs" "$depth" "$params" "$sram_json" > "$tmp"
mv -f "$tmp" "$out"
if [ -n "${LTP_OUT:-}" ]; then cp "$WORK/unit.ltp" "$LTP_OUT"; fi
