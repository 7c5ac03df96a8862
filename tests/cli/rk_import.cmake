# CLI tests of rk-import frames (SPEC.md §1.1 "Recordings", §2.1 video frame times, §4; docs/rk-import.md): a
# recording's own times from real files (../shared/data/real: skipped, exit 77, when absent), synthetic CINE,
# MRAW and rk-capture segments (rk_import/make_recordings.py), a container's times, and malformed files.
set(RKI_DIR ${RK_CLI_DATA}/import)
rk_cli_test(import_cli_inputs SETUP import_inputs REQUIRES extract_inputs COMMAND ${RK_TEST_PYTHON}
            ${CMAKE_CURRENT_SOURCE_DIR}/rk_import/make_recordings.py ${RKI_DIR} ${RK_CLI_DATA}/extract/beacon.mkv)

# Real files: ball_12bit.mraw (15 frames at 30 000 fps from frame 52, 20 µs, nominal) and chart1.cine (its time
# block, not IRIG-synchronised, against --epoch-utc; the trigger time of 2014 said as a disagreement).
rk_cli_script(rk_import/import_cli_real_files)
set_tests_properties(import_cli_real_files PROPERTIES SKIP_RETURN_CODE 77)
# Synthetic: an MRAW's nominal times; a CINE's IRIG stamps against --epoch-utc with the gap (frame 3) and the step
# back (frame 4) reported, never renumbered; rk-capture's segments (host times from its frames.csv); an MKV's
# container times; an image sequence with --fps; the report's headline and warnings.
rk_cli_script(rk_import/import_cli_sources REQUIRES import_inputs)
# The other tools take the same times without --frames/--fps: rk-extract beacon on the beacon as an MRAW gives the
# rows of the MKV with --fps 20; a time going back stops it (exit 3, the frame named); rk-calibrate lens
# --images reads a board recording as an MRAW like its image sequence.
rk_cli_script(rk_import/import_cli_tools_take_file_times REQUIRES import_inputs)

# Malformed input: exit 3 with the byte offset or the header line, no output, --report still written; a missing
# header (4); no times for an image sequence without --fps, a bad --epoch-utc (2).
rk_cli_script(rk_import/import_cli_bad_input REQUIRES import_inputs)

# rk-import asterix. Synthetic feeds (rk_import/make_asterix.py, written without rangekit's code): a redundant feed
# over midnight into 24 plots in time order with el from the 3-D radar's height and azimuths across 0/360, CAT034
# north markers into the scan period, the same plots from a raw .ast stream; bad records skipped with their byte
# offset or (--bad-records error) exit 3 with no output; radars.json errors with line:column; a fake .pcap.
rk_cli_script(rk_import/import_cli_asterix)
# The real radar feed against Wireshark's own ASTERIX dissector (tshark; skipped, exit 77, without it or the file).
rk_cli_script(rk_import/import_cli_asterix_real)
set_tests_properties(import_cli_asterix_real PROPERTIES SKIP_RETURN_CODE 77)
