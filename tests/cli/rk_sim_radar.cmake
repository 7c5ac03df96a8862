# CLI tests of rk-sim radar (seed 002 scenarios; docs/rk-sim.md). The fixture sim_radar_data writes
# ${RK_CLI_DATA}/radar3 (scenario 3, 80 scans, seed 1) for rk-register's CLI tests to REQUIRE.

rk_cli_script(rk_sim_radar/rk_sim_radar_scenario3 SETUP sim_radar_data)

# Same seed → same files; another seed differs; options change what they say.
rk_cli_script(rk_sim_radar/rk_sim_radar_options)

rk_cli_test(rk_sim_radar_bad_scenario COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad1 "scenario" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad1 --scenario 4)
rk_cli_test(rk_sim_radar_bad_pd COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad2 "--pd must be in" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad2 --pd 0)
rk_cli_test(rk_sim_radar_bad_offset COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad3 "half the scan interval" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad3 --time-offset-b 3)
rk_cli_test(rk_sim_radar_bad_origin COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/radar_bad4 "origin" --
  $<TARGET_FILE:rk-sim> radar --out ${RK_CLI_DATA}/radar_bad4 --origin 25,110)
rk_cli_script(rk_sim_radar/rk_sim_radar_refuses_nonempty_out)
