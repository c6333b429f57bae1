#!/usr/bin/env bash
# The profile training of a preset model (sim/CMakeLists.txt, KDRT_MODEL_PGO):
# runs kdrt sim on the instrumented model of the preset (a few 64x64 frames of
# three generators, the RTL checked against the reference as always), then
# copies GCC's profile (.gcda, one per source of the Verilated code) beside the
# objects of the model that is compiled with it.
#   sim/pgo_train.sh KDRT INSTRUMENTED_MODEL PRESET GEN_OBJ_DIR USE_OBJ_DIR WORK_DIR
set -euo pipefail
if [ $# -ne 6 ]; then
  sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
kdrt=$1 model=$2 preset=$3 gen_objs=$4 use_objs=$5 work=$6
mkdir -p "$work" "$use_objs"
rm -f "$work/trained.stamp" "$gen_objs"/*.gcda "$use_objs"/*.gcda
for scene in gen:balls:10000 gen:tree:10000 gen:gears:10000; do
  if ! KDRT_SIM_MODEL_BINARY="$model" "$kdrt" sim "$scene" --format "$preset" --res 64x64 -q \
      -o "$work/train.png" 2> "$work/train.log"; then
    cat "$work/train.log" >&2
    echo "pgo_train: kdrt sim $scene --format $preset on $model failed" >&2
    exit 1
  fi
done
shopt -s nullglob
profiles=("$gen_objs"/*.gcda)
if [ ${#profiles[@]} -eq 0 ]; then
  echo "pgo_train: the training wrote no profile in $gen_objs (not an instrumented model?)" >&2
  exit 1
fi
cp "${profiles[@]}" "$use_objs/"
touch "$work/trained.stamp"
