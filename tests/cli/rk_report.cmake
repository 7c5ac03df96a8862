# CLI tests of the trial report page (scripts/rk-report, made by rk-run) and rk-nightly's index.html (issue 19,
# docs/rk-run.md "The report page"). The scripts are in tests/cli/rk_report/ and use rk_run/lib.sh.

# rk-run makes out/report.html once per new out/: self-contained (no script, no external reference), with the
# trial's figures; an up-to-date run leaves it alone, remakes it when it is missing; --no-plots makes none; a
# page that cannot be made (a failing rk-report) is a warning: rk-run exits 0 and last-run.json says why.
rk_cli_script(rk_report/rk_report_page REQUIRES sim_small SETUP report_pages)

# Both pages in a real browser (headless Chromium, tests/cli/browser_check.py over the DevTools pipe): no
# console error, no network request (proxy and host resolver point nowhere; the pages' own CSP forbids every
# fetch), the tracked-frame percentage of report.json shown on the trial page and on rk-nightly's index, the
# failed trial listed first with its reason. Skipped (exit 77) when chromium is not installed; CI installs it
# (scripts/setup.sh --browser).
rk_cli_script(rk_report/rk_report_pages_in_chromium REQUIRES sim_small report_pages)
set_tests_properties(rk_report_pages_in_chromium PROPERTIES SKIP_RETURN_CODE 77)

# Angles that wrap (scripts/rk_html.py angle_wraps: azimuth, yaw, roll, longitude, right ascension): the small
# trial's page with its azimuth turned to cross north mid-track. Neither the static page's line nor the interactive
# panel's (its ±1σ band included) is drawn across the wrap: the static line is one piece more than its gaps; in
# headless Chromium the panel's wraps equal the CSV's and every drawn series is clipped over each, on the whole
# series and after a zoom and reset. A target sitting on north (its azimuth jittering across it, a wrap between
# every pair of rows): every row drawn as a point, statically and in the browser. Skipped (77) without chromium or
# node, once the static pages have passed.
rk_cli_script(rk_report/rk_report_azimuth_wrap REQUIRES report_pages)
set_tests_properties(rk_report_azimuth_wrap PROPERTIES SKIP_RETURN_CODE 77)

# The page's series encoding: numpy (long series) and pure Python (short ones, or no numpy) give the same bytes
# for smooth series, gaps, infinities, all-missing, tiny negatives, one row and a jump beyond int32; decoded
# within half a quantum. Skipped (77) without numpy.
rk_cli_script(rk_report/rk_report_encode_paths)
set_tests_properties(rk_report_encode_paths PROPERTIES SKIP_RETURN_CODE 77)

# Issue 27 item 9: a manifest with an extra key 5000 levels deep (legal: SPEC.md §6 keeps extra keys) still gets
# its page: rk-report reads report.json with the depth cut at 100 levels (scripts/rk_html.py loads_bounded),
# shows the cut in the manifest and as a warning, and the rest of the page is that of the same trial without it.
rk_cli_script(rk_report/rk_report_deep_manifest REQUIRES report_pages)

# Issue 34's target page: a 1-hour two-station trial at 20 Hz (tests/cli/rk_report/hour_page.sh: rk-sim
# multistation's located targets at 20 and 25 Hz, rk-intersect's trajectory, 162 000 rows; rk-report on them):
# under 15 MB with every row, first paint under 1.5 s in headless Chromium, zoomed to a 1-s window and back by
# playwright-core dragging boxes, the read-out equal to the CSVs. Alone: the first paint is timed. Skipped (77)
# without chromium or node.
rk_cli_script(rk_report/rk_report_hour_page)
set_tests_properties(rk_report_hour_page PROPERTIES SKIP_RETURN_CODE 77 RUN_SERIAL TRUE)
