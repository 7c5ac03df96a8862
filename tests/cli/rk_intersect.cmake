# CLI tests of rk-intersect (SPEC.md §7, §4). The fixture intersect_data writes an rk-sim multistation trial
# (three stations, 5 s) and bad stations files to ${RK_CLI_DATA}/intersect; the other tests REQUIRE it.
# Decisions (docs/rk-intersect.md "Errors"): fewer than two stations is invalid input (exit 3, at the
# "stations" array's line:column); stations whose times never overlap is invalid input too (exit 3, naming
# stations.json and each station's time span), as rk-locate's turret log that covers no frame.
rk_cli_script(rk_intersect/rk_intersect_data SETUP intersect_data)

# Good input: one row per union time, columns, statuses, error against truth within 5 σ, report, stdout.
rk_cli_script(rk_intersect/rk_intersect_good REQUIRES intersect_data)

# Bad input: exit codes 2/3/4, one-line errors with file:line:col, no partial output.
rk_cli_script(rk_intersect/rk_intersect_bad_input REQUIRES intersect_data)

# Located files with ids (rk-locate of points tracks): one trajectory per id, the id after t_s; each id's rows
# equal the trajectory of the same rows without ids; an id seen by one station only gets none and a warning.
rk_cli_script(rk_intersect/rk_intersect_ids REQUIRES intersect_data)

# A duplicated record (a row written twice): in a located file without ids and, for one (id, time), in a file
# with ids. Without --bad-rows skip exit 3 at the copy's file:line:col, no output, the failure report; with it
# the copy is dropped with a warning naming it and the trajectory equals the one from the files without it.
rk_cli_script(rk_intersect/rk_intersect_duplicates REQUIRES intersect_data)

# Station clock offsets (SPEC §7, issue 33): rk-sim multistation --time-offsets, rk-intersect
# --estimate-time-offsets (report time_offsets within 3 σ of the truth, no warning on a climbing turn, the
# trajectory much closer than without), a known time_offset_s applied, another time reference, and bad
# stations files (a non-numeric offset, two references, a reference not true/false, one station): exit 3 at
# their line:column, no output.
rk_cli_script(rk_intersect/rk_intersect_offsets)
