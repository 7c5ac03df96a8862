# The whole beacon chain on the sim_small trial (rk_sim.cmake): extract → locate → compare vs truth.
rk_cli_test(rk_chain_beacon_small REQUIRES sim_small
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/chain_check.sh ${RK_CLI_DATA}/small ${RK_CLI_DATA}/chain_small ${RK_SOURCE_DIR})
