#!/usr/bin/env bash
# The low-damping study (B6 in verification/REPORT.md), one run at a time on 2 threads:
# 1. models/ucs_ldb_lowdamping.toml (6,500 blocks, both platens at 0.2 m/s as the paper's walls,
#    true masses) with local damping 0.7 and 0.015, compared by postproc/low_damping_study.py
#    (REPORT.md rows and a PNG), with each run's AE plots;
# 2. the strength drop against the loading: the top platen alone at 0.2 and 0.4 m/s (the same
#    closing speeds as before and as the paper's), both damping levels;
# 3. models/triaxial_ldb_lowdamping.toml (20 MPa confinement, damping 0.015, and 0.7 beside it):
#    the cracks before and after the peak (postproc/crack_evolution.py).
# Usage: bench/low_damping.sh [build dir] [results dir]
set -euo pipefail
build=${1:-build}
out=${2:-results/low_damping}
mkdir -p "$out"
run() {  # name model [--set ...]: a run, its wall time, its peak and status
  local name=$1 model=$2
  shift 2
  local start
  start=$(date +%s.%N)
  "$build/vorodec" run "$model" --threads 2 --no-vtk "$@" --out "$out/$name" > "$out/$name.log" 2>&1 || true
  echo "$name: $(echo "$(date +%s.%N) - $start" | bc) s wall; $(grep -E '^models' "$out/$name.log" | tail -1 | cut -c1-200)"
}
for alpha in 0.7 0.015; do
  run "alpha_$alpha" models/ucs_ldb_lowdamping.toml --set solver.local_damping=$alpha
  /usr/bin/python3 postproc/plot_ae.py "$out/alpha_$alpha"
done
/usr/bin/python3 postproc/low_damping_study.py "$out/alpha_0.7" "$out/alpha_0.015" -o "$out/b6_low_damping"
for v in 0.2 0.4; do
  for alpha in 0.7 0.015; do
    run "top_${v}_alpha_$alpha" models/ucs_ldb_lowdamping.toml --set solver.local_damping=$alpha \
      --set loading.platens=top --set "stage[0].platen_velocity=$v"
  done
  /usr/bin/python3 postproc/low_damping_study.py "$out/top_${v}_alpha_0.7" "$out/top_${v}_alpha_0.015" \
    -o "$out/b6_top_$v" | grep -E "UCS|drop|tensile"
done
for alpha in 0.015 0.7; do
  run "confined_alpha_$alpha" models/triaxial_ldb_lowdamping.toml --set solver.local_damping=$alpha
  /usr/bin/python3 postproc/crack_evolution.py "$out/confined_alpha_$alpha" \
    -o "$out/b6_confined_alpha_$alpha" --label "20 MPa confinement, local damping $alpha"
done
