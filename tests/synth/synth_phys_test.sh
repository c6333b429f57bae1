#!/usr/bin/env bash
# scripts/synth-phys.sh on a small unit: rt_rr_arb at N=8 gives a JSON with a
# positive area and critical path, N=32 a larger area; a Liberty file that is
# not there gives exit status 1, the reason, and no JSON. A memory kept as an
# SRAM macro (--sram) delivers its data at the model's access time: the
# critical path starts at it and is at least that long; --input-delay does
# the same for a named port, and a port that is not there is refused.
# Usage: synth_phys_test.sh SOURCE_DIR
set -euo pipefail
src="$1"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
field() { sed -n "s/.*\"$2\": \([0-9.]*\).*/\1/p" "$1"; }

"$src/scripts/synth-phys.sh" --json "$work/n8.json" rt_rr_arb N=8
"$src/scripts/synth-phys.sh" --json "$work/n32.json" rt_rr_arb N=32
for f in n8 n32; do
  grep -q '"unit": "rt_rr_arb"' "$work/$f.json" || fail "$f: no unit in $(cat "$work/$f.json")"
  grep -q '"library": "osu018"' "$work/$f.json" || fail "$f: not the osu018 library"
  area=$(field "$work/$f.json" area_um2) crit=$(field "$work/$f.json" crit_ns)
  awk -v a="$area" -v c="$crit" 'BEGIN { exit !(a > 0 && c > 0) }' || fail "$f: area '$area', crit_ns '$crit'"
done
a8=$(field "$work/n8.json" area_um2) a32=$(field "$work/n32.json" area_um2)
[ "$a32" -gt "$a8" ] || fail "N=32 area $a32 um2 not above N=8's $a8 um2"
ff8=$(field "$work/n8.json" flip_flops) ff32=$(field "$work/n32.json" flip_flops)
[ "$ff32" -gt "$ff8" ] || fail "N=32 has $ff32 flip-flops, N=8 $ff8"

rc=0
LIBERTY="$work/none.lib" "$src/scripts/synth-phys.sh" --json "$work/bad.json" rt_rr_arb N=8 2> "$work/err" || rc=$?
[ "$rc" = 1 ] || fail "a missing Liberty file: exit status $rc, expected 1"
grep -q "none.lib: Liberty file not found" "$work/err" || fail "a missing Liberty file: message '$(cat "$work/err")'"
[ ! -e "$work/bad.json" ] || fail "a missing Liberty file left a JSON"
ls "$work" | grep -q 'bad.json' && fail "a missing Liberty file left $(ls "$work")"

rc=0
"$src/scripts/synth-phys.sh" rt_rr_arb N=eight 2> "$work/err" || rc=$?
[ "$rc" = 2 ] || fail "N=eight: exit status $rc, expected 2"
grep -q "N=eight: expected NAME=VALUE" "$work/err" || fail "N=eight: message '$(cat "$work/err")'"
"$src/scripts/synth-phys.sh" --sram --json "$work/ram.json" rt_ram_1r1w Words=256 Width=16
access=$(python3 "$src/scripts/sram_model.py" 256 16 | sed -n 's/.*"access_ns": \([0-9.]*\).*/\1/p')
crit=$(field "$work/ram.json" crit_ns)
grep -q '"from": "rdata_q.i\[' "$work/ram.json" || fail "--sram: the path does not start at the macro: $(cat "$work/ram.json")"
awk -v c="$crit" -v a="$access" 'BEGIN { exit !(c >= a) }' || fail "--sram: crit_ns $crit below the macro's access $access"
"$src/scripts/synth-phys.sh" --input-delay req_i=3.5 --json "$work/d.json" rt_rr_arb N=8
crit=$(field "$work/d.json" crit_ns)
awk -v c="$crit" 'BEGIN { exit !(c >= 3.5) }' || fail "--input-delay 3.5: crit_ns $crit"
rc=0
"$src/scripts/synth-phys.sh" --input-delay no_such_port=1 rt_rr_arb N=8 2> "$work/err" || rc=$?
[ "$rc" = 1 ] || fail "--input-delay of a missing port: exit status $rc, expected 1"
grep -q "no input port no_such_port" "$work/err" || fail "--input-delay of a missing port: message '$(cat "$work/err")'"
rc=0
"$src/scripts/synth-phys.sh" --input-delay req_i rt_rr_arb N=8 2> "$work/err" || rc=$?
[ "$rc" = 2 ] || fail "--input-delay req_i: exit status $rc, expected 2"
echo "synth_phys_test: ok (N=8: $a8 um2, N=32: $a32 um2)"
