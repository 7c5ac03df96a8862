# CLI tests of rk-smooth resample (SPEC.md §1.1, §4). The fixture smooth_resample_data writes
# small inputs to ${RK_CLI_DATA}/resample; every other test here REQUIRES it.

rk_cli_script(rk_smooth_resample/rk_smooth_resample_data SETUP smooth_resample_data)

rk_cli_script(rk_smooth_resample/rk_smooth_resample_good REQUIRES smooth_resample_data)

rk_cli_script(rk_smooth_resample/rk_smooth_resample_bad REQUIRES smooth_resample_data)
