#!/usr/bin/env bash
# scripts/synth-core.sh refuses what is not an rt_core parameter (exit 2, the
# parameter named) and a missing Liberty file (exit 1, the reason, no
# core.json), both before any synthesis.
# Usage: synth_core_args_test.sh SOURCE_DIR
set -euo pipefail
core="$1/scripts/synth-core.sh"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

rc=0
"$core" --out "$work/a" Thread=32 2> "$work/err" || rc=$?
[ "$rc" = 2 ] || fail "Thread=32: exit status $rc, expected 2"
grep -q "Thread: not a parameter of rt_core" "$work/err" || fail "Thread=32: message '$(cat "$work/err")'"
rc=0
LIBERTY="$work/none.lib" "$core" --out "$work/b" Threads=32 2> "$work/err" || rc=$?
[ "$rc" = 1 ] || fail "a missing Liberty file: exit status $rc, expected 1"
grep -q "none.lib: Liberty file not found" "$work/err" || fail "a missing Liberty file: message '$(cat "$work/err")'"
[ ! -e "$work/b/core.json" ] || fail "a missing Liberty file left a core.json"
echo "synth_core_args_test: ok"
