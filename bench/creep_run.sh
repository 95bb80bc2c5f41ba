#!/usr/bin/env bash
# Whole-run timing of the B4 multi-step creep (models/creep_sandstone.toml: 12 simulated days at
# 160 / 190 / 220 MPa) at the default creep step and at half of it: wall time, steps, steps per
# simulated day of each creep stage, and the end-of-stage strains of the two runs.
# Usage: bench/creep_run.sh [build dir] [threads]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
threads=${2:-2}
out=$(mktemp -d)
half=""
for s in 2 4 6; do half="$half --set stage[$s].creep_step_factor=5e-4"; done
for run in default half; do
  args=$([[ $run == half ]] && echo "$half" || true)
  # shellcheck disable=SC2086
  /usr/bin/time -f "$run: wall %e s, peak memory %M KiB" "$build/vorodec" run \
    "$here/../models/creep_sandstone.toml" --threads "$threads" --no-vtk --out "$out/$run" $args \
    > "$out/$run.log" 2>&1 || true
  tail -n 1 "$out/$run.log"
  grep -E '"(status|steps|wall_time_s)"|"stage": "creep' "$out/$run/summary.json"
done
/usr/bin/python3 - "$out" <<'PY'
import csv, sys
ends = {}
for run in ("default", "half"):
    rows = list(csv.DictReader(open("%s/%s/history.csv" % (sys.argv[1], run))))
    ends[run] = {r["stage"].split(":")[0]: float(r["axial_strain"]) for r in rows}
for stage in ("creep160", "creep190", "creep220"):
    d, h = ends["default"][stage], ends["half"][stage]
    print("%s end strain: default %.6g, half step %.6g, difference %.2e" % (stage, d, h, abs(d - h) / h))
PY
rm -rf "$out"
