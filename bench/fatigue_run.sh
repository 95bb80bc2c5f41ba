#!/usr/bin/env bash
# Whole-run timing of one static-fatigue point (models/fatigue_ldb_granite.toml: LdB granite,
# rs 0.8, unconfined) to failure on one core: wall time, corrosion steps, mechanical steps per
# corrosion step, failure time. The whole B3 programme: `vorodec batch
# models/batch_ldb_fatigue.toml` (2 cases at a time, one thread each; wall_time_s per case in its
# results.csv).
# Usage: bench/fatigue_run.sh [build dir] [driving-stress ratio]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
rs=${2:-0.8}
out=$(mktemp -d)
/usr/bin/time -o "$out/time.txt" -f "rs $rs: wall %e s, peak memory %M KiB" "$build/vorodec" run \
  "$here/../models/fatigue_ldb_granite.toml" --threads 1 --no-vtk --out "$out/run" \
  --set "stage[0].driving_stress_ratio=$rs" > "$out/run.log" 2>&1 || true
cat "$out/time.txt"
grep -m1 "static-fatigue\|finished\|no bond" "$out/run.log" || true
grep -o '"failure_time_s": [^,]*, "corrosion_steps": [^,]*, "mechanical_steps": [^,]*, "mechanical_steps_per_corrosion_step": [^,]*' \
  "$out/run/summary.json"
rm -rf "$out"
