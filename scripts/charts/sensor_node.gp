# The source paper's sensor node over the six hand signs (the aloha preset's light, 2 s a sign): the
# mean latency to the first decision and the share of events lost against the FIFO's depth, one line
# per processor clock. From scripts/sensor_node.
csv = ARG1; out = ARG2; kind = ARG3  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
if (kind eq "svg") { set terminal svg size 1000,480 font ",11" noenhanced } else { set terminal pngcairo size 1000,480 font ",11" noenhanced }
set output out
set multiplot layout 1,2 title "Sensor node: six hand signs, ALOHA imager (aloha preset), recogniser at 100 cycles per template per event"
set grid
set logscale x 2
set xlabel "event FIFO depth (events)"
set key top right
set ylabel "latency to the first decision (s, mean of six signs)"
set title "Recognition latency"
clocks = "1.8 3.6 7.2 14.4 57.6"
plot for [c in clocks] csv using ($1 == real(c) ? $2 : NaN):5 with linespoints lw 2 pt 7 title sprintf("%s MHz", c)
set ylabel "events lost in the FIFO (% of delivered, mean of six signs)"
set title "Events lost"
set key right center
plot for [c in clocks] csv using ($1 == real(c) ? $2 : NaN):6 with linespoints lw 2 pt 7 title sprintf("%s MHz", c)
unset multiplot
