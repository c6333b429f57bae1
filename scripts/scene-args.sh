# Sourced by the measurement scripts that run `kdrt sim` over scenes
# (efficiency.sh, cache-ways.sh, scaling.sh, packed-images.sh): their arguments end in
# `SCENE... [-- SIM OPTIONS]`.
#   read_scenes "DEFAULT SCENES" "$@"   (the arguments after the script's own)
# sets `scenes` (the defaults when none is given) and `extra` (the options
# for every `kdrt sim` run).
read_scenes() {
  local defaults=$1
  shift
  scenes=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do scenes+=("$1"); shift; done
  [ "${1:-}" = "--" ] && shift
  extra=("$@")
  [ ${#scenes[@]} -gt 0 ] || read -r -a scenes <<< "$defaults"
}
