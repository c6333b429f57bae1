#!/usr/bin/env bash
# The tree speaks of the project as it is: no word of how it was developed
# (work periods, tracker numbers, earlier defaults, first-person notes) in
# code, docs, help texts, tests or sweep files. History is git log's.
#   tests/docs/no_history_test.sh [SOURCE_DIR]
set -euo pipefail
root=${1:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"}
cd "$root"

# Written in pieces so that this file does not match itself.
s="sess""ion"
patterns=(
  "\\b${s}s?\\b"
  "\\biss""ues? #?[0-9]+"
  "\\biss""ue \""
  "\\bof mi""ne\\b"
  "former defa""ult"
  "defa""ult (since|until)"
  "was the defa""ult"
  "defa""ult back"
)
regex=$(IFS='|'; echo "${patterns[*]}")

if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard)
else
  mapfile -t files < <(find . -path ./build -prune -o -path ./.git -prune -o -type f -print | sed 's|^\./||')
fi
existing=()
for f in "${files[@]}"; do [ -f "$f" ] && existing+=("$f"); done

if hits=$(grep -nIiE "$regex" -- "${existing[@]}"); then
  echo "no_history: the tree speaks of its own development ($(echo "$hits" | wc -l) lines):" >&2
  echo "$hits" | head -50 >&2
  exit 1
fi
echo "no_history: ${#existing[@]} files, none speaks of the project's development"
