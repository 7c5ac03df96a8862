# CLI tests of rk-export (issue 34; docs/rk-export.md). The fixture export_data writes an rk-sim multistation trial
# (three stations, 5 s), its rk-intersect trajectory, a copy with two ids (one with lost rows) and a located target
# with WGS-84 columns (rows without a range have no position) to ${RK_CLI_DATA}/export.
rk_cli_script(rk_export/export_cli_data SETUP export_data)

# Good input: KML and CZML of the trajectory, of the ids and of the located target; coordinates equal the CSV's
# WGS-84 columns to 1e-7 deg (heights to 1 µm, less --geoid-undulation in KML), KML time stamps = epoch + t_s, the
# CZML packets as its specification describes them (rk_export/check_export.py); -o - equals -o FILE; stdin input;
# the report; --bad-rows skip; the CZML warning without an epoch.
rk_cli_script(rk_export/export_cli_good REQUIRES export_data)

# The KML files validate against the OGC KML 2.2 schema with xmllint --schema (--nonet): the schema ogckml22.xsd with
# its atom-author-link.xsd and xAL.xsd taken out of Debian's pytrainer package by scripts/setup.sh --kml-schema
# (build-cache/kml-schema/; or an installed pytrainer's, or where $RK_KML_SCHEMA names it); skipped (77) without
# xmllint or the schema.
rk_cli_script(rk_export/export_cli_kml_schema REQUIRES export_data)
set_tests_properties(export_cli_kml_schema PROPERTIES SKIP_RETURN_CODE 77)

# Bad input: exit 3 with file:line:col (a missing column, an unknown status, an ok row without its position, a located
# target without WGS-84 columns naming the file), 1 when no row has a position, 2 for usage (no input or two, a bad
# --epoch-utc, an option out of range, -o naming the input), 4 for I/O; one line on stderr, no output left.
rk_cli_script(rk_export/export_cli_bad_input REQUIRES export_data)
