# CLI tests of rk-calibrate pointing and rk-sim pointing (SPEC.md §1.1, §3.1, §4; docs/rk-calibrate.md).
# The fixture pointing_data simulates a small session (8 landmarks, 10 stars) into ${RK_CLI_DATA}/pointing.
rk_cli_script(rk_calibrate_pointing/rk_calibrate_pointing_data SETUP pointing_data)

# Good input: pointing.json (SPEC.md §3.1 keys, sigma, correlation, residuals), --camera-out with
# calibration.sigma, the plot, the report; the truth is within 5σ.
rk_cli_script(rk_calibrate_pointing/rk_calibrate_pointing_good REQUIRES pointing_data)

# Bad input: unknown target id, stars without --epoch-utc, a star below the horizon, a turret log that does not
# cover an observation, too few observations, a malformed CSV, an unknown --estimate term, a missing file.
rk_cli_script(rk_calibrate_pointing/rk_calibrate_pointing_bad_input REQUIRES pointing_data)

# End to end (issue 17): a station with every SPEC.md §3.1 error calibrated by rk-calibrate pointing; its
# pointing.json and --camera-out camera locate the session's validation track within 10 % of the true model's
# and of a perfect station's az/el RMS; without --pointing the azimuth is 137° off.
rk_cli_script(rk_calibrate_pointing/rk_calibrate_pointing_end_to_end)
