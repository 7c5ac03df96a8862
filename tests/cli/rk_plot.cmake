# CLI tests of scripts/rk-plot (python3 + matplotlib, Agg backend).

rk_cli_script(rk_plot/rk_plot_png SETUP plot_data)

rk_cli_script(rk_plot/rk_plot_bad_input REQUIRES plot_data)
