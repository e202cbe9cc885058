# Wall time per simulated second against error for every rung, from `aesim compare` CSV
csv = ARG1; png = ARG2; svg = ARG3  # paths arrive as arguments, never as code
max(a, b) = a > b ? a : b
# (scripts/fidelity_ladder). Exact rungs (error 0) are drawn on the floor of each axis.
set datafile separator ","
set datafile columnheaders
set logscale xy
set grid
set key outside bottom center horizontal maxrows 3 font ",9"
time_floor = 1e-9
count_floor = 1e-5
scene(i) = i == 1 ? "scenes/letters/A.pgm" : i == 2 ? "scenes/hdr/window.pfm" : "scenes/moving_disc"
short(i) = i == 1 ? "letter A" : i == 2 ? "HDR window" : "moving disc"
is(i) = strcol("scene") eq scene(i)
label(i) = strcol("rung") . (column("step_s") > 0 ? sprintf(" %gus", column("step_s") * 1e6) : "")
do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1500,680 font ",10"; set output png }
  if (format eq "svg") { set terminal svg size 1500,680 dynamic font ",10"; set output svg }
  set multiplot layout 1,2 title "aesim fidelity ladder: cost against accuracy (aloha sensor, 0.5 s runs; lines: Pareto fronts)"
  set xlabel "wall time per simulated second (s)"
  set ylabel "RMS firing-time error against the event rung (s)"
  set yrange [time_floor/2:1]
  plot for [i=1:3] csv using (is(i) ? column("wall_per_sim_s") : NaN):(max(column("rms_time_error_s"), time_floor)) \
         with points pt 5+2*i ps 1.4 title short(i), \
       for [i=1:3] csv using (is(i) && column("pareto") > 0 ? column("wall_per_sim_s") : NaN):(max(column("rms_time_error_s"), time_floor)) \
         smooth unique with lines lw 1.5 notitle, \
       csv using (is(1) ? column("wall_per_sim_s") : NaN):(max(column("rms_time_error_s"), time_floor)):(label(0)) \
         with labels offset 0,1 font ",8" noenhanced notitle
  set ylabel "per-pixel event-count error against the event rung"
  set yrange [count_floor/2:1]
  plot for [i=1:3] csv using (is(i) ? column("wall_per_sim_s") : NaN):(max(column("count_error"), count_floor)) \
         with points pt 5+2*i ps 1.4 title short(i), \
       csv using (is(1) ? column("wall_per_sim_s") : NaN):(max(column("count_error"), count_floor)):(label(0)) \
         with labels offset 0,1 font ",8" noenhanced notitle
  unset multiplot
  set output
}
