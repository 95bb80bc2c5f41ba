#!/usr/bin/env bash
# Writes verification/REPORT.md as a whole from the section files verification/report/NN-*.md, in
# name order, and the tables the cases last generated. Runs no case.
#
# In a section file, a line
#   <!-- include FILE: head -->   stands for FILE up to its first "## " heading,
#   <!-- include FILE: rest -->   for FILE from that heading to its end,
#   <!-- include FILE -->         for all of FILE but its "# " title line,
# where FILE is relative to verification/ (generated.md: the full run's main table, stiff and
# extreme cases and convergence ladders, written by verification/run.sh). Prints the PNGs in
# verification/ that the report does not show, and the images it shows that are missing.
# Usage: verification/assemble_report.sh [output, default verification/REPORT.md]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
/usr/bin/python3 - "$here" "${1:-$here/REPORT.md}" <<'PY'
import glob, os, re, sys

here, out = sys.argv[1], sys.argv[2]
directive = re.compile(r"^<!-- include (\S+?)(?:: (head|rest))? -->$")


def fragment(name, part):
    path = os.path.join(here, name)
    if not os.path.exists(path):
        sys.exit("assemble_report: %s is missing (run verification/run.sh first)" % path)
    lines = open(path).read().splitlines()
    cut = next((i for i, l in enumerate(lines) if l.startswith("## ")), len(lines))
    if part == "head":
        lines = lines[:cut]
    elif part == "rest":
        lines = lines[cut:]
    elif lines and lines[0].startswith("# "):
        lines = lines[1:]
    return "\n".join(lines).strip("\n")


sections = sorted(glob.glob(os.path.join(here, "report", "[0-9][0-9]-*.md")))
if not sections:
    sys.exit("assemble_report: no section files in %s/report" % here)
parts = []
for section in sections:
    body = []
    for line in open(section).read().splitlines():
        m = directive.match(line.strip())
        body.append(fragment(m.group(1), m.group(2)) if m else line)
    parts.append("\n".join(body).strip("\n"))
text = "\n\n".join(parts) + "\n"
with open(out + ".tmp", "w") as f:
    f.write(text)
os.replace(out + ".tmp", out)

shown = set(re.findall(r"!\[[^\]]*\]\(([^)\s]+\.png)\)", text))
for png in sorted(shown):
    if not os.path.exists(os.path.join(here, png)):
        print("assemble_report: shown but missing: %s" % png, file=sys.stderr)
for png in sorted(glob.glob(os.path.join(here, "*.png"))):
    if os.path.basename(png) not in shown:
        print("assemble_report: not shown in the report: %s" % os.path.basename(png),
              file=sys.stderr)
print("report: %s (%d sections)" % (out, len(sections)), file=sys.stderr)
PY
