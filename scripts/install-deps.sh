#!/usr/bin/env bash
# Installs the Debian 12 packages kdrt needs, only when something is missing.
# Idempotent: a second run does nothing but check. Uses sudo only when not root.
#   scripts/install-deps.sh          everything: build, tests, synthesis, sweeps
#   scripts/install-deps.sh --demo   only what `make demo` builds and runs
set -euo pipefail

# What the build needs (CMake finds all of these when it configures).
PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libopenimageio-dev openimageio-tools
  libtinyobjloader-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libembree-dev libmpfr-dev libgmp-dev
  verilator libsystemc-dev
)
case "${1:-}" in
  --demo) ;;
  "")
    PACKAGES+=(
      yosys     # make synth, kdrt trade's on-demand synthesis
      opensta qflow-tech-osu018  # make synth's physical flow: timing, the OSU 0.18 um cells
      chromium  # the screenshot test of the kdrt trade page
      python3 python3-yaml python3-distributed  # kdrt sweep: the spec, the Dask cluster
    )
    ;;
  -h | --help) sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "install-deps: unknown option '$1' (use --demo or nothing)" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing missing packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: not root and no sudo; install these by hand: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
