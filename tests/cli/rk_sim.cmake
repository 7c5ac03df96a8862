# CLI tests of rk-sim (SPEC.md §4). The fixture sim_small writes the trial
# ${RK_CLI_DATA}/small that other tools' CLI tests REQUIRE:
#   small preset (640x512), 3 s at 20 fps (60 frames), FFV1 mkv, seed 1, one
#   0.5 s occlusion from 1.5 s after frame 0 (frames 30-39), one distractor; the
#   range error rate is raised to 0.05 so that the 3 s range log contains a
#   device-error row (status 255, empty range_m).
set(RK_SIM $<TARGET_FILE:rk-sim>)

rk_cli_script(rk_sim/rk_sim_small SETUP sim_small)

# Same seed → identical trial (apart from the manifest's name); PNG, 16-bit, report.
rk_cli_script(rk_sim/rk_sim_deterministic_png16)

# Bad usage → 2, nothing written.
rk_cli_test(rk_sim_unknown_option COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad1 --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad1 --preset small --bogus 1)
rk_cli_test(rk_sim_no_subcommand COMMAND ${RK_EXPECT} 2 - -- ${RK_SIM} --out ${RK_CLI_DATA}/sim_bad2)
rk_cli_test(rk_sim_missing_out COMMAND ${RK_EXPECT} 2 - "--out" -- ${RK_SIM} beacon --preset small)
rk_cli_test(rk_sim_bad_lamps COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad3 "lamps" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad3 --preset small --duration 0.5 --lamps 3)
rk_cli_test(rk_sim_bad_occlusion COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad4 "occlusion" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad4 --preset small --duration 0.5 --occlusion 1.5)
rk_cli_test(rk_sim_bad_range COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad5 "range" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad5 --preset small --duration 0.5 --range-m 5)
rk_cli_test(rk_sim_bad_format COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad6 --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad6 --preset small --duration 0.5 --format avi)
rk_cli_test(rk_sim_target_leaves_image COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad7 "leaves the image" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad7 --preset small --duration 2 --trajectory straight
  --range-m 20 --speed-mps 100)

# Existing non-empty --out without --force → 2, and the folder is left exactly as it was.
rk_cli_script(rk_sim/rk_sim_refuses_nonempty_out)

# Unwritable --out → 4, nothing written.
rk_cli_script(rk_sim/rk_sim_unwritable_out)
# --servo-hold (issue 15 item 2): malformed → 2 naming the option; a good one is recorded in the report.
rk_cli_test(rk_sim_bad_servo_hold COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_bad_hold "servo-hold" --
  ${RK_SIM} beacon --out ${RK_CLI_DATA}/sim_bad_hold --preset small --duration 0.5 --servo-hold 0.2)
rk_cli_script(rk_sim/rk_sim_servo_hold_report)
# Options from the tables (issue 16 item 1): one message form per subcommand and nested table, report keys.
rk_cli_script(rk_sim/rk_sim_option_bounds)
# rk-sim points (issue 31): files, columns, a re-seed row at the truth, the report; bad values → 2, one line.
rk_cli_script(rk_sim/rk_sim_points)
rk_cli_test(rk_sim_points_bad_bits COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_points_bad1 "bits" --
  ${RK_SIM} points --out ${RK_CLI_DATA}/sim_points_bad1 --frames 3 --bits 12)
rk_cli_test(rk_sim_points_bad_reseed COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_points_bad2 "re-seed id 'q9'" --
  ${RK_SIM} points --out ${RK_CLI_DATA}/sim_points_bad2 --frames 3 --reseed q9:1)
rk_cli_test(rk_sim_points_bad_exposure COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/sim_points_bad3 "exposure" --
  ${RK_SIM} points --out ${RK_CLI_DATA}/sim_points_bad3 --frames 3 --fps 1000 --exposure 0.002)
