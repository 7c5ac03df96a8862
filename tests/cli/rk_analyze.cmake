# CLI tests of rk-analyze compare (SPEC.md §1.1, §4). The fixture
# analyze_data writes tiny estimate/reference files to ${RK_CLI_DATA}/analyze.

# Reference: az through north, range linear. Estimate errors by hand:
#   t=0.5: az 359.99 vs 0.0 → −0.01°, range 101.5 vs 101 → +0.5
#   t=1.5: az 0.25 vs 0.2 → +0.05°,   range 102.9 vs 103 → −0.1
#   t=2.5: az empty (skipped), range outside the reference (skipped)
rk_cli_script(rk_analyze/rk_analyze_data SETUP analyze_data)

rk_cli_script(rk_analyze/rk_analyze_good REQUIRES analyze_data)

rk_cli_script(rk_analyze/rk_analyze_bad_input REQUIRES analyze_data)
