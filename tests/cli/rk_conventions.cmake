# Command-line conventions of the suite (issue 19): the rk dispatcher, --version with the git commit,
# man pages and bash completion made from --help, progress only on a terminal.

# rk help lists every rk-* tool of the build with one line; rk <tool> runs it with its exit code and
# streams; rk --version and every tool's --version name the version and the git commit.
rk_cli_script(rk_conventions/rk_dispatcher)

# A man page per tool and for rk (when help2man is installed), each with a NAME and, for tools with
# subcommands, a section per subcommand; every docs/ page a man page names exists and each tool's SEE ALSO
# names one (issue 27); no '§' (help2man writes it as "??") in any --help; a bash completion file per tool that
# completes options,
# subcommands, choice values and file names (driven through bash's completion variables).
rk_cli_script(rk_conventions/rk_man_and_completion)

# Progress: nothing on stderr when it is not a terminal; on a pseudo-terminal (script(1)) the progress
# line with done/total, rate and ETA, then the closing summary line; nothing with --quiet.
# rk-extract, rk-register kf and batch (both stages), rk-calibrate pointing.
rk_cli_script(rk_conventions/rk_progress_only_on_a_terminal REQUIRES sim_small sim_radar_data pointing_data)

# Issue 27: no Python tool takes a prefix of an option (argparse's allow_abbrev): rk-plot given -o and a manifest's
# --out, rk-report --out, rk-nightly --summ, rk-slurm submit --max-par, long_functions.py and golden_outputs.py
# --chec exit 2 with one error line and write nothing; the full name still works.
rk_cli_script(rk_conventions/rk_python_tools_refuse_abbreviations)
