# CLI tests of rk-calibrate lens (SPEC.md §1.1, §3, §4; docs/rk-calibrate.md): OpenCV's sample board images
# (Debian opencv-doc, installed by scripts/setup.sh) and malformed input; products in ${RK_CLI_DATA}/cal_lens.

# Good input (left0%d.jpg and left1%d.jpg: 13 views, there is no left10.jpg): camera.json per SPEC §3 with its calibration object, the plot, the report with a summary.
rk_cli_script(rk_calibrate_lens/rk_calibrate_lens_good)
# Bad input: unreadable image (missing 4, undecodable 3), no boards (1), too few views (1), bad options (2);
# no partial output, and --report still written (status failed).
rk_cli_script(rk_calibrate_lens/rk_calibrate_lens_bad_input)
