#!/usr/bin/env bash
# Byte-for-byte comparison of two deltamesh binaries' outputs on every
# ../shared/corpus .poly (and .node) file under a set of switch strings.
# Usage: scripts/compare_outputs.sh BASE_BIN NEW_BIN [SWITCHES...]
# Default switches: -pq30 -pq33. An argument may hold several words
# ("-p --cdt=lifting"): they are passed as separate arguments, and only the
# first (Triangle's switches) loses its p for .node files. Prints one line
# per difference, then a summary; exits 1 when any output differs.
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
    sw_eff=${words[0]}
    case "$name" in *.node) sw_eff=${sw_eff//p/} ; [ "$sw_eff" = "-" ] && sw_eff=-Q ;; esac
    words[0]=$sw_eff
    for side in base new; do
      rm -rf "$work/$side"; mkdir -p "$work/$side"; cp "$f" "$work/$side/"
      bin=$base; [ $side = new ] && bin=$new
      (cd "$work/$side" && timeout 60 "$bin" "${words[@]}" -Q "$name" > stdout.txt 2> stderr.txt; echo "exit $?" >> stdout.txt)
    done
    if diff -r -q "$work/base" "$work/new" > /dev/null; then same=$((same+1))
    else diff=$((diff+1)); echo "DIFF $name ${words[*]}: $(diff -r -q "$work/base" "$work/new" | head -3 | tr '\n' ' ')"; fi
  done
done
echo "compare_outputs: $same identical, $diff different"
[ $diff -eq 0 ]
