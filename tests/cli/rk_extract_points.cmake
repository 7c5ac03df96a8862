# CLI tests of rk-extract points (SPEC.md §1.1, §2.1, §4) on rk-sim points trials: good input scored against the
# truth, the look-alike scene, stdout streaming, and malformed seeds.

# A moving, rotating, growing target with clouds: every method's rows against the truth, hidden rows never
# measured, re-acquisition within 2 frames, σ honest; the fixture points_small for the chain tests.
rk_cli_script(rk_extract_points/rk_extract_points_good SETUP points_small)

# The look-alike scene: no measured row ever lies on the look-alike.
rk_cli_script(rk_extract_points/rk_extract_points_lookalike)

# --fps and -o -: the same rows as with frames.csv to a file.
rk_cli_script(rk_extract_points/rk_extract_points_fps_stdout REQUIRES points_small)

# Malformed seeds: unknown method, outside the image, past the end, an id twice at one frame, no --seeds, an
# unreadable seeds file: the SPEC exit code, one line naming seeds.csv:LINE:COL, no output (not even on stdout).
rk_cli_script(rk_extract_points/rk_extract_points_bad REQUIRES points_small)
