# CLI tests of rk-extract silhouette (SPEC.md §1.1, §4; docs/rk-extract.md) on the rendered frames of the
# fixture sim_theodolite_trial, and malformed input.

# Sub-pixel points within 0.3 px of the exact projections, then the attitude from them.
rk_cli_script(rk_extract_silhouette/rk_extract_silhouette_good REQUIRES sim_theodolite_trial)

rk_cli_script(rk_extract_silhouette/rk_extract_silhouette_bad_input REQUIRES sim_theodolite_trial)
