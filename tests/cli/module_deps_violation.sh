#!/usr/bin/env bash
# scripts/check_module_deps.py must fail, naming file:line, when an estimator includes the simulator, and
# when a module is missing from docs/architecture.md's graph, when a CMake list disagrees with the graph and when
# a module other than geo includes GeographicLib.
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
# The graph's second copy: a module's CMake list that links a module its row does not name (issue 28).
rm -rf "$w/lib/newmod"; cp -r "$src/lib/intersect" "$w/lib/intersect.orig"
sed -i 's/PRIVATE rangekit::track rangekit::numeric /PRIVATE rangekit::track rangekit::numeric rangekit::sim /' \
  "$w/lib/intersect/CMakeLists.txt"
grep -q "rangekit::sim" "$w/lib/intersect/CMakeLists.txt"
python3 "$src/scripts/check_module_deps.py" "$w" > "$w/out3.txt" && { echo "CMake list not checked"; exit 1; }
grep -q "^lib/intersect/CMakeLists.txt: rk_add_module lists .*(not in the row: sim)" "$w/out3.txt"
rm -rf "$w/lib/intersect"; mv "$w/lib/intersect.orig" "$w/lib/intersect"
# GeographicLib belongs to geo: another module including it is caught at its line.
sed -i '1i #include <GeographicLib/Geocentric.hpp>' "$w/lib/registration/radar_model.cc"
python3 "$src/scripts/check_module_deps.py" "$w" > "$w/out4.txt" && { echo "GeographicLib outside geo not caught"; exit 1; }
grep -q "^lib/registration/radar_model.cc:1: GeographicLib belongs to module 'geo'" "$w/out4.txt"
echo ok
