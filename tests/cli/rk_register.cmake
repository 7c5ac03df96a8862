# CLI tests of rk-register bernoulli|kf|batch (SPEC.md §1.1, §2.1, §4; docs/rk-register.md). They
# REQUIRE the fixture sim_radar_data (rk_sim_radar.cmake: ${RK_CLI_DATA}/radar3, scenario 3, 80
# scans).

rk_cli_script(rk_register/rk_register_good REQUIRES sim_radar_data)

# Radar b reports 0.3 s after radar a, and the nav is a 1 Hz log: steps pair by time, nav is
# interpolated; rows carry the later time.
rk_cli_script(rk_register/rk_register_time_offset)

rk_cli_script(rk_register/rk_register_bad_input REQUIRES sim_radar_data)
