#!/usr/bin/env bash
# Golden outputs for a change that must not move a result (a refactor):
#   scripts/golden-outputs.sh run VORODEC_BINARY DIR   # every model's outputs into DIR
#   scripts/golden-outputs.sh compare DIR_BEFORE DIR_AFTER
# `run` runs every model in models/ for 2000 steps and every model in tests/models/ to its end (both
# on one thread, batch files with their cases' outputs). `compare` wants every file byte-identical,
# but summary.json and a batch's results files, which are compared parsed with the wall times left
# out (a refactor may change their layout and add keys, which it lists, never change a value).
set -uo pipefail
root="${VORODEC_ROOT:-$(cd "$(dirname "$0")/.." && pwd)}"  # the checkout whose models run

run_all() {
  local bin="$1" out="$2"
  mkdir -p "$out"
  for model in "$root"/models/*.toml "$root"/tests/models/*.toml; do
    local name dir steps=()
    name="$(basename "$(dirname "$model")")_$(basename "$model" .toml)"
    dir="$out/$name"
    [[ "$model" == "$root/models/"* ]] && steps=(--max-steps 2000)
    case "$(basename "$model")" in
      calibrate_*) continue ;;  # an hour each; tests/test_calibrate.cpp pins the small one
      batch_*) "$bin" batch "$model" "${steps[@]}" --jobs 1 --out "$dir" > "$dir.log" 2>&1 ;;
      *) "$bin" run "$model" "${steps[@]}" --threads 1 --out "$dir" > "$dir.log" 2>&1 ;;
    esac
    echo "$name exit $?" | tee -a "$out/exit_codes.txt"
  done
}

compare_all() {
  local a="$1" b="$2" bad=0
  while IFS= read -r -d '' f; do
    local rel="${f#"$a"/}"
    if [[ ! -e "$b/$rel" ]]; then
      echo "missing after: $rel"; bad=1; continue
    fi
    case "$rel" in
      *.log | */log.txt | */case_outcome.txt | */case_command.txt) ;;  # timings and paths
      *summary.json) /usr/bin/python3 - "$f" "$b/$rel" <<'EOF' || { echo "differs: $rel"; bad=1; }
import json, sys
def same(a, b, path=""):
    """b holds every value of a unchanged (wall times aside); keys only b has are reported."""
    if isinstance(a, dict) and isinstance(b, dict):
        ok = True
        for k in b.keys() - a.keys():
            print(f"  {sys.argv[2]}: new key {path}/{k}")
        for k, v in a.items():
            if k in ("wall_time_s", "solve_wall_time_s"):
                continue
            ok = k in b and same(v, b[k], f"{path}/{k}") and ok
        return ok
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y, path) for x, y in zip(a, b))
    return a == b
a, b = (json.load(open(p)) for p in sys.argv[1:3])
sys.exit(0 if same(a, b) else 1)
EOF
        ;;
      *results.csv) /usr/bin/python3 - "$f" "$b/$rel" <<'PY' || { echo "differs: $rel"; bad=1; }
import csv, sys
def rows(p):
    r = list(csv.reader(open(p)))
    keep = [i for i, k in enumerate(r[0]) if k != "wall_time_s"]
    return [[row[i] for i in keep if i < len(row)] for row in r]
sys.exit(0 if rows(sys.argv[1]) == rows(sys.argv[2]) else 1)
PY
        ;;
      *)
        cmp -s "$f" "$b/$rel" || { echo "differs: $rel"; bad=1; } ;;
    esac
  done < <(find "$a" -type f -print0 | sort -z)
  while IFS= read -r -d '' f; do
    [[ -e "$a/${f#"$b"/}" ]] || { echo "new after: ${f#"$b"/}"; bad=1; }
  done < <(find "$b" -type f -print0 | sort -z)
  [[ $bad -eq 0 ]] && echo "golden outputs: identical"
  return $bad
}

case "${1:-}" in
  run) run_all "$2" "$3" ;;
  compare) compare_all "$2" "$3" ;;
  *) echo "usage: $0 run BINARY DIR | compare DIR_BEFORE DIR_AFTER" >&2; exit 2 ;;
esac
