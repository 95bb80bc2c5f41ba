#!/usr/bin/env bash
# Runs verification cases and rewrites verification/REPORT.md as a whole.
# Usage: verification/run.sh [build dir] [vorodec_verify options]
#        verification/run.sh --assemble
# The full run (no option, or --ladders, --deformable-ladder, --analytic-only) writes the main
# table, the stiff and extreme cases and the convergence ladders to verification/generated.md;
# an --X-only option writes its case group's rows to verification/generated-X.md (they then
# replace that group's rows in its section file under verification/report/). Plots are written
# to verification/. Then assemble_report.sh writes REPORT.md from generated.md and the section
# files. --assemble only re-assembles REPORT.md from the files as they are, running no case.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if [[ ${1:-} == --assemble ]]; then
  exec "$here/assemble_report.sh"
fi
build=$here/../build
if [[ $# -gt 0 && $1 != --* ]]; then
  build=$1
  shift
fi
out=$here/generated.md
for option in "$@"; do
  if [[ $option == --*-only ]]; then
    part=${option#--}
    out=$here/generated-${part%-only}.md
  fi
done
status=0
"$build/verification/vorodec_verify" "$here/.." "$build/vorodec" "$out" "$@" || status=$?
# 0: every check passed, 1: some failed (the tables say which); anything else wrote no tables.
if ((status <= 1)); then
  "$here/assemble_report.sh"
fi
exit "$status"
