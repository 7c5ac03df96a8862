# CLI tests of rk-sim attitude (SPEC.md §4, docs/rk-sim.md). The fixture sim_attitude_small
# writes ${RK_CLI_DATA}/att_small: a 1000x800 sensor with the 100 mm lens (3.45 um pixels), the
# default 8-marker target at 40 m (markers ~8 px radius), 1 s at 10 fps (10 frames), the fin
# hidden for 0.3 s; rk-extract features and rk-attitude oi tests REQUIRE it.

rk_cli_script(rk_sim_attitude/rk_sim_attitude_small SETUP sim_attitude_small)

# Same seed → same truth; yaw across 0/360 and roll across ±180 written in their SPEC ranges.
rk_cli_script(rk_sim_attitude/rk_sim_attitude_wraps_and_determinism)

# Bad usage → 2, nothing written; bad target file → 3; unwritable → 4.
rk_cli_test(rk_sim_attitude_bad_bitdepth COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad1 "bit-depth" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad1 --bit-depth 12)
rk_cli_test(rk_sim_attitude_bad_hide COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad2 "nosecone" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad2 --hide nosecone:0:1)
rk_cli_test(rk_sim_attitude_hide_syntax COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad3 "ID:START_S:DURATION_S" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad3 --hide fin:1)
rk_cli_test(rk_sim_attitude_too_close COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/att_bad4 "leaves the 2448x2048 image" --
  $<TARGET_FILE:rk-sim> attitude --out ${RK_CLI_DATA}/att_bad4 --range-m 5 --approach-m 1 --return-m 1 --no-video)
rk_cli_script(rk_sim_attitude/rk_sim_attitude_bad_target)
rk_cli_script(rk_sim_attitude/rk_sim_attitude_refuses_nonempty_out)
