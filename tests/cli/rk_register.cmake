# CLI tests of rk-register bernoulli|kf|batch (SPEC.md §1.1, §2.1, §4; docs/rk-register.md). They
# REQUIRE the fixture sim_radar_data (rk_sim_radar.cmake: ${RK_CLI_DATA}/radar3, scenario 3, 80
# scans).

rk_cli_script(rk_register/rk_register_good REQUIRES sim_radar_data)

# Radar b reports 0.3 s after radar a, and the nav is a 1 Hz log: steps pair by time, nav is
# interpolated; rows carry the later time.
rk_cli_script(rk_register/rk_register_time_offset)

rk_cli_script(rk_register/rk_register_bad_input REQUIRES sim_radar_data)

# 2-D radars (docs/rk-register.md "2-D radars"): rk-sim radar --2d; the el bias of the 2-D radar empty with a
# warning, the others within 4.5 sigma of the truth; both 2-D refused (exit 1); ASTERIX columns ignored; a
# non-numeric el_deg still exit 3 with file:line:col.
rk_cli_script(rk_register/rk_register_two_d)
