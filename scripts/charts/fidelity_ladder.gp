# Wall time per simulated second against error for every rung, from `aesim compare` CSV
# (scripts/fidelity_ladder). Exact rungs (error 0) are drawn on a dashed floor of each axis, which
# the chart labels; their names are slanted so that neighbours do not overlap.
csv = ARG1; png = ARG2; svg = ARG3  # paths arrive as arguments, never as code
max(a, b) = a > b ? a : b
set datafile separator ","
set datafile columnheaders
set logscale xy
set grid
set key outside bottom center horizontal maxrows 1 font ",9"
set bmargin 6
set format y "1e%L"
time_floor = 1e-9
count_floor = 1e-5
scene(i) = i == 1 ? "scenes/letters/A.pgm" : i == 2 ? "scenes/hdr/window.pfm" : "scenes/moving_disc"
short(i) = i == 1 ? "letter A" : i == 2 ? "HDR window" : "moving disc"
is(i) = strcol("scene") eq scene(i)
label(i) = strcol("rung") . (column("step_s") > 0 ? sprintf(" %gus", column("step_s") * 1e6) : "")
floor_note = "exact: zero error, drawn on this floor"
do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1500,680 font ",10"; set output png }
  if (format eq "svg") { set terminal svg size 1500,680 dynamic font ",10"; set output svg }
  set multiplot layout 1,2 title "aesim fidelity ladder: cost against accuracy (aloha sensor, 0.5 s runs; lines: Pareto fronts)"
  set xlabel "wall time per simulated second (s)"
  set ylabel "RMS firing-time error against the event rung (s)"
  set yrange [time_floor/2:1]
  set arrow 1 from graph 0, first time_floor to graph 1, first time_floor nohead dt 2 lc rgb "gray60"
  set label 1 floor_note at graph 0.99, first time_floor * 0.62 right font ",8" tc rgb "gray40"
  plot for [i=1:3] csv using (is(i) ? column("wall_per_sim_s") : NaN):(max(column("rms_time_error_s"), time_floor)) \
         with points pt 5+2*i ps 1.4 title short(i), \
       for [i=1:3] csv using (is(i) && column("pareto") > 0 ? column("wall_per_sim_s") : NaN):(max(column("rms_time_error_s"), time_floor)) \
         smooth unique with lines lw 1.5 notitle, \
       csv using (is(1) && column("rms_time_error_s") > 0 ? column("wall_per_sim_s") : NaN):(column("rms_time_error_s")):(label(0)) \
         with labels offset 0,1 font ",8" noenhanced notitle, \
       csv using (is(1) && column("rms_time_error_s") == 0 ? column("wall_per_sim_s") : NaN):(time_floor):(label(0)) \
         with labels rotate by 35 left offset 0.2,0.9 font ",8" noenhanced notitle
  set ylabel "per-pixel event-count error against the event rung"
  set yrange [count_floor/2:1]
  set arrow 1 from graph 0, first count_floor to graph 1, first count_floor nohead dt 2 lc rgb "gray60"
  set label 1 floor_note at graph 0.99, first count_floor * 0.62 right font ",8" tc rgb "gray40"
  plot for [i=1:3] csv using (is(i) ? column("wall_per_sim_s") : NaN):(max(column("count_error"), count_floor)) \
         with points pt 5+2*i ps 1.4 title short(i), \
       csv using (is(1) && column("count_error") > 0 ? column("wall_per_sim_s") : NaN):(column("count_error")):(label(0)) \
         with labels offset 0,1 font ",8" noenhanced notitle, \
       csv using (is(1) && column("count_error") == 0 ? column("wall_per_sim_s") : NaN):(count_floor):(label(0)) \
         with labels rotate by 35 left offset 0.2,0.9 font ",8" noenhanced notitle
  unset multiplot
  set output
}
