#!/usr/bin/env bash
# scripts/synth_core.py's estimate of a unit from two smaller sizes: area,
# cells and flip-flops linear in the size, the critical path linear in its
# log2, and each SRAM macro's words linear in the size (a macro that does not
# grow keeps its words).
# Usage: synth_core_estimate_test.sh SOURCE_DIR
set -euo pipefail
PYTHONPATH="$1/scripts" python3 - <<'PY'
import sys
import synth_core

def unit(size, crit):
    return {"area_um2": 1000 + 10 * size, "cells": 50 + 2 * size, "flip_flops": 7 * size, "crit_ns": crit,
            "srams": [{"name": "buf", "words": size, "width": 128},
                      {"name": "tgt", "words": 8 * size, "width": 16},
                      {"name": "lines", "words": 512, "width": 256}]}

est = synth_core.extrapolate(128, 16, unit(16, 3.0), 8, unit(8, 2.5))
want = {"area_um2": 1000 + 1280, "cells": 50 + 256, "flip_flops": 7 * 128, "crit_ns": 4.5}
errors = [f"{k}: {est[k]}, want {v}" for k, v in want.items() if est[k] != v]
words = {m["name"]: m["words"] for m in est["srams"]}
for name, w in (("buf", 128), ("tgt", 1024), ("lines", 512)):
    if words.get(name) != w:
        errors.append(f"macro {name}: {words.get(name)} words, want {w}")
if errors:
    print("FAIL: " + "; ".join(errors), file=sys.stderr)
    sys.exit(1)
print("synth_core estimate: PASS")
PY
