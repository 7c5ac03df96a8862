# CLI tests of rk-locate (SPEC.md §1.1, §4). The fixture locate_data writes
# tiny inputs to ${RK_CLI_DATA}/locate; every other test here REQUIRES it.

# Camera: default 50 mm / 3.45 µm; turret at 10 Hz through north; frames at
# 20 Hz; range at 5 Hz with one device-error row (status 7).
rk_cli_script(rk_locate/rk_locate_data SETUP locate_data)

# Good input: one row per track row, statuses, range statuses, report.
rk_cli_script(rk_locate/rk_locate_good REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_stdout REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_partial_turret_warns REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_bad_input REQUIRES locate_data)

# End to end on rk-sim's small trial: the truth beacon pixels as a perfect
# track. With the true turret the angles must match truth to < 0.05″ RMS
# (limited by the 1e-4 px rounding of truth/beacon.csv); with the logged
# turret (0.003° encoder steps) within 5″ RMS; range RMS ≤ 1 mm (issue target).
rk_cli_script(rk_locate/rk_locate_sim_small REQUIRES sim_small)
