# Power per quadrant against reconstruction PSNR for every run of a sizing sweep
# (scripts/sweeps/sizing.toml), feasible designs' runs highlighted, the recommended design's runs
# marked, the PSNR and power constraints drawn. Called by aesim sweep as
# gnuplot -c sizing.gp CSV PNG SVG SENSOR PSNR_MIN POWER_PER_TILE_MAX (bounds in dB and W, empty
# when the spec has none): paths and labels arrive as arguments, never as code.
csv = ARG1; png = ARG2; svg = ARG3
sensor = (ARGC >= 4 && strlen(ARG4) > 0) ? ARG4 : "the"
set datafile separator ","
set datafile columnheaders
set grid
set key outside bottom center horizontal font ",10"
set bmargin 5
set xlabel "power per 32x32 quadrant (uW)"
set ylabel "PSNR of the reconstruction after the readout window (dB)"
if (ARGC >= 5 && strlen(ARG5) > 0) {
  psnr_min = real(ARG5)
  set arrow 1 from graph 0, first psnr_min to graph 1, first psnr_min nohead dt 2 lw 1.5 lc rgb "#d55e00"
  set label 1 sprintf("PSNR >= %g dB", psnr_min) at graph 0.01, first psnr_min offset 0, 0.7 tc rgb "#d55e00" font ",10"
}
if (ARGC >= 6 && strlen(ARG6) > 0) {
  power_max = 1e6 * real(ARG6)
  set arrow 2 from first power_max, graph 0 to first power_max, graph 1 nohead dt 2 lw 1.5 lc rgb "#d55e00"
  # The bound stays on the chart when every run lies on one side of it, its label on the inner side.
  stats csv using (1e6 * column("power_per_tile_w")) nooutput
  lo = STATS_min < power_max ? STATS_min : power_max
  hi = STATS_max > power_max ? STATS_max : power_max
  set xrange [lo - 0.05 * (hi - lo) : hi + 0.08 * (hi - lo)]
  if (power_max - lo > 0.5 * (hi - lo)) {
    set label 2 sprintf("power <= %g uW", power_max) at first power_max, graph 0.97 right offset -0.5, 0 tc rgb "#d55e00" font ",10"
  } else {
    set label 2 sprintf("power <= %g uW", power_max) at first power_max, graph 0.97 left offset 0.5, 0 tc rgb "#d55e00" font ",10"
  }
}
do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1100,700 font ",11"; set output png }
  if (format eq "svg") { set terminal svg size 1100,700 dynamic font ",11"; set output svg }
  set title sprintf("Sizing %s pixel: every run (scene x light x design); filled: designs feasible in every condition", \
                    sensor eq "the" ? "the" : "the " . sensor) noenhanced
  plot csv using (column("feasible") > 0 ? NaN : 1e6 * column("power_per_tile_w")):"psnr_db" with points pt 6 ps 1.2 lc rgb "gray50" title "infeasible design", \
       csv using (column("feasible") > 0 ? 1e6 * column("power_per_tile_w") : NaN):"psnr_db" with points pt 7 ps 1.4 lc rgb "#0072b2" title "feasible design", \
       csv using (column("recommended") > 0 ? 1e6 * column("power_per_tile_w") : NaN):"psnr_db" with points pt 3 ps 2.6 lw 2 lc rgb "#e69f00" title "recommended design"
  set output
}
