#!/usr/bin/env bash
# The low-damping study (B6 in verification/REPORT.md): models/ucs_ldb_lowdamping.toml (6,500
# blocks, 0.2 m/s, true masses) with local damping 0.7 and 0.015, one after the other on 2 threads,
# then the comparison (postproc/low_damping_study.py: REPORT.md rows and a PNG) and each run's AE
# plots.
# Usage: bench/low_damping.sh [build dir] [results dir]
set -euo pipefail
build=${1:-build}
out=${2:-results/low_damping}
mkdir -p "$out"
for alpha in 0.7 0.015; do
  start=$(date +%s.%N)
  "$build/vorodec" run models/ucs_ldb_lowdamping.toml --threads 2 --no-vtk \
    --set solver.local_damping=$alpha --out "$out/alpha_$alpha" > "$out/alpha_$alpha.log" 2>&1 || true
  echo "alpha $alpha: $(echo "$(date +%s.%N) - $start" | bc) s wall"
  /usr/bin/python3 postproc/plot_ae.py "$out/alpha_$alpha"
done
/usr/bin/python3 postproc/low_damping_study.py "$out/alpha_0.7" "$out/alpha_0.015" -o "$out/b6_low_damping"
