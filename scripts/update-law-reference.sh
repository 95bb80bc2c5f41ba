#!/usr/bin/env bash
# Writes `vorodec laws` (the contact laws' keys from their own parameter specs) into
# docs/model-file.md between its markers. Usage: scripts/update-law-reference.sh [VORODEC_BINARY]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${1:-$root/build/vorodec}"
page="$root/docs/model-file.md"
"$bin" laws > "$page.laws"
/usr/bin/python3 - "$page" "$page.laws" <<'PY'
import sys
page, laws = sys.argv[1], open(sys.argv[2]).read()
text = open(page).read()
begin, end = "<!-- vorodec laws: begin -->\n", "<!-- vorodec laws: end -->"
i, j = text.index(begin) + len(begin), text.index(end)
open(page, "w").write(text[:i] + laws + text[j:])
PY
rm "$page.laws"
