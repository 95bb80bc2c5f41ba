#!/usr/bin/env bash
# Whole-run timing of the default model (and the same model at half the loading rate, to show the
# loading rate does not decide the UCS), and of the default model with the implicit elastic start
# (models/ucs_marble_implicit.toml). Usage: bench/whole_run.sh [build dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
out=$(mktemp -d)
half="$out/ucs_marble_half_rate.toml"
sed 's/^platen_velocity = 5e-3 /platen_velocity = 2.5e-3 /' "$here/../models/ucs_marble.toml" > "$half"
for model in "$here/../models/ucs_marble.toml" "$half" "$here/../models/ucs_marble_implicit.toml"; do
  name=$(basename "$model" .toml)
  /usr/bin/time -f "$name: wall %e s, peak memory %M KiB" \
    "$build/vorodec" run "$model" --no-vtk --out "$out/$name" > "$out/$name.log" 2>&1 || true
  tail -n 1 "$out/$name.log"
  grep -E '"(status|peak_stress_Pa|youngs_modulus_Pa|poisson_ratio|steps|wall_time_s)"' "$out/$name/summary.json"
done
