# CLI tests of scripts/rk-plot (python3 + matplotlib, Agg backend).
set(RK_PLOT ${PROJECT_SOURCE_DIR}/scripts/rk-plot)
function(rk_plot_script name body)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh
       "#!/usr/bin/env bash\nset -eu\ndata=$1; expect=$2; plot=$3\n${body}")
  rk_cli_test(${name} ${ARGN} COMMAND bash ${CMAKE_CURRENT_BINARY_DIR}/${name}.sh ${RK_CLI_DATA} ${RK_EXPECT} ${RK_PLOT})
endfunction()

rk_plot_script(rk_plot_png [==[
d=$data/plot; rm -rf "$d"; mkdir -p "$d"
printf '# comment\nt_s,az_deg,range_m,status\n0,1.0,10,ok\n# mid comment\n0.1,1.1,,lost\n0.2,1.3,10.2,ok\n' > "$d/a.csv"
printf 't_s,range_m,az_deg\n0,10.1,0.9\n0.2,10.3,1.2\n' > "$d/b.csv"
"$plot" -i "$d/a.csv" -i "$d/b.csv" --columns az_deg,range_m --title 'test' -o "$d/out.png"
test "$(od -An -tx1 -N8 "$d/out.png" | tr -d ' \n')" = 89504e470d0a1a0a
test -z "$(ls -A "$d" | grep '^\.rk-plot-' || true)"   # no temporary left behind
"$plot" -i - --columns range_m --x t_s -o - < "$d/a.csv" > "$d/stdout.png"
test "$(od -An -tx1 -N4 "$d/stdout.png" | tr -d ' \n')" = 89504e47
echo ok
]==] SETUP plot_data)

rk_plot_script(rk_plot_bad_input [==[
d=$data/plot; o=$d/bad.png; rm -f "$o"
printf 't_s,a_m\n0,1\n1,x\n' > "$d/text.csv"
printf 't_s,a_m\n0,1\n1,2,3\n' > "$d/fields.csv"
L() { "$expect" "$@"; }
L 3 "$o" 'text.csv:3:3:' -- "$plot" -i "$d/text.csv" --columns a_m -o "$o"
L 3 "$o" 'fields.csv:3:' -- "$plot" -i "$d/fields.csv" --columns a_m -o "$o"
L 3 "$o" 'a.csv:2:' -- "$plot" -i "$d/a.csv" --columns nope_m -o "$o"
L 4 "$o" 'no_such.csv' -- "$plot" -i "$d/no_such.csv" --columns a_m -o "$o"
L 2 "$o" -- "$plot" -i "$d/a.csv" --columns az_deg -o "$o" --bogus
L 2 "$o" -- "$plot" -i "$d/a.csv" -o "$o"
L 2 - 'refusing to overwrite' -- "$plot" -i "$d/a.csv" --columns az_deg -o "$d/a.csv"
echo ok
]==] REQUIRES plot_data)
