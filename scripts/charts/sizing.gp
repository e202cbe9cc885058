# Power per quadrant against reconstruction PSNR for every run of a sizing sweep
# (scripts/sweeps/sizing.toml), feasible designs' runs highlighted. Called by aesim sweep.
csv = ARG1; png = ARG2; svg = ARG3  # paths arrive as arguments, never as code
set datafile separator ","
set datafile columnheaders
set grid
set key outside bottom center horizontal font ",10"
set xlabel "power per 32x32 quadrant (uW)"
set ylabel "PSNR of the reconstruction after the 1 s window (dB)"
do for [format in "png svg"] {
  if (format eq "png") { set terminal pngcairo size 1100,700 font ",11"; set output png }
  if (format eq "svg") { set terminal svg size 1100,700 dynamic font ",11"; set output svg }
  set title "Sizing the aloha pixel: every run (scene x light x design); filled: designs feasible in every condition"
  plot csv using (column("feasible") > 0 ? NaN : 1e6 * column("power_per_tile_w")):"psnr_db" with points pt 6 ps 1.2 lc rgb "gray50" title "infeasible design", \
       csv using (column("feasible") > 0 ? 1e6 * column("power_per_tile_w") : NaN):"psnr_db" with points pt 7 ps 1.4 lc rgb "#0072b2" title "feasible design"
  set output
}
