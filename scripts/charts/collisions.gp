# Throughput S and collision fraction against offered load G, from an `aesim sweep` CSV of
# scripts/sweeps/collisions.toml. Called as `gnuplot -c SCRIPT CSV PNG SVG` (by aesim sweep).
csv = ARG1; png = ARG2; svg = ARG3  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
set logscale x
set xrange [0.005:8]
set key outside bottom center horizontal maxrows 4 font ",9"
# Room under the axis title for the four rows of the key.
set bmargin 8
set grid
pure(g) = g * exp(-2 * g)
slotted(g) = g * exp(-g)
name(i) = i == 1 ? "event letter" : i == 2 ? "event natural" : i == 3 ? "cycle letter" : i == 4 ? "cycle natural" : i == 5 ? "lock-step: reset + no mismatch" : "lock-step: reset + 2% mismatch"
pt(i) = i == 1 ? 7 : i == 2 ? 5 : i == 3 ? 6 : i == 4 ? 4 : i == 5 ? 9 : 11
g_of(i) = strcol("group") eq name(i) ? column("offered_load") : NaN

do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1400,700 font ",11"; set output png }
  if (format eq "svg") { set terminal svg size 1400,700 dynamic font ",11"; set output svg }
  set multiplot layout 1,2 title "ALOHA bus of the aloha sensor: simulation against theory (each point a 2 s run)"
  set xlabel "offered load G per bus (fired events x tau)"
  set ylabel "throughput S (delivered events x tau)"
  set yrange [-0.005:0.4]
  plot pure(x) lw 2 lc rgb "black" title "pure ALOHA G e^{-2G}", \
       slotted(x) lw 2 dt 2 lc rgb "gray40" title "slotted ALOHA G e^{-G}", \
       for [i=1:6] csv using (g_of(i)):"throughput" with points pt pt(i) ps 1.3 title name(i)
  set ylabel "fraction of fired events lost to collisions"
  set yrange [0:1.05]
  plot 1 - exp(-2 * x) lw 2 lc rgb "black" title "pure ALOHA 1 - e^{-2G}", \
       1 - exp(-x) lw 2 dt 2 lc rgb "gray40" title "slotted ALOHA 1 - e^{-G}", \
       for [i=1:6] csv using (g_of(i)):"collision_fraction" with points pt pt(i) ps 1.3 title name(i)
  unset multiplot
  set output
}
