#!/usr/bin/env bash
# Checks that library dependencies run one way:
#   tools -> trade -> sim -> setup -> structures -> trace -> accel -> scene, fp, common
# (sw/setup may use trace, accel, scene, fp and common; the simulator may use
# setup and below; nothing but sw/tools uses sw/tools). Prints each include
# that goes the wrong way; exit status 1 if there is one. Run by ctest.
set -u
cd "$(dirname "$0")/.."
bad=0
check() {  # check <dirs...> -- <forbidden include prefixes...>
  local dirs=() pats=()
  while [ "$1" != "--" ]; do dirs+=("$1"); shift; done
  shift
  pats=("$@")
  for p in "${pats[@]}"; do
    if grep -rnE "#include \"$p/" "${dirs[@]}" --include=*.h --include=*.cpp --include=*.def; then bad=1; fi
  done
}
check sw/trade -- tools
check sim -- tools trade
check sw/setup -- tools trade sim
check sw/structures -- tools trade sim setup
check sw/trace sw/accel sw/scene sw/fp sw/common scenes -- tools trade sim setup structures
check sw/accel sw/scene sw/fp sw/common scenes -- trace
if [ "$bad" -ne 0 ]; then
  echo "check-layers: the includes above go against the dependency order (docs/simulator.md)" >&2
  exit 1
fi
echo "check-layers: dependencies run one way"
