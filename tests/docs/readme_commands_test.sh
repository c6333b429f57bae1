#!/usr/bin/env bash
# Every `kdrt ...` command line in the README's sh code blocks runs as
# written and exits 0: the README's examples stay true.
#   tests/docs/readme_commands_test.sh KDRT [SOURCE_DIR]
# The commands run in a scratch folder that holds the repository's scenes/
# and docs/ (read-only inputs), so what they write lands there.
set -euo pipefail
kdrt=${1:?usage: readme_commands_test.sh KDRT [SOURCE_DIR]}
root=${2:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"}
kdrt=$(cd "$(dirname "$kdrt")" && pwd)/$(basename "$kdrt")

mapfile -t commands < <(awk '
  /^```/ { if (inblock) { inblock = 0 } else if ($0 ~ /^```(sh|bash)$/) { inblock = 1 }; next }
  inblock {
    line = $0
    if (cont != "") { line = cont " " line; cont = "" }
    if (line ~ /\\$/) { sub(/\\$/, "", line); cont = line; next }
    if (line ~ /^kdrt /) print line
  }' "$root/README.md")
[ ${#commands[@]} -gt 0 ] || { echo "readme_commands: no kdrt command found in $root/README.md" >&2; exit 1; }

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
ln -s "$root/scenes" "$scratch/scenes"
ln -s "$root/docs" "$scratch/docs"
mkdir -p "$scratch/bin" "$scratch/out"
ln -s "$kdrt" "$scratch/bin/kdrt"

failed=0
for c in "${commands[@]}"; do
  echo "readme_commands: $c"
  start=$(date +%s)
  if (cd "$scratch" && PATH="$scratch/bin:$PATH" bash -c "$c" > "$scratch/last.log" 2>&1); then
    echo "  exit 0 ($(($(date +%s) - start)) s)"
  else
    rc=$?
    echo "  FAILED: exit $rc; its output ends:" >&2
    tail -20 "$scratch/last.log" >&2
    failed=$((failed + 1))
  fi
done
echo "readme_commands: $((${#commands[@]} - failed)) of ${#commands[@]} README commands exit 0"
[ $failed -eq 0 ]
