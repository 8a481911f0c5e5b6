#!/usr/bin/env bash
# Byte-for-byte comparison of two deltamesh binaries' outputs on every
# ../shared/corpus .poly (and .node) file under a set of switch strings.
# Usage: scripts/compare_outputs.sh BASE_BIN NEW_BIN [SWITCHES...]
# Default switches: -pq30 -pq33. A switch argument may hold several options
# separated by spaces ("-pq30 --steiner=offcenter"). Prints one line per
# difference, then a summary; exits 1 when any output differs.
set -uo pipefail
base=$(realpath "$1"); new=$(realpath "$2"); shift 2
switches=("$@"); [ ${#switches[@]} -eq 0 ] && switches=(-pq30 -pq33)
corpus=${CORPUS:-$(cd "$(dirname "$0")/.." && pwd)/../shared/corpus}
[ -d "$corpus" ] || { echo "compare_outputs: no corpus at $corpus" >&2; exit 2; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
same=0; diff=0
for f in "$corpus"/*.poly "$corpus"/*.node; do
  name=$(basename "$f")
  for sw in "${switches[@]}"; do
    read -ra words <<< "$sw"
    # A .node file has no segments: its switches are the same without -p.
    case "$name" in *.node) words[0]=${words[0]//p/} ; [ "${words[0]}" = "-" ] && words[0]=-Q ;; esac
    sw_eff="${words[*]}"
    for side in base new; do
      rm -rf "$work/$side"; mkdir -p "$work/$side"; cp "$f" "$work/$side/"
      bin=$base; [ $side = new ] && bin=$new
      (cd "$work/$side" && timeout 60 "$bin" "${words[@]}" -Q "$name" > stdout.txt 2> stderr.txt; echo "exit $?" >> stdout.txt)
    done
    if diff -r -q "$work/base" "$work/new" > /dev/null; then same=$((same+1))
    else diff=$((diff+1)); echo "DIFF $name $sw_eff: $(diff -r -q "$work/base" "$work/new" | head -3 | tr '\n' ' ')"; fi
  done
done
echo "compare_outputs: $same identical, $diff different"
[ $diff -eq 0 ]
