# CLI tests of rk-attitude oi (SPEC.md §1.1, §4) on the sim_attitude_small trial and the points
# extracted from its video (fixture features_small): accuracy against the truth, per-row status
# for turret gaps and missing points, and malformed input.

# Extracted points → pose; errors against the truth: yaw/pitch/roll std well under 0.05 deg.
rk_cli_script(rk_attitude_oi/rk_attitude_oi_good REQUIRES sim_attitude_small features_small)

# Truth points (no image noise) with a fixed boresight, to stdout; --pure-oi also runs.
rk_cli_script(rk_attitude_oi/rk_attitude_oi_boresight_stdout REQUIRES sim_attitude_small)

# Per-row status: a turret-log hole → invalid (note turret); a frame with 3 points → lost.
rk_cli_script(rk_attitude_oi/rk_attitude_oi_row_status REQUIRES sim_attitude_small)

# Malformed input and usage (SPEC.md §4): one-line error, exit code, no output.
rk_cli_script(rk_attitude_oi/rk_attitude_oi_bad REQUIRES sim_attitude_small)

# Issue 17, SPEC.md §3.1: rk-attitude oi and cylinder apply --pointing. Logs whose azimuth reads 1.25° high plus
# a pointing model with az_offset_deg -1.25 give the poses and axes of the true logs (within 1e-6); without the
# model the yaw is off by 1.25°.
rk_cli_script(rk_attitude_oi/rk_attitude_pointing REQUIRES sim_attitude_small features_small sim_theodolite_trial)
