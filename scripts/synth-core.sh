#!/usr/bin/env bash
# Physical cost of one rt_core configuration on the OSU 0.18 um library: every
# unit rt_core instantiates, at the parameters rt_core gives it, synthesized
# and timed by scripts/synth-phys.sh, cached, summed into DIR/core.json.
# Usage: scripts/synth-core.sh --out DIR [--period NS] [--jobs N] [--mem-gb G]
#          [--time-min M] NAME=VALUE...     (--help: the details)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command -v python3 > /dev/null || { echo "synth-core: python3: command not found (apt-get install python3)" >&2; exit 1; }
exec python3 "$ROOT/scripts/synth_core.py" "$@"
