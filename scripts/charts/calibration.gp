# A calibrated pixel: period against photocurrent from ngspice, the model aesim runs with the
# calibrated preset, and the ideal eq. 2 pixel of the base preset; below, each relative to the
# ideal pixel, where the percent-level differences show. Shaded: the currents outside those at
# which the circuit fired (ARG3 to ARG4), where the model extrapolates along eq. 2 and `aesim run`
# warns. From `aesim calibrate --chart`.
csv = ARG1; png = ARG2  # paths arrive as arguments, never as code
fired_lo = ARG3 + 0.0; fired_hi = ARG4 + 0.0  # "1.000000e-12": gnuplot reads a number from a string only with its decimal point
set datafile separator ","
set datafile columnheaders
set datafile missing ""
set terminal pngcairo size 900,900 font ",11"
set output png
set multiplot layout 2,1 title "Pixel circuit (ngspice) against the calibrated model and the ideal eq. 2 pixel"
set logscale x
set grid
set format x "%.0e"
set xlabel "photocurrent (A)"
set logscale y
set format y "%.0e"
set ylabel "firing period (s)"
set key top right
set object 1 rect from graph 0, graph 0 to first fired_lo, graph 1 behind fc rgb "#e8e8e8" fs solid noborder
set object 2 rect from first fired_hi, graph 0 to graph 1, graph 1 behind fc rgb "#e8e8e8" fs solid noborder
set label 1 "extrapolated" at graph 0.02, graph 0.05 tc rgb "gray40"
set label 2 "extrapolated" at graph 0.98, graph 0.05 right tc rgb "gray40"
plot csv using 1:4 with lines lw 2 dt 2 lc rgb "gray40" title "ideal eq. 2 (base preset)", \
     csv using 1:3 with lines lw 2 lc rgb "#1f77b4" title "calibrated model (pixel.transfer)", \
     csv using 1:2 with points pt 7 ps 1.2 lc rgb "#d62728" title "ngspice"
unset logscale y
set format y "%g"
set ylabel "period / ideal eq. 2 period - 1 (%)"
set key top left
plot csv using 1:(0) with lines lw 2 dt 2 lc rgb "gray40" title "ideal eq. 2", \
     csv using 1:(100 * (column(3) / column(4) - 1)) with lines lw 2 lc rgb "#1f77b4" title "calibrated model", \
     csv using 1:(100 * (column(2) / column(5) - 1)) with points pt 7 ps 1.2 lc rgb "#d62728" title "ngspice"
unset multiplot
