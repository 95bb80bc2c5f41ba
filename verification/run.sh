#!/usr/bin/env bash
# Runs every verification case and rewrites verification/REPORT.md.
# Usage: verification/run.sh [build dir] [--analytic-only]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
shift || true
"$build/verification/vorodec_verify" "$here/.." "$build/vorodec" "$here/REPORT.md" "$@"
