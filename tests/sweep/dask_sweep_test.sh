#!/usr/bin/env bash
# kdrt sweep (docs/sweep.md): a small sweep on the local pool; again (nothing
# runs: resumed); through a real Dask cluster on 127.0.0.1 (a dask-scheduler
# and two dask-worker processes, stopped at the end) with the same results as
# the local run, both workers used; and the spec errors.
# Usage: dask_sweep_test.sh KDRT
set -euo pipefail
kdrt=$1
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2> /dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2> /dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
# Runs the sweep $work/NAME.yaml into $work/NAME on the local pool, or fails
# with its stderr.
local_sweep() {
  "$kdrt" sweep "$work/$1.yaml" -o "$work/$1" --jobs 2 > /dev/null 2> "$work/$1.err" ||
    { cat "$work/$1.err"; fail "$1 sweep"; }
}

# The RTL on the prebuilt fp32 model (a sweep over formats runs the same way
# with the model of each format, built on first use).
cat > "$work/spec.yaml" << 'SPEC'
scenes: [gen:balls:300]
formats: [fp32]
res: 8x8
params:
  mem_latency: [20, 60]
  mem_bw: [8, 16]
SPEC

"$kdrt" sweep "$work/spec.yaml" -o "$work/local" --jobs 2 > "$work/local.out" 2> "$work/local.err" ||
  { cat "$work/local.err"; fail "local sweep"; }
[ "$(ls "$work/local/points" | wc -l)" = 4 ] || fail "expected 4 point files"
[ "$(wc -l < "$work/local/sweep.csv")" = 5 ] || fail "expected 4 rows and a header in sweep.csv"
ls "$work/local/plots/"*mem_latency.svg > /dev/null || fail "no plot of cycles per ray against mem_latency"

# Resumed: every point is there, nothing runs, the same CSV.
cp "$work/local/sweep.csv" "$work/first.csv"
"$kdrt" sweep "$work/spec.yaml" -o "$work/local" > /dev/null 2> "$work/again.err" || fail "second local sweep"
grep -q "4 done already, 0 to run" "$work/again.err" || { cat "$work/again.err"; fail "the second run ran points"; }
cmp -s "$work/first.csv" "$work/local/sweep.csv" || fail "the resumed sweep changed sweep.csv"

# A stack smaller than the tree (allow_overflow: the fast model ends a ray at
# the push that meets the full stack, as the RTL does): rays overflow at
# depth 2 and none at 40, and the CSV says so.
cat > "$work/stack.yaml" << 'SPEC'
scenes: [gen:balls:300]
res: 8x8
model: fast
allow_overflow: true
params:
  stack_depth: [2, 40]
SPEC
local_sweep stack
/usr/bin/python3 - "$work/stack/sweep.csv" << 'PY' || fail "overflows column"
import csv, sys
rows = {int(r["stack_depth"]): int(r["overflows"]) for r in csv.DictReader(open(sys.argv[1]))}
assert rows[2] > 0 and rows[40] == 0, rows
PY

# Formats as parameters: an fp32 core reading a bf16 image reads fewer bytes
# per ray than one reading the fp32 image (--image-format).
cat > "$work/image.yaml" << 'SPEC'
scenes: [gen:tree:300]
res: 8x8
model: fast
params:
  image_format: [fp32, bf16]
SPEC
local_sweep image
/usr/bin/python3 - "$work/image/sweep.csv" << 'PY' || fail "bytes_per_ray by image_format"
import csv, sys
rows = {r["image_format"]: float(r["bytes_per_ray"]) for r in csv.DictReader(open(sys.argv[1]))}
assert rows["bf16"] < rows["fp32"], rows
PY
ls "$work/image/plots/"*image_format.svg > /dev/null || fail "no plot against image_format"

# The tree as a parameter (--min-split-gain): on gears' overlapping slivers a
# minimum split gain makes a tree of fewer nodes (each point's report has
# its tree), and the CSV has the column.
cat > "$work/gain.yaml" << 'SPEC'
scenes: [gen:gears:2000]
res: 16x16
model: fast
params:
  min_split_gain: [0, 0.1]
SPEC
local_sweep gain
/usr/bin/python3 - "$work/gain" << 'PY' || fail "min_split_gain column"
import csv, json, sys
rows = {float(r["min_split_gain"]): r for r in csv.DictReader(open(sys.argv[1] + "/sweep.csv"))}
assert sorted(rows) == [0.0, 0.1], rows
nodes = {}
for r in rows.values():
    point = json.load(open(sys.argv[1] + "/points/" + r["id"] + ".json"))
    nodes[float(r["min_split_gain"])] = point["report"]["tree"]["nodes"]
assert nodes[0.1] * 3 < nodes[0.0] * 2, nodes
PY

# The order the camera's rays enter the core (--ray-order): the same rays,
# so the same hits and reference work, and in Z-order tree's cache lines
# serve more rays in flight (fewer bytes per ray).
cat > "$work/order.yaml" << 'SPEC'
scenes: [gen:tree:10000]
res: 48x48
model: fast
params:
  ray_order: [linear, morton]
SPEC
local_sweep order
/usr/bin/python3 - "$work/order" << 'PY' || fail "ray_order column"
import csv, json, sys
rows = {r["ray_order"]: r for r in csv.DictReader(open(sys.argv[1] + "/sweep.csv"))}
assert sorted(rows) == ["linear", "morton"], rows
points = {k: json.load(open(sys.argv[1] + "/points/" + r["id"] + ".json"))["report"] for k, r in rows.items()}
assert points["morton"]["ray_order"] == "morton" and points["linear"]["ray_order"] == "linear"
assert points["morton"]["hits"] == points["linear"]["hits"]
assert points["morton"]["reference_per_ray"] == points["linear"]["reference_per_ray"]
assert float(rows["morton"]["bytes_per_ray"]) < float(rows["linear"]["bytes_per_ray"]), rows
PY

# A Dask cluster on loopback.
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
dask-scheduler --host 127.0.0.1 --port "$port" --no-dashboard > "$work/scheduler.log" 2>&1 &
pids+=($!)
for w in w1 w2; do
  dask-worker "tcp://127.0.0.1:$port" --nthreads 1 --nworkers 1 --name "$w" --no-dashboard \
    --local-directory "$work/$w" > "$work/$w.log" 2>&1 &
  pids+=($!)
done
/usr/bin/python3 - "$port" << 'PY' || { cat "$work/scheduler.log" "$work/w1.log" "$work/w2.log"; fail "cluster did not start"; }
import sys, time
from distributed import Client
deadline = time.time() + 60
while True:
    try:
        c = Client("tcp://127.0.0.1:%s" % sys.argv[1], timeout=5)
        break
    except OSError:
        if time.time() > deadline:
            raise
        time.sleep(0.5)
c.wait_for_workers(2, timeout=60)
c.close()
PY
"$kdrt" sweep "$work/spec.yaml" -o "$work/dask" --scheduler "tcp://127.0.0.1:$port" > "$work/dask.out" \
  2> "$work/dask.err" || { cat "$work/dask.err"; fail "sweep on the Dask cluster"; }
/usr/bin/python3 - "$work/local/sweep.csv" "$work/dask/sweep.csv" "$work/dask/points" << 'PY' || fail "results differ"
import csv, json, os, sys
def rows(path):
    return {r["id"]: {k: v for k, v in r.items() if k != "sim_seconds"} for r in csv.DictReader(open(path))}
local, dask = rows(sys.argv[1]), rows(sys.argv[2])
assert len(local) == 4 and local == dask, "local and Dask results differ"
assert all(float(r["cycles"]) > 0 for r in local.values())
workers = {json.load(open(os.path.join(sys.argv[3], f)))["ran_on"] for f in os.listdir(sys.argv[3])}
assert workers == {"w1", "w2"}, "points ran on %s, expected both workers" % sorted(workers)
PY

# Spec errors: named, exit 1, nothing written.
printf 'scenes: [gen:room:300]\nparams:\n  no_such_param: [1]\n' > "$work/bad1.yaml"
printf 'scenes: [gen:room:300]\nmodel: turbo\n' > "$work/bad2.yaml"
printf 'scenes: [gen:room:300\n' > "$work/bad3.yaml"
for b in bad1:no_such_param bad2:"expected rtl, fast or both" bad3:"not valid YAML"; do
  f=${b%%:*}
  want=${b#*:}
  set +e
  "$kdrt" sweep "$work/$f.yaml" -o "$work/$f.out" > /dev/null 2> "$work/$f.err"
  rc=$?
  set -e
  [ "$rc" = 1 ] || fail "$f: exit $rc, expected 1"
  grep -q "$want" "$work/$f.err" || { cat "$work/$f.err"; fail "$f: message"; }
  grep -q "$f.yaml" "$work/$f.err" || fail "$f: the message does not name the file"
  [ ! -e "$work/$f.out" ] || fail "$f: wrote output"
done
echo "PASS: kdrt sweep (local, resumed, Dask cluster of 2 workers, spec errors)"
