# CLI tests of rk-smooth singer (SPEC.md §1.1, §4). The fixture smooth_singer_data writes
# small inputs to ${RK_CLI_DATA}/singer; every other test here REQUIRES it.

rk_cli_script(rk_smooth_singer/rk_smooth_singer_data SETUP smooth_singer_data)

rk_cli_script(rk_smooth_singer/rk_smooth_singer_good REQUIRES smooth_singer_data)

# Bad input: SPEC.md §4 exit codes, one-line errors naming file:line:col, no output.
rk_cli_script(rk_smooth_singer/rk_smooth_singer_bad REQUIRES smooth_singer_data)
