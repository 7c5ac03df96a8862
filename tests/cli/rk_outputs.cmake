# Output paths that are not regular files (SPEC.md §2, "Writes are atomic"; docs/conventions.md): a FIFO
# with a reader, symbolic links (to a file, a chain, a dangling one), -o -, /dev/stdout into a pipe and
# into a file, a character device made for the test, rk-plot, rk-sim's and rk-run's folders behind a
# link. No test here writes to the real /dev/null; devnull_after checks that nothing in the suite did.

# rk-locate (the C++ writer every tool uses): reference output to a regular file, then each kind of path.
rk_cli_script(rk_outputs/rk_outputs_locate REQUIRES locate_data)

# rk-plot (Python writer, scripts/rk_output.py): a link stays a link, a FIFO is written through, -o -.
rk_cli_script(rk_outputs/rk_outputs_plot REQUIRES locate_data)

# Folder outputs behind a link: rk-sim --out and rk-run's out/ keep the link and replace its target.
rk_cli_script(rk_outputs/rk_outputs_folders)

# The suite never damages the machine: /dev/null is a character device, and neither it nor /dev/stdout,
# /dev/stderr, /dev/stdin is a regular file, before and after every test (every CLI and unit test requires the
# devnull fixture, so devnull_after runs last).
rk_cli_test(devnull_before COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/rk_outputs/device_files_intact.sh SETUP devnull)
rk_cli_test(devnull_after COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/rk_outputs/device_files_intact.sh)
set_tests_properties(devnull_after PROPERTIES FIXTURES_CLEANUP devnull)
