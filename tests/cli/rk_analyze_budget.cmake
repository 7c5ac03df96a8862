# CLI tests of rk-analyze budget (docs/rk-analyze.md): the seed 004 budget shipped in data/seed004, an inline
# locate budget, malformed budgets.

# Seed 004 §4.1: the eight angle errors combine to 5.215'; Jacobian and Monte Carlo side by side.
rk_cli_script(rk_analyze_budget/rk_analyze_budget_seed004)

rk_cli_script(rk_analyze_budget/rk_analyze_budget_locate)

rk_cli_script(rk_analyze_budget/rk_analyze_budget_bad)

# Issue 28 item 1: the locate model's line of sight is rk-locate's, pointing model included. A pointing.json beside
# the budget (with σ from rk-calibrate pointing) and a camera with a calibrated mount σ add their σ as sources; the
# azimuth σ grows by the az_offset σ in quadrature; a malformed pointing file is exit 3 at its line:col, and
# "pointing" in a cylinder budget is exit 3.
rk_cli_script(rk_analyze_budget/rk_analyze_budget_pointing)
