# CLI tests of scripts/rk-plot (python3 + matplotlib, Agg backend).

# Two files overlaid, a gap, stdin and stdout; an azimuth crossing north drawn byte for byte as the same rows with
# a gap at the wrap (a range column with the same jump is not).
rk_cli_script(rk_plot/rk_plot_png SETUP plot_data)

rk_cli_script(rk_plot/rk_plot_bad_input REQUIRES plot_data)
