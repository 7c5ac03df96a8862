# Issue 27: what whoever can write into a trial folder must not be able to do to files elsewhere, and what a
# run must never delete (docs/conventions.md "Threat model"). Scripts in tests/cli/rk_safety/.

# rk-capture recover: a manifest path (../, absolute, or a link) that leads outside the trial folder is
# refused before anything is opened for writing (exit 3 at the key's line:column), with --check alike;
# trial.json and the file outside are unchanged. A link named like a log (events.log) is not followed.
rk_cli_script(rk_safety/rk_recover_stays_inside)

# rk-run's own files in the trial folder (.rk-run.lock, last-run.json, rk-run.log) as links to a file
# outside: refused (exit 4), the target untouched; linked out.tmp.*/out.old.* never emptied; a step
# option that only abbreviates a real option (rk-plot --out for --output) refused at its trial.json
# position, checked against the tool's own --help; rk-run's output options come after the user's.
rk_cli_script(rk_safety/rk_run_own_files_no_links REQUIRES sim_small)

# A run that does less never deletes what it did not redo: --no-plots keeps up-to-date plots and the page,
# keeps stale plots marked stale (the page says so), the user's files in out/ survive every rebuild, a
# collision with a new product is refused (exit 4, out/ unchanged), a file named out is exit 4; out/ has
# the umask's mode.
rk_cli_script(rk_safety/rk_run_keeps_what_it_did_not_make REQUIRES sim_small)

# A really full disk (a tmpfs in a private mount namespace; skipped where that is not allowed):
# last-run.json never keeps claiming an earlier "done" after a failed run, and a step that fails on the full
# disk is reported with its own error line although its log could not be written.
rk_cli_script(rk_safety/rk_run_disk_full REQUIRES sim_small)
set_tests_properties(rk_run_disk_full PROPERTIES SKIP_RETURN_CODE 77)

# SIGTERM while the report page is made (a slow stand-in rk-report): exit 1, last-run.json "failed",
# "interrupted by signal 15"; out/ complete.
rk_cli_script(rk_safety/rk_run_interrupted_page REQUIRES sim_small)

# A beacon seen in two frames (smoothing needs three): the chain still delivers extract and locate products and a
# page saying why smoothing did not run (the tool's report says "error_kind": "too-few-samples"); no message
# names a temporary path; the next run is up to date.
rk_cli_script(rk_safety/rk_run_too_few_frames)

# A manifest with an extra key nested 5000 levels deep: rk-run refuses it at its place (exit 3, "nested deeper
# than 512 levels") instead of overflowing its stack; 300 levels are kept, and the run and its page are made.
rk_cli_script(rk_safety/rk_run_deep_manifest REQUIRES sim_small)
