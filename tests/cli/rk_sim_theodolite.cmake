# CLI tests of rk-sim theodolite (SPEC.md §4, docs/rk-sim.md). The fixture sim_theodolite_trial writes
# ${RK_CLI_DATA}/theo_trial (640x640 sensor of seed 004's optics, 5 frames with PNG images) for the
# rk-attitude cylinder and rk-extract silhouette CLI tests to REQUIRE.

rk_cli_script(rk_sim_theodolite/rk_sim_theodolite_trial SETUP sim_theodolite_trial)

# Quantised points are whole pixels; --angle-budget seed004 biases the log; same seed → same files.
rk_cli_script(rk_sim_theodolite/rk_sim_theodolite_quantise_budget)

# Bad usage → 2, nothing written; unwritable → 4.
rk_cli_test(rk_sim_theodolite_bad_range COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad1 "range" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad1 --range-m 5)
rk_cli_test(rk_sim_theodolite_bad_images COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad2 "images" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad2 --images gif)
rk_cli_test(rk_sim_theodolite_budget_and_bias COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad3 "angle-budget" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad3 --angle-budget seed004 --angle-bias-arcsec 3)
rk_cli_test(rk_sim_theodolite_leaves_image COMMAND ${RK_EXPECT} 2 ${RK_CLI_DATA}/theo_bad4 "leaves the" --
  $<TARGET_FILE:rk-sim> theodolite --out ${RK_CLI_DATA}/theo_bad4 --sensor-px 128)
rk_cli_script(rk_sim_theodolite/rk_sim_theodolite_refuses_nonempty_out)
rk_cli_script(rk_sim_theodolite/rk_sim_theodolite_unwritable_out)
