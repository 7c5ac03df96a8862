# CLI tests of rk-analyze budget (docs/rk-analyze.md): the seed 004 budget shipped in data/seed004, an inline
# locate budget, malformed budgets.

# Seed 004 §4.1: the eight angle errors combine to 5.215'; Jacobian and Monte Carlo side by side.
rk_cli_script(rk_analyze_budget/rk_analyze_budget_seed004)

rk_cli_script(rk_analyze_budget/rk_analyze_budget_locate)

rk_cli_script(rk_analyze_budget/rk_analyze_budget_bad)
