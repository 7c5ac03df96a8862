#!/usr/bin/env bash
# scripts/long_functions.py --check must fail, naming file:line, on a function over 120 lines without a
# reason written above it, and pass once the reason is there.
#   long_functions_violation.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1; w=$2
rm -rf "$w"; mkdir -p "$w"
{
  echo 'int Long(int x) {'
  for i in $(seq 1 125); do echo "  x += $i;"; done
  echo '  return x;'
  echo '}'
} > "$w/long.cc"
if python3 "$src/scripts/long_functions.py" --check "$w" > "$w/out.txt" 2> "$w/err.txt"; then
  echo "long function not caught"; exit 1
fi
grep -q "long.cc:1: Long: 128 lines" "$w/out.txt" "$w/err.txt"
sed -i '1i // Long function: one straight sequence of steps (a test input).' "$w/long.cc"
python3 "$src/scripts/long_functions.py" --check "$w" > "$w/out2.txt" || { echo "reason not accepted"; exit 1; }
