# Latency (mean, p99, max, in units of tau) and throughput against offered load on an arbitrated
# bus, from an `aesim sweep` CSV of scripts/sweeps/arbitrated.toml.
csv = ARG1; png = ARG2; svg = ARG3  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
set logscale xy
set grid
set key top left font ",10"
do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1400,620 font ",11"; set output png }
  if (format eq "svg") { set terminal svg size 1400,620 dynamic font ",11"; set output svg }
  set multiplot layout 1,2 title "Arbitrated bus of the aloha sensor: nothing lost, everything waits (each point a 2 s run)"
  set xlabel "offered load G per bus (fired events x tau)"
  set ylabel "latency / tau"
  set xrange [0.005:8]
  set yrange [1e-4:1e6]
  # An M/D/1 queue's mean wait (Poisson arrivals, service tau) for G < 1: G / (2 (1 - G)).
  md1(g) = g < 1 ? g / (2 * (1 - g)) : 1/0
  plot md1(x) lw 2 lc rgb "black" title "M/D/1 mean wait G/(2(1-G))", \
       csv using "offered_load":(column("latency_mean_s") / column("tau_s")) with linespoints pt 7 title "mean", \
       csv using "offered_load":(column("latency_p99_s") / column("tau_s")) with linespoints pt 5 title "99th percentile", \
       csv using "offered_load":(column("latency_max_s") / column("tau_s")) with linespoints pt 9 title "max"
  set ylabel "throughput S (delivered events x tau)"
  unset logscale y
  set yrange [0:1.1]
  set key bottom right
  plot (x < 1 ? x : 1) lw 2 lc rgb "black" title "min(G, 1)", \
       x * exp(-2 * x) lw 2 dt 2 lc rgb "gray40" title "pure ALOHA, for comparison", \
       csv using "offered_load":"throughput" with points pt 7 title "arbitrated"
  unset multiplot
  set output
}
