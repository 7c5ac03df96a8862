# CLI tests of rk-sim posetrack (SPEC.md §4, docs/rk-sim.md). The fixture
# sim_posetrack_turntable writes ${RK_CLI_DATA}/posetrack_turntable (seed 000's turntable
# experiment, seed 1: 181 samples 0-9 s, 180 mid-times) for rk-smooth's CLI tests to REQUIRE.

rk_cli_script(rk_sim_posetrack/rk_sim_posetrack_turntable SETUP sim_posetrack_turntable)

# Head scenario: yaw written in [0, 360) and crossing north; same seed → same files; dropout rows empty.
rk_cli_script(rk_sim_posetrack/rk_sim_posetrack_head)

# Bad usage → 2, nothing written.
rk_cli_test(rk_sim_posetrack_unknown_scenario COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad1 "scenario" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad1 --scenario spin)
rk_cli_test(rk_sim_posetrack_bad_noise COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad2 "--noise-deg must be in" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad2 --noise-deg -1)
rk_cli_test(rk_sim_posetrack_rate_with_head COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad3 "turntable only" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad3 --scenario head --rate-deg-s 5)
rk_cli_test(rk_sim_posetrack_bad_dropout COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/pt_bad4 "dropout" --
  $<TARGET_FILE:rk-sim> posetrack --out ${RK_CLI_DATA}/pt_bad4 --dropout 1)
rk_cli_script(rk_sim_posetrack/rk_sim_posetrack_refuses_nonempty_out)
rk_cli_script(rk_sim_posetrack/rk_sim_posetrack_unwritable_out)
