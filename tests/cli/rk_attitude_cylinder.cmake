# CLI tests of rk-attitude cylinder (SPEC.md §1.1, §4; docs/rk-attitude-cylinder.md) on the trial of the
# fixture sim_theodolite_trial (tests/cli/rk_sim_theodolite.cmake): good input and malformed input.

# Exact points: the truth to 1e-4 deg, the mirror in alt_*, one row per frame, report, both methods.
rk_cli_script(rk_attitude_cylinder/rk_attitude_cylinder_good REQUIRES sim_theodolite_trial)

# -o - writes to stdout; the points may come from stdin.
rk_cli_script(rk_attitude_cylinder/rk_attitude_cylinder_stdio REQUIRES sim_theodolite_trial)

# Bad input: one-line error, SPEC.md §4 exit code, no output file.
rk_cli_script(rk_attitude_cylinder/rk_attitude_cylinder_bad_input REQUIRES sim_theodolite_trial)

# Per-row statuses: a missing point is lost, frames in a theodolite gap are invalid, the others keep their values.
rk_cli_script(rk_attitude_cylinder/rk_attitude_cylinder_row_status REQUIRES sim_theodolite_trial)

# Image fit (--video): rk-extract silhouette points refined on the fixture's own frames. Tolerances 4σ of one
# frame at this 298-px image (the fit's σ ≈ 0.055° yaw, 0.021° pitch); bad input: no frame column, a video
# shorter than the points file.
rk_cli_script(rk_attitude_cylinder/rk_attitude_cylinder_image_fit REQUIRES sim_theodolite_trial)
