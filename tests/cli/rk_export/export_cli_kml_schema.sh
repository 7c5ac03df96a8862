#!/usr/bin/env bash
# CLI test export_cli_kml_schema: registered, and described, in tests/cli/rk_export.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
# The schema: $RK_KML_SCHEMA, else where scripts/setup.sh --kml-schema puts it, else an installed pytrainer's.
schema=${RK_KML_SCHEMA:-$src/build-cache/kml-schema/usr/share/pytrainer/schemas/ogckml22.xsd}
[ -r "$schema" ] || schema=/usr/share/pytrainer/schemas/ogckml22.xsd
command -v xmllint >/dev/null || { echo "SKIPPED: no xmllint (Debian package libxml2-utils)"; exit 77; }
[ -r "$schema" ] || { echo "SKIPPED: no OGC KML 2.2 schema at $schema (scripts/setup.sh --kml-schema; or set RK_KML_SCHEMA)"; exit 77; }
grep -q 'ogckml22.xsd 2008-01-23' "$schema" || { echo "$schema is not the OGC KML 2.2 schema"; exit 1; }
d=$data/export; o=$d/schema; rm -rf "$o"; mkdir -p "$o"
E=2026-01-01T06:30:00Z
rk-export kml --trajectory "$d/traj.csv" --epoch-utc "$E" -o "$o/t.kml"
rk-export kml --trajectory "$d/traj.csv" --sample-interval 0 --extrude --name 'a <b> & "c"' -o "$o/all.kml"
rk-export kml --trajectory "$d/ids.csv" --epoch-utc "$E" -o "$o/ids.kml"
rk-export kml --located "$d/located.csv" -o "$o/loc.kml"
# --nonet: the schema's imports (atom-author-link.xsd, xAL.xsd) are read beside it, never fetched.
xmllint --noout --nonet --schema "$schema" "$o/t.kml" "$o/all.kml" "$o/ids.kml" "$o/loc.kml"
# The check checks: an element out of the schema's order fails.
sed 's|<styleUrl>#path-0</styleUrl>|<styleUrl>#path-0</styleUrl><name>x</name>|' "$o/t.kml" > "$o/broken.kml"
if xmllint --noout --nonet --schema "$schema" "$o/broken.kml" 2>/dev/null; then echo "an invalid KML validated"; exit 1; fi
echo ok
