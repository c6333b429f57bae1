#!/usr/bin/env bash
# Re-measures the tables that depend on the default core into OUT/ (one
# file per step, and `times` with each step's seconds) and writes them into
# docs/results.md and the README's headline tables (scripts/results_md.py:
# the blocks between <!-- results:NAME begin/end --> markers; the text
# around them stays): what a change of the default (core_params.def, the
# frame's ray order) must be followed by. The fast model does the cycle
# tables (it is cycle-exact against the RTL); the RTL runs the balls runs,
# `kdrt trade` and the sweep example.
#   scripts/remeasure.sh [--timed-only | --no-timed] OUT [KDRT]
#   scripts/remeasure.sh --write-only OUT
# --timed-only: only the fast-versus-RTL speed sweeps, which
#   must run alone on an idle machine, one point at a time;
# --no-timed: everything else, two steps at a time (51 minutes on 2 cores
#   with the 128-thread default core, most of it kdrt trade's RTL runs:
#   efficiency at 128x128 and 1024x1024, secondary rays, scaling,
#   packed images at 10k-1M, the wider traversal, the latency-200 sweep,
#   kdrt trade, the sweep example);
# --write-only: measure nothing, write the docs from OUT's step outputs.
# The docs are written only when every step succeeded; a block whose step
# outputs OUT lacks keeps its text and is named on stderr.
set -euo pipefail
mode=all
case "${1:-}" in
  --timed-only) mode=timed; shift ;;
  --no-timed) mode=untimed; shift ;;
  --write-only) mode=write; shift ;;
esac
if [ $# -lt 1 ] || [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -lt 1 ] && exit 2 || exit 0
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
write_docs() {
  python3 "$root/scripts/results_md.py" "$1" --results "$root/docs/results.md" --readme "$root/README.md"
}
if [ "$mode" = write ]; then
  [ -d "$1" ] || { echo "remeasure: $1: no such directory" >&2; exit 1; }
  write_docs "$1"
  exit
fi
out=$1
kdrt=${2:-$root/build/bin/kdrt}
[ -x "$kdrt" ] || { echo "remeasure: no kdrt at $kdrt (build first: make build)" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
cd "$root"

gen18=""
for n in 10000 100000 1000000; do
  for s in room balls rings tetra tree gears; do gen18+=" gen:$s:$n"; done
done
fast=(--model fast --timeout 50000000)

step() {  # step NAME COMMAND...: runs it, logs to OUT/NAME.err, times it; a failure is noted, not fatal
  local name=$1 start
  shift
  start=$(date +%s)
  echo "remeasure: $name" >&2
  if ! "$@" 2> "$out/$name.err"; then
    echo "remeasure: $name FAILED (see $out/$name.err)" >&2
    echo "$name FAILED" >> "$out/times"
    return 0
  fi
  echo "$name $(($(date +%s) - start)) s" >> "$out/times"
}

lane1() {
  # shellcheck disable=SC2086
  step eff128 env JSONL="$out/eff128.jsonl" scripts/efficiency.sh "$kdrt" 128x128 "20 200" $gen18 -- "${fast[@]}" \
    > "$out/eff128.md"
  # shellcheck disable=SC2086
  step eff1024 env JSONL="$out/eff1024.jsonl" scripts/efficiency.sh "$kdrt" 1024x1024 "20 200" $gen18 -- "${fast[@]}" \
    > "$out/eff1024.md"
  step packed1m scripts/packed-images.sh "$kdrt" 128x128 gen:balls:1000000 gen:rings:1000000 gen:tetra:1000000 \
    gen:room:1000000 -- "${fast[@]}" > "$out/packed1m.md"
  step trav1m scripts/packed-images.sh "$kdrt" 128x128 gen:balls:1000000 gen:tetra:1000000 gen:room:1000000 -- \
    "${fast[@]}" --trav-format fp32 > "$out/trav1m.md"
  step lat200 "$kdrt" sweep docs/sweep-latency-200.yaml -o "$out/lat200" --jobs 1 > /dev/null
}

lane2() {
  local n s
  for n in 1000 10000 100000; do
    step "balls$n" "$kdrt" sim "gen:balls:$n" --res 128x128 --model both -q -o "$out/balls$n.png" \
      --json "$out/balls$n.json"
  done
  for s in room balls rings tetra tree gears; do
    step "shade_$s" "$kdrt" sim "gen:$s:10000" --res 128x128 --shade --ao 2 --bounce "${fast[@]}" -q \
      -o "$out/shade_$s.png" --json "$out/shade_$s.json"
  done
  step scaling scripts/scaling.sh "$kdrt" 128x128 "1 2 4 8 16" "16 4" "$out/scaling" gen:balls:10000 \
    gen:tree:10000 gen:rings:100000 -- --model fast > "$out/scaling.md"
  local packed=(gen:balls:10000 gen:rings:10000 gen:tetra:10000 gen:balls:100000 gen:rings:100000 gen:tetra:100000)
  step packed scripts/packed-images.sh "$kdrt" 128x128 "${packed[@]}" -- --model fast > "$out/packed.md"
  step travfmt scripts/packed-images.sh "$kdrt" 128x128 "${packed[@]}" -- --model fast --trav-format fp32 \
    --stack-depth 32 --node-idx-width 24 --tri-idx-width 24 --addr-width 28 > "$out/travfmt.md"
  step trade "$kdrt" trade gen:balls:10000 --formats fp32,fp24,bf16,fp16 --sim --html "$out/trade_html" \
    --json "$out/trade.json" > "$out/trade.txt"
  step example "$kdrt" sweep docs/sweep-example.yaml -o "$out/example" --jobs 1 > /dev/null
}

timed() {
  local spec k
  for spec in sweep-fast-generators sweep-fast-generators-128 sweep-fast-vs-rtl sweep-fast-cores; do
    step "$spec" "$kdrt" sweep "docs/$spec.yaml" -o "$out/$spec" --jobs 1 > /dev/null
  done
  for k in 1 2 3; do
    step "speed$k" "$kdrt" sim gen:balls:10000 --res 128x128 -q -o "$out/speed.png" --json "$out/speed$k.json"
  done
}

if [ "$mode" = timed ]; then  # the other steps' notes stay: the docs are written from their outputs too
  [ ! -f "$out/times" ] || sed -i -E '/^(sweep-fast-|speed[0-9])/d' "$out/times"
else
  rm -f "$out/times"
fi
if [ "$mode" != timed ]; then
  lane1 &
  lane2 &
  wait
fi
if [ "$mode" != untimed ]; then
  timed
fi
echo "remeasure: done, results in $out (times in $out/times)" >&2
if grep -q FAILED "$out/times"; then
  grep FAILED "$out/times" >&2
  echo "remeasure: docs not written; after a fix, rerun the step or write them anyway with --write-only $out" >&2
  exit 1
fi
write_docs "$out"
