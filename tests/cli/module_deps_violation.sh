#!/usr/bin/env bash
# scripts/check_module_deps.py must fail, naming file:line, when an estimator includes the simulator, and
# when a module is missing from docs/architecture.md's graph.
#   module_deps_violation.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1; w=$2
rm -rf "$w"; mkdir -p "$w/lib" "$w/docs"
cp -r "$src/lib/." "$w/lib/"
cp "$src/docs/architecture.md" "$w/docs/"
python3 "$src/scripts/check_module_deps.py" "$w" > "$w/clean.txt"
f=$(ls "$w"/lib/attitude/*.cc | head -n 1)
sed -i '1i #include "sim/trial_writer.h"' "$f"
if python3 "$src/scripts/check_module_deps.py" "$w" > "$w/out.txt"; then echo "violation not caught"; exit 1; fi
grep -q "^lib/attitude/$(basename "$f"):1: module 'attitude' includes 'sim/...'" "$w/out.txt"
mkdir -p "$w/lib/newmod"; echo 'rk_add_module(newmod)' > "$w/lib/newmod/CMakeLists.txt"
python3 "$src/scripts/check_module_deps.py" "$w" > "$w/out2.txt" && { echo "missing module not caught"; exit 1; }
grep -q "module 'newmod' (lib/newmod) is not in the module graph" "$w/out2.txt"
