#!/usr/bin/env bash
# Benchmarks taken in turn, round after round, so that a machine whose speed drifts between minutes
# moves every measure alike. Prints, per benchmark, the median and range of cu/s over the rounds
# (of the time per step where a benchmark reports no cu/s, as vorodec_bench_deformable); given two
# binaries (A and B, e.g. a build before and after a change), also the median of the per-round
# ratios A/B (of rates: above 1 when A is faster; of times: below 1 when A is faster).
# Usage: bench/interleaved.sh ROUNDS FILTER BENCH_A [BENCH_B]
#   e.g. bench/interleaved.sh 8 'BM_ScaledStepFixed/' build/bench/vorodec_bench
#        (linearity: the same 200 steps at 1e3, 1e4 and 1e5 blocks, each round)
#        bench/interleaved.sh 10 'BM_ZoneForces/1000/1' build/bench/vorodec_bench_deformable \
#          /tmp/vorodec_bench_deformable.before  (a change's zone kernel, A/B of times)
set -euo pipefail
if [[ $# -lt 3 || $# -gt 4 ]]; then
  echo "usage: $0 ROUNDS FILTER BENCH_A [BENCH_B]" >&2
  exit 2
fi
rounds=$1 filter=$2
binaries=("$3")
[[ $# -eq 4 ]] && binaries+=("$4")
rates=$(mktemp)
trap 'rm -f "$rates"' EXIT
for ((r = 1; r <= rounds; ++r)); do
  for i in "${!binaries[@]}"; do
    label=$([[ $i -eq 0 ]] && echo A || echo B)
    "${binaries[$i]}" --benchmark_filter="$filter" 2>/dev/null |
      awk -v r="$r" -v l="$label" '/^BM_/ {
        if (match($0, /cu\/s=[0-9.]+[kMG]?/)) {
          v = substr($0, RSTART + 5, RLENGTH - 5)
          scale = v ~ /G$/ ? 1e9 : v ~ /M$/ ? 1e6 : v ~ /k$/ ? 1e3 : 1
          print r, l, $1, "cu/s", v * scale
        } else print r, l, $1, $3, $2 }' >>"$rates"
  done
done
/usr/bin/python3 - "$rates" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(lambda: collections.defaultdict(dict))
unit = {}
for line in open(sys.argv[1]):
    r, label, name, what, value = line.split()
    runs[name][label][r] = float(value)
    unit[name] = what
for name, by_label in runs.items():
    parts = []
    for label in sorted(by_label):
        v = list(by_label[label].values())
        parts.append(f"{label} median {statistics.median(v):.3g} {unit[name]} ({min(v):.3g}-{max(v):.3g}, {len(v)} rounds)")
    if len(by_label) == 2:
        a, b = by_label["A"], by_label["B"]
        ratios = [a[r] / b[r] for r in a if r in b]
        parts.append(f"A/B per round: median {statistics.median(ratios):.3f} ({min(ratios):.2f}-{max(ratios):.2f})")
    print(name + ": " + "; ".join(parts))
PY
