# CLI tests of rk-smooth aukf (SPEC.md §1.1, §4). The fixture smooth_aukf_data writes small inputs to
# ${RK_CLI_DATA}/aukf; every other test here REQUIRES it.

rk_cli_script(rk_smooth_aukf/rk_smooth_aukf_data SETUP smooth_aukf_data)

rk_cli_script(rk_smooth_aukf/rk_smooth_aukf_good REQUIRES smooth_aukf_data)

rk_cli_script(rk_smooth_aukf/rk_smooth_aukf_bad REQUIRES smooth_aukf_data)

# Causality (issue: predictions used the future): truncating the input at a row leaves every earlier
# prediction and estimate row identical (values, rates, 1σ), with the default causal noise fit; with the old
# whole-file fit (--noise-fit file) they change, so the comparison can fail.
rk_cli_script(rk_smooth_aukf/rk_smooth_aukf_causal REQUIRES smooth_aukf_data)
