#!/bin/sh
# Measures rigidlab's wall time, CPU time and peak memory on one command, best of N runs
# (N=${RUNS:-1}; the least wall time, the largest peak memory):
#   RUNS=3 tools/budget_measure.sh check tests/budget/discs_1000_one_point.ron --no-advice
# prints "wall_s cpu_s peak_MB exit | command". The release binary must be built
# (cargo build --release). Used for the unit costs in src/runner/budget.rs and the table in
# docs/cli.md.
BIN=${RIGIDLAB:-target/release/rigidlab}
out=$(mktemp)
best=""
i=0
while [ $i -lt "${RUNS:-1}" ]; do
  /usr/bin/time -v "$BIN" "$@" >/dev/null 2>"$out"
  code=$?
  wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$out" | awk -F: '{ if (NF==3) print $1*3600+$2*60+$3; else print $1*60+$2 }')
  cpu=$(awk '/User time \(seconds\)/ {u=$4} /System time \(seconds\)/ {s=$4} END {printf "%.2f", u+s}' "$out")
  rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$out")
  best=$(printf '%s\n%s %s %s %s\n' "$best" "$wall" "$cpu" "$rss" "$code" | awk 'NF==4 { if (w=="" || $1<w) {w=$1; c=$2; x=$4} if ($3>m) m=$3 } END {printf "%s %s %.1f %s", w, c, m/1024, x}')
  i=$((i+1))
done
echo "$best | $*"
rm -f "$out"
