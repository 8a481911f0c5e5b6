#!/usr/bin/env bash
# Triangle counts and below-bound counts of deltamesh against Triangle 1.6's,
# per corpus file, at the quality bounds of the reference table.
#
#   bench/quality_vs_triangle.sh CLI [extra switches...]
#     e.g. bench/quality_vs_triangle.sh build/bin/deltamesh --steiner=best
#
# Environment: CORPUS (default /work/shared/corpus), REF (default
# /work/shared/reference/triangle-quality-counts.tsv: file, q, triangles,
# below_bound, ...), QS (bounds to run, default "30 33"), JOBS (parallel
# runs, default 2).
# Prints TSV: file, q, Triangle's triangles and below-bound count, ours
# (ERR if the run failed), then a TOTAL line per bound. "Below" = triangles
# of the final mesh with an angle under the bound (--stats=json below_angle).
set -euo pipefail
if [[ $# -lt 1 ]]; then
  sed -n '2,14p' "$0" >&2
  exit 2
fi
CLI=$(realpath "$1")
shift
CORPUS=${CORPUS:-/work/shared/corpus}
REF=${REF:-/work/shared/reference/triangle-quality-counts.tsv}
QS=${QS:-30 33}
JOBS=${JOBS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Jobs: "file<TAB>q" lines for the selected bounds.
awk -F'\t' -v qs=" $QS " '!/^#/ && $1 != "file" && index(qs, " " $2 " ") { print $1 "\t" $2 }' "$REF" >"$work/jobs"

# One job: each run in its own directory (the input is a symlink, -NEP
# writes no mesh files), result "file q triangles below" in DIR/result.
one() {
  local file=$1 q=$2 d=$work/$2-$1
  local -a extra
  read -r -a extra <<<"$EXTRA"
  mkdir -p "$d"
  ln -s "$CORPUS/$file" "$d/$file"
  (cd "$d" && "$CLI" -pq"$q" -NEPQ --stats=json "${extra[@]}" "$file" >json 2>err) || true
  python3 -c '
import json, sys
f, q, path = sys.argv[1:4]
try:
    text = open(path).read()
    d = json.loads(text[text.index("{"):text.rindex("}") + 1])
    print("\t".join([f, q, str(d["triangles"]), str(d["below_angle"])]))
except Exception:
    print("\t".join([f, q, "ERR", "ERR"]))
' "$file" "$q" "$d/json" >"$d/result"
}
export -f one
EXTRA="$*"  # the extra switches, split at spaces
export CLI CORPUS work EXTRA

tr '\t' '\n' <"$work/jobs" | xargs -d '\n' -n 2 -P "$JOBS" bash -c 'one "$@"' one

printf 'file\tq\ttriangle_tris\ttriangle_below\tour_tris\tour_below\n'
# Reference rows joined with ours, in the reference's order.
awk -F'\t' -v OFS='\t' -v qs=" $QS " '
  FNR == NR { ours[$1 "\t" $2] = $3 "\t" $4; next }
  /^#/ || $1 == "file" || !index(qs, " " $2 " ") { next }
  {
    k = $1 "\t" $2
    split(ours[k], o, "\t")
    print $1, $2, $3, $4, o[1], o[2]
    tt[$2] += $3; tb[$2] += $4
    if (o[1] ~ /^[0-9]+$/) { ot[$2] += o[1]; ob[$2] += o[2] } else { err[$2]++ }
  }
  END {
    n = split(qs, list, " ")
    for (i = 1; i <= n; ++i) {
      q = list[i]
      printf "TOTAL\t%s\t%d\t%d\t%d\t%d", q, tt[q], tb[q], ot[q], ob[q]
      if (err[q]) printf "\t(%d runs failed)", err[q]
      if (tt[q]) printf "\tratio %.3f", ot[q] / tt[q]
      printf "\n"
    }
  }' <(cat "$work"/*/result) "$REF"
