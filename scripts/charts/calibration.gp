# A calibrated pixel: period against photocurrent from ngspice, the model aesim runs with the
# calibrated preset, and the ideal eq. 2 pixel of the base preset. From `aesim calibrate --chart`.
csv = ARG1; png = ARG2  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
set datafile missing ""
set terminal pngcairo size 900,620 font ",11"
set output png
set logscale xy
set grid
set format x "%.0e"
set format y "%.0e"
set xlabel "photocurrent (A)"
set ylabel "firing period (s)"
set key top right
set title "Pixel circuit (ngspice) against the calibrated model and the ideal eq. 2 pixel"
plot csv using 1:4 with lines lw 2 dt 2 lc rgb "gray40" title "ideal eq. 2 (base preset)", \
     csv using 1:3 with lines lw 2 lc rgb "#1f77b4" title "calibrated model (pixel.transfer)", \
     csv using 1:2 with points pt 7 ps 1.2 lc rgb "#d62728" title "ngspice"
