# Shared by scripts/synth-unit.sh, scripts/synth-phys.sh and
# scripts/synth-core.sh (sourced, not run): the RTL files in the order Yosys
# reads them, the NAME=VALUE parameters, and the SRAM macros (--sram).

# synth_rtl_files RTL_DIR: the RTL files, the packages first.
synth_rtl_files() {
  local rtl="$1"
  echo "$rtl/kdrt_fp_pkg.sv $rtl/kdrt_pkg.sv $(ls "$rtl"/*.sv | grep -v _pkg.sv | tr '\n' ' ')"
}

# synth_parse_params PROG NAME=VALUE...: checks each argument (a parameter and
# a number; exit 2 with a message otherwise) and sets
#   SYNTH_CHP_SET      " -set NAME VALUE ..." for chparam
#   SYNTH_PARAMS_JSON  "\"NAME\": VALUE, ..." for the JSON's "params"
synth_parse_params() {
  local prog="$1" kv
  shift
  SYNTH_CHP_SET="" SYNTH_PARAMS_JSON=""
  for kv in "$@"; do
    if ! [[ "$kv" =~ ^[A-Za-z][A-Za-z0-9]*=[0-9]+$ ]]; then
      echo "$prog: $kv: expected NAME=VALUE (a parameter and a number)" >&2
      exit 2
    fi
    SYNTH_CHP_SET="$SYNTH_CHP_SET -set ${kv%%=*} ${kv#*=}"
    SYNTH_PARAMS_JSON="$SYNTH_PARAMS_JSON${SYNTH_PARAMS_JSON:+, }\"${kv%%=*}\": ${kv#*=}"
  done
}

# The arrays kept as SRAM macros with --sram: the memories of rt_ram_1r1w
# (sram_q: the caches' lines, the stacks, the miss registers' buffers; banked
# by rt_ram_banked), each with one write port and one read port registered
# inside the array, as an SRAM compiler's macro reads. Every other memory
# (tags, thread tables: read in the cycle they are addressed) is built from
# flip-flops.
SYNTH_SRAM_LINES='t:$mem_v2 n:*sram_q %i'

# synth_sram_flow UNIT: Yosys' `synth -flatten` up to its fine stage with the
# line arrays left out of memory_map (the rest of Yosys 0.23's fine stage:
# opt, techmap); the caller maps the logic and says what becomes of the arrays.
synth_sram_flow() {
  echo "synth -flatten -top $1 -run begin:fine
    opt -fast -full
    memory_map $SYNTH_SRAM_LINES %n
    opt -full
    techmap
    opt -fast"
}

# synth_sram_list PROG UNIT MEM_DUMP: reads the `dump` of the kept arrays and
# prints one line per macro, "name words width"; exit 1 if one is not what an
# SRAM macro can be (a read port not registered, or more than one write port).
synth_sram_list() {
  local prog="$1" unit="$2" dump="$3" srams
  srams=$(awk '
    /^ *cell \$mem_v2 / { name = ""; words = 0; width = 0; rclk = ""; wr = 0 }
    /parameter .MEMID / { name = $3; gsub(/["\\]/, "", name) }
    /parameter .SIZE / { words = $3 }
    /parameter .WIDTH / { width = $3 }
    /parameter .RD_CLK_ENABLE / { rclk = $3 }
    /parameter .WR_PORTS / { wr = $3 }
    /^ *end$/ && name != "" {
      sync = (rclk ~ /^[0-9]+.[1]+$/) && wr == 1
      printf "%s %d %d %d\n", name, words, width, sync; name = "" }
  ' "$dump")
  if echo "$srams" | awk 'NF && $4 != 1 { bad = 1 } END { exit !bad }'; then
    echo "$prog: $unit: a line array is not an SRAM macro (an unregistered read or more than one write port): $(echo "$srams" | tr '\n' ';')" >&2
    exit 1
  fi
  echo "$srams" | awk 'NF { print $1, $2, $3 }'
}

# synth_sram_outputs MEM_DUMP: one line per kept array, "name wire" for each
# wire its read data drives (the RD_DATA connection, slices dropped).
synth_sram_outputs() {
  awk '
    /^ *cell \$mem_v2 / { name = "" }
    /parameter .MEMID / { name = $3; gsub(/["\\]/, "", name) }
    /^ *connect .RD_DATA / && name != "" {
      for (i = 3; i <= NF; i++) {
        if ($i !~ /^\\/) continue
        w = substr($i, 2)
        if (!((name, w) in seen)) { seen[name, w] = 1; print name, w }
      }
    }
  ' "$1"
}

# synth_sram_json LIST: the "srams" entries (name, words, width) of a
# synth_sram_list output.
synth_sram_json() {
  echo "$1" | awk 'NF { printf "%s{\"name\": \"%s\", \"words\": %d, \"width\": %d}", sep, $1, $2, $3; sep = ", " }'
}

# synth_read RTL_DIR UNIT CHP_SET: the Yosys commands that read the RTL and
# set UNIT's parameters (CHP_SET: " -set NAME VALUE...", for chparam).
synth_read() {
  echo "read_verilog -sv $(synth_rtl_files "$1")"
  if [ -n "$3" ]; then echo "chparam$3 $2"; fi
}
