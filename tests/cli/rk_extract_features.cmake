# CLI tests of rk-extract features (SPEC.md §1.1, §4) on the sim_attitude_small trial
# (rk_sim_attitude.cmake): good input scored against the truth, and malformed input. The good
# run is the fixture features_small used by rk-attitude oi's tests.

# Every marker found with its own id (no identity error), sub-0.05 px, the hidden fin lost for
# 3 frames then reacquired; report counts.
rk_cli_script(rk_extract_features/rk_extract_features_good REQUIRES sim_attitude_small SETUP features_small)

# --fps/--t0 and stdout; the same points as with frames.csv (t0 = 1 s, 10 fps).
rk_cli_script(rk_extract_features/rk_extract_features_fps_stdout REQUIRES sim_attitude_small features_small)

# Nothing to find: every marker hidden → exit 1 (SPEC: nothing detected at all), no output.
rk_cli_script(rk_extract_features/rk_extract_features_nothing REQUIRES sim_attitude_small)

# Malformed input and usage.
rk_cli_script(rk_extract_features/rk_extract_features_bad REQUIRES sim_attitude_small)

# Image-sequence input (rk-sim --format png) given as two segments: frame numbers count on, the
# second copy is read as frames 5-9 (10 frames x 8 ids = 80 rows).
rk_cli_script(rk_extract_features/rk_extract_features_png_segments REQUIRES sim_attitude_small)

# 16-bit video: the same thresholds in noise sigmas work on 16-bit DN.
rk_cli_script(rk_extract_features/rk_extract_features_16bit REQUIRES sim_attitude_small)
