# CLI tests of rk-capture and rk-sim device (SPEC.md §4, §6; docs/rk-capture.md).
# The full test records emulated devices (rk-sim device dimetix|ptu, with injected faults) and a
# replayed video (the sim_small fixture, looped) for 11.5 s, kills rk-capture with SIGKILL, runs
# `rk-capture recover` and checks every record against the emulators' truth logs and every frame
# against the source video (tests/cli/capture_check.py).
# The scripts (tests/cli/rk_capture/) source rk_capture/lib.sh (wait_links).

rk_cli_script(rk_capture/rk_capture_kill9_recover REQUIRES sim_small)

# SIGINT: clean stop, exit 0, manifest complete, nothing to repair; the station's model copied in.
rk_cli_script(rk_capture/rk_capture_sigint_clean)

# A file-size limit (ulimit -f, RLIMIT_FSIZE) hits the video in the middle of frames: each frame is
# written whole or not at all, the recording goes on in new segments, the other files stay
# readable, the exit status is 4, and recover finds the trial readable.
rk_cli_script(rk_capture/rk_capture_file_size_limit)

# Bad usage → 2; bad data → 3 with the file (and line:col for JSON syntax); missing device → 4.
# Nothing is left behind and nothing the user gave is touched.
rk_cli_script(rk_capture/rk_capture_errors)

# A really full disk (ENOSPC), where the machine allows it: tests/cli/capture_disk_full.sh mounts a
# 12 MB tmpfs in a private mount namespace (needs CAP_SYS_ADMIN; the test is skipped otherwise).
rk_cli_test(rk_capture_disk_full COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/capture_disk_full.sh ${RK_CLI_DATA})
set_tests_properties(rk_capture_disk_full PROPERTIES SKIP_RETURN_CODE 77)

# The live status line: on a terminal (a pty from script(1)), rewritten in place with frames, drops, range
# rate and turret angles; not printed when stderr is not a terminal.
rk_cli_script(rk_capture/rk_capture_status_line)

# GigE Vision through Aravis (issue 32): Aravis' software camera (arv-fake-gv-camera-0.8) in a private network
# namespace (unshare -n, loopback only); --list-cameras lists it; 10 s recorded with a size, rate and exposure
# other than its defaults, set in the file's order and read back (report, events.log); frame count = duration
# × rate within a frame (the frames the camera's clock spans; every frame it sent written), camera stamps strictly
# increasing at the configured period within 1 %, ≥ 6 decimals; the receive thread's scheduling as the report
# says (/proc);
# stream counters and the camera → host clock fit in the report; paused (SIGSTOP) and resumed, then killed and
# restarted: two gaps, one reconnect with the features set again, no duplicated frame; packet loss (the software
# camera's -r): incomplete frames counted, none written, seq jumps by the lost; a camera whose clock resets and
# is set forward again (restarted under libfaketime): a new mapping each time, t_s continuous; a camera that does not answer:
# exit 4, no trial. Skipped (77) without aravis-tools or without a network namespace.
rk_cli_script(rk_capture/rk_capture_aravis)
# Alone: the software camera stamps its frames by its own timer, which other tests' load would delay. It also
# runs at a real-time priority (chrt -f 20, above rk-capture's receive thread) where the kernel allows it: one
# late wake-up of its single thread misses or shifts a frame (a loaded CI machine: 6 of 200 missed). Where the
# kernel refuses, the tolerances on the stand-in's own timing are looser (named in the script).
set_tests_properties(rk_capture_aravis PROPERTIES SKIP_RETURN_CODE 77 RUN_SERIAL TRUE)
