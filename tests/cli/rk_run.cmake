# CLI tests of rk-run, rk-nightly and the kill -9 safety target (docs/rk-run.md). Every test copies the
# sim_small trial (rk_sim.cmake: 60 frames of 640x512, range log with a device-error row, truth) into
# its own folder under ${RK_CLI_DATA}/run, because rk-run writes into the trial folder.
# The scripts (tests/cli/rk_run/) source rk_run/lib.sh (check_out, fresh, json).

# The beacon chain end to end: every product, report.json (inputs with checksums that sha256sum agrees
# with, tool versions, timings, quality figures), PNG plots, and the located target against truth with
# the tolerances of rk_chain_beacon_small (same tools, same trial: 5" in angle for the turret log's
# 0.003 deg encoder steps, 1 mm in range).
rk_cli_script(rk_run/rk_run_beacon_chain REQUIRES sim_small)

# Idempotence: unchanged → nothing runs and out/ is the same folder; touch → still up to date (content
# hash); a step option → that step and everything downstream; a changed input → its steps; --force → all.
rk_cli_script(rk_run/rk_run_skip_logic REQUIRES sim_small)

# A failing run leaves the previous good out/ exactly as it was, exits with the step's SPEC code and a
# one-line error naming file:line:col, removes its temporary folder, and records the tool's stderr.
rk_cli_script(rk_run/rk_run_failure_keeps_out REQUIRES sim_small)

# The lock: a second run of the same trial exits at once (4) while the first holds it, or waits with
# --wait-lock; stale temporaries and an interrupted two-rename swap are repaired by the next run.
rk_cli_script(rk_run/rk_run_lock_and_recovery REQUIRES sim_small)

# Malformed manifests and usage: SPEC codes, one-line errors with trial.json:LINE:COL.
rk_cli_script(rk_run/rk_run_bad_input REQUIRES sim_small)

# The plan per unit (issue 20): one line per camera / unit / unused log on stderr and in report.json and
# last-run.json (planned steps, skipped steps and why), none with --quiet; a theodolite trial with no images
# says there is nothing to run; a product the manifest asks for that cannot be made (a "steps" key, a camera's
# role) is exit 3 at its line:col; a radar block without nav and a silhouette camera without target are
# manifest errors; a chain switched off asks for nothing.
rk_cli_script(rk_run/rk_run_plan_by_unit REQUIRES sim_small)

# Several stations (issue 18, docs/rk-run.md "Several stations"): rk-sim multistation --video writes a
# three-station trial (rendered frames, turret logs, trial.json with "stations"); rk-run runs each station's
# chain and rk-intersect (--smooth, as the manifest asks) into one out/; the trajectory is within a named
# tolerance of truth; a second run skips everything; malformed multi-station manifests fail with exit 3 at
# trial.json:LINE:COL (4 for a missing file), and a single-station manifest may not ask for the intersection;
# a trial whose stations' clocks are off, with "steps": {"intersect": {"estimate-time-offsets": true}}: the
# offsets in the intersection's report within 3 σ of the truth and on the report page (issue 33).
rk_cli_script(rk_run/rk_run_multistation REQUIRES sim_small)

# rk-nightly: parallel run over a root of trials, a failing trial reported with its reason, summary JSON
# and text table, log file, non-zero exit; the second run finds everything up to date; a second
# instance exits at once (75).
rk_cli_script(rk_run/rk_nightly_summary REQUIRES sim_small)

# Issue 27 item 9: one trial's page never costs the others the index. With a stand-in rk-run (--rk-run), four
# trials: one whose report.json nests 5000 levels deep (listed with its figures), one whose report.json the index
# cannot read (its row says why), one whose report page rk-run could not make (report_page_warning), one good:
# index.html lists all four, the summary's pages_not_made names the two, and rk-nightly exits 1.
rk_cli_script(rk_run/rk_nightly_page_failures)

# Issue 27 item 12: index.html links trial folders named with '#', '?', '%' (also '%25'), a space, and one in a
# subfolder: every link, resolved against the index's file:// URL as a browser does, opens that trial's
# out/report.html (no fragment, no query). A stand-in rk-run, as above.
rk_cli_script(rk_run/rk_nightly_index_links)

# Issue 27 item 14: trial folders reached through symbolic links are found (a link to a trial outside ROOT is
# run), each folder once; a second path to a trial, a link back up to ROOT and a link to nothing are not followed
# and said so (stderr, summary "not_followed", the text table). A stand-in rk-run, as above.
rk_cli_script(rk_run/rk_nightly_symlinks)

# Issue 27 item 14: SIGTERM while the first of three trials runs (-j 1): the running one is failed (stopped),
# the two never started are counted "not_started" (result "not-started"), not failed; exit 1. A stand-in rk-run.
rk_cli_script(rk_run/rk_nightly_interrupted)

# Target "kill -9 of a nightly run in the middle": the next run finishes every trial, and no trial's out/
# is ever half-written. Three trials that already have a good out/ are all forced to rebuild; rk-nightly is
# killed with SIGKILL while they run (twice, at two moments) (its rk-runs and their tools die with it through PDEATHSIG). Then
# every out/ must be complete (old or new), the next run must bring every trial to done/up-to-date, and
# no temporary may be left.
rk_cli_script(rk_run/rk_nightly_kill9 REQUIRES sim_small)

# Steps of tools that other issues add (features, silhouette, radar): registered only when the tool and
# its simulator subcommand exist. Each simulates a trial with rk-sim <kind> (which writes trial.json as
# rk-sim beacon does, SPEC.md §6) and checks that rk-run runs that unit's steps to "ok" (other_unit in
# rk_run/lib.sh).
function(rk_run_other_unit name tool sim_cmd_file)
  if(TARGET ${tool} AND EXISTS ${PROJECT_SOURCE_DIR}/apps/${sim_cmd_file})
    rk_cli_script(rk_run/${name} ${ARGN})
  endif()
endfunction()
# Small trials: the attitude camera of the sim_attitude_small fixture (1000x800, 40 m), 1 s at 10 fps;
# 0.5 s of 640x640 theodolite frames.
rk_run_other_unit(rk_run_features_oi rk-attitude sim_attitude_cmd.cpp REQUIRES sim_attitude_small)
rk_run_other_unit(rk_run_silhouette_cylinder rk-attitude sim_theodolite_cmd.cpp)
rk_run_other_unit(rk_run_radar_register rk-register sim_radar_cmd.cpp)

# Until rk-attitude, rk-register and rk-extract features/silhouette exist, the features, silhouette and radar
# units are exercised with stand-in executables (in a --bin folder, found before the real tools): each
# records its command line and writes a small CSV and report. This checks rk-run's side only — the
# SPEC.md §1.1 command lines it builds, the order, the plots of data-dependent columns, skipping and
# re-running after an input change — not the tools (rk_run_features_oi etc. above do that once they exist).
rk_cli_script(rk_run/rk_run_other_units_stand_ins)

# Issue 17: the manifest's station.pointing and position reach rk-locate (--pointing, --station): on a trial
# with station errors (rk-sim beacon --az-offset-deg ...) whose manifest names truth/pointing.json, the whole
# chain (rk-extract, rk-locate) is within 5″ RMS of truth, and located.csv has lat_deg,lon_deg,h_m.
rk_cli_script(rk_run/rk_run_station_pointing)

# Issue 31: a `points` camera end to end from trial.json (docs/rk-run.md): the small trial's lamp cluster seeded
# as a centroid-bright point; rk-run plans and runs extract-points and locate-points; one row per frame, nothing
# measured while hidden and back within 2 frames, located az/el against truth (5" RMS, mean NEES ≤ 3), up to
# date on a second run and rerun when the seeds change.
rk_cli_script(rk_run/rk_run_points_chain REQUIRES sim_small)
