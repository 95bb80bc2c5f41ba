#!/usr/bin/env bash
# Fails if any of the given object files or binaries holds a packed fused multiply-add instruction
# (FMA3, FMA4 or AVX-512 forms): docs/theory.md section 18. Scalar ones are a library's explicit
# std::fma (CGAL's segment intersection), rounded once on every build, by the instruction or by
# the C library's fma where there is none; -ffp-contract=off forms no other.
# Usage: tests/check_no_fma.sh FILE...
set -euo pipefail
command -v objdump > /dev/null || { echo "objdump not found: skipped"; exit 77; }
status=0
for file in "$@"; do
  fused=$(objdump -d --no-show-raw-insn -C "$file" |
    awk '/^[0-9a-f]+ <.*>:$/ { fn = $0 } $2 ~ /^v?fn?m(add|sub)[a-z0-9]*p[sdh]$/ { n[fn]++ }
         END { for (f in n) print n[f], f }')
  if [[ -n $fused ]]; then
    echo "$file: packed fused multiply-adds (count, function):"
    echo "$fused"
    status=1
  fi
done
exit "$status"
