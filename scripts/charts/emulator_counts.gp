# Entries per frame against grey level in the emulator (f_max 20): eq. 1, the even spread and the
# literal eq. 3. From scripts/emulator_counts.
csv = ARG1; png = ARG2  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
set terminal pngcairo size 900,560 font ",11" noenhanced
set output png
set grid
set key top left
set xlabel "grey level (0-255)"
set ylabel "entries per frame (f_max = 20)"
set xrange [0:255]
set title "Emulator counts per frame: eq. 1, rounded once and spread evenly, against eq. 3 as written"
plot csv using 1:2 with lines lw 2 lc rgb "gray40" title "eq. 1: f_max g / 255", \
     csv using 1:4 with steps lw 2 lc rgb "#d62728" title "eq. 3 literal (--spread literal): 20 / k only", \
     csv using 1:3 with steps lw 2 lc rgb "#1f77b4" title "even (default): round(f_max g / 255)"
