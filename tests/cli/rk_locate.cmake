# CLI tests of rk-locate (SPEC.md §1.1, §4). The fixture locate_data writes
# tiny inputs to ${RK_CLI_DATA}/locate; every other test here REQUIRES it.

# Camera: default 50 mm / 3.45 µm; turret at 10 Hz through north; frames at
# 20 Hz; range at 5 Hz with one device-error row (status 7).
rk_cli_script(rk_locate/rk_locate_data SETUP locate_data)

# Good input: one row per track row, statuses, range statuses, report.
rk_cli_script(rk_locate/rk_locate_good REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_stdout REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_partial_turret_warns REQUIRES locate_data)

# Issue 28 item 4: the report's uniform keys. The turret warning on stderr and a row skipped under --bad-rows skip
# are typed warnings {code, message} in the report; rows_by_status counts the rows written; a headline.
rk_cli_script(rk_locate/rk_locate_report_typed_warnings REQUIRES locate_data)

rk_cli_script(rk_locate/rk_locate_bad_input REQUIRES locate_data)

# End to end on rk-sim's small trial: the truth beacon pixels as a perfect
# track. With the true turret the angles must match truth to < 0.05″ RMS
# (limited by the 1e-4 px rounding of truth/beacon.csv); with the logged
# turret (0.003° encoder steps) within 5″ RMS; range RMS ≤ 1 mm (issue target).
rk_cli_script(rk_locate/rk_locate_sim_small REQUIRES sim_small)

# Issue 17: --pointing (SPEC.md §3.1) and --station. A zero pointing model changes nothing (byte-identical
# output); a real one moves the azimuth by about its offset; the 1σ columns are always written and the
# WGS-84 ones with --station; the pointing model's σ reaches sigma_az_deg.
rk_cli_script(rk_locate/rk_locate_pointing REQUIRES locate_data)

# Bad pointing models, camera calibration σ and --station: SPEC.md §4 codes (4 unreadable, 3 malformed with
# the file and the key, 2 usage), one-line message, no output; rk-attitude reads the file the same way.
rk_cli_script(rk_locate/rk_locate_pointing_bad_input REQUIRES locate_data)

# Station errors end to end (rk-sim beacon --az-offset-deg ... --time-offset-s): the truth beacon pixels as a
# perfect track, the logged (quantised) turret. With truth/pointing.json rk-locate's az/el RMS is within 1.1×
# (+0.2″) of the perfect station's (same seed); without it the error is degrees.
rk_cli_script(rk_locate/rk_locate_station_errors)

# A points track (rk-extract points: an id column) is one located series per id: the id after t_s, the ids of a
# frame together; each id's rows equal those of the same pixels given as a beacon track.
rk_cli_script(rk_locate/rk_locate_points_ids REQUIRES locate_data)
