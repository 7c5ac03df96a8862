# CLI tests of --bad-rows (every tool that reads CSV) and of the report of a failed run (--report on
# every tool). Each test uses another tool's fixture; its script (tests/cli/rk_bad_rows/) sources
# tests/cli/bad_rows.sh (dirty, report_ok, fails). For --bad-rows skip the check is always the
# same: a copy of the input with bad rows added (bad_rows.sh `dirty`) and --bad-rows skip gives
# byte-identical output to the clean input, the report counts the rows skipped, stderr names each
# one, and without the option the tool still stops at the first with exit 3 and file:line:col.

rk_cli_script(rk_bad_rows/rk_bad_rows_locate REQUIRES locate_data)

rk_cli_script(rk_bad_rows/rk_bad_rows_extract REQUIRES extract_inputs)

# Issue 27 items 13 and 14 on rk-extract's frames.csv: under skip, a skipped row's frame number is a hole (not
# measured, one warning) while a frame number wrong for another reason stays an error; pandas-style frame
# numbers (+0, 1.0, 2e0), a UTF-8 byte-order mark and quoted fields (a newline inside one) read as the clean
# file, with the file's own line numbers; UTF-16 is named as such (exit 3).
rk_cli_script(rk_bad_rows/rk_bad_rows_frames_forms REQUIRES extract_inputs)

rk_cli_script(rk_bad_rows/rk_bad_rows_extract_features REQUIRES sim_attitude_small)

rk_cli_script(rk_bad_rows/rk_bad_rows_extract_silhouette REQUIRES sim_theodolite_trial)

rk_cli_script(rk_bad_rows/rk_bad_rows_smooth REQUIRES smooth_aukf_data)

rk_cli_script(rk_bad_rows/rk_bad_rows_attitude REQUIRES sim_attitude_small)

rk_cli_script(rk_bad_rows/rk_bad_rows_attitude_cylinder REQUIRES sim_theodolite_trial)

rk_cli_script(rk_bad_rows/rk_bad_rows_register REQUIRES sim_radar_data)

rk_cli_script(rk_bad_rows/rk_bad_rows_analyze REQUIRES analyze_data)

# Tools that read no CSV still write the report of a failed run: rk-sim, rk-capture, rk-run.
rk_cli_script(rk_bad_rows/rk_failure_report_sim_capture_run)
