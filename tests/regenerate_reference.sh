#!/usr/bin/env bash
# Regenerates tests/reference/ from the current build. A reviewed act: commit the new reference
# only together with the change that explains why the results moved.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../build/vorodec}
out=$(mktemp -d)
"$bin" run "$here/models/e2e_small.toml" --threads 1 --no-vtk --out "$out"
cp "$out/history.csv" "$here/reference/e2e_small_history.csv"
echo "tests/reference/e2e_small_history.csv regenerated with $bin"
