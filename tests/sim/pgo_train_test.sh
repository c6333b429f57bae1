#!/usr/bin/env bash
# sim/pgo_train.sh on a model that is not instrumented: the training runs
# (kdrt sim checks every ray), finds no profile, says so and fails without
# marking the training done; with the wrong number of arguments it prints its
# usage and fails.
#   tests/sim/pgo_train_test.sh SOURCE_DIR KDRT MODEL
set -uo pipefail
src=$1 kdrt=$2 model=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/gen" "$work/use"
out=$(bash "$src/sim/pgo_train.sh" "$kdrt" "$model" fp32 "$work/gen" "$work/use" "$work/pgo" 2>&1)
rc=$?
fail=0
if [ $rc -eq 0 ]; then echo "FAIL: pgo_train.sh succeeded on a model without a profile"; fail=1; fi
if ! grep -q 'wrote no profile' <<< "$out"; then echo "FAIL: no 'wrote no profile' in: $out"; fail=1; fi
if [ -e "$work/pgo/trained.stamp" ]; then echo "FAIL: the stamp was written"; fail=1; fi
if [ -n "$(ls -A "$work/use")" ]; then echo "FAIL: something was copied beside the objects"; fail=1; fi
usage=$(bash "$src/sim/pgo_train.sh" "$kdrt" 2>&1)
if [ $? -ne 2 ] || ! grep -q 'INSTRUMENTED_MODEL' <<< "$usage"; then echo "FAIL: no usage: $usage"; fail=1; fi
[ $fail -eq 0 ] && echo "pgo_train_test: PASS"
exit $fail
