# Does measuring K pay? Left: query wall time per particle against the counted
# cost T/N = (checks + K accesses)/N over the calibration scenes, for the
# paper's K = 0.2 and the calibrated K. Right: on figure-11-like packings,
# wall time with the optimal sizes for K = 0.2 over that with the sizes for
# the calibrated K (> 1: the calibrated K picks faster sizes).
# Run by plots/calibration.sh:
# gnuplot -e "scenes='results/calibration-scenes.csv'; ratio='results/calibration-ratio.csv'; out='paper_figs/calibration.png'; Kcal=1.0" plots/calibration.gp
set terminal pngcairo enhanced size 1500,620 font 'Helvetica,12'
set output out
set datafile separator ','
set datafile columnheaders
set multiplot layout 1,2

# Pearson correlation of log W against log T, for each K.
stats scenes using (log(column("T_K02") / column("n"))):(log(column("seconds") / column("n"))) nooutput
r02 = STATS_correlation
stats scenes using (log(column("T_Kcal") / column("n"))):(log(column("seconds") / column("n"))) nooutput
rcal = STATS_correlation

set title 'calibration scenes: wall time vs counted cost'
set logscale xy
set xlabel 'counted T / N = (checks + K accesses) / N'
set ylabel 'query wall time / N  [ns]  (fastest uncounted run)'
set key top left box opaque
set grid
plot scenes using (column("T_K02") / column("n")):(1e9 * column("seconds") / column("n")) \
       with points pt 6 ps 1.4 lc rgb '#d62728' title sprintf('K = 0.2 (paper): corr. of logs %.3f', r02), \
     scenes using (column("T_Kcal") / column("n")):(1e9 * column("seconds") / column("n")) \
       with points pt 7 ps 1.1 lc rgb '#1f77b4' title sprintf('K = %.3g (calibrated): corr. of logs %.3f', Kcal, rcal)

unset logscale
set title sprintf('fig.-11-like packings (3D, {/Symbol a} = -3, N = 10^5): optimal sizes for K = 0.2 vs K = %.3g', Kcal)
set xlabel 'packing fraction {/Symbol n}'
set ylabel 'query time (sizes for K = 0.2) / query time (sizes for calibrated K)'
set xrange [0.05:0.65]
set yrange [*:*]
set key top left box opaque
sel(p, w, v) = (strcol("placement") eq p && abs(column("omega") - w) < 1e-9) ? v : NaN
omegas = "2 10 50 100"
plot 1 with lines lc rgb 'black' dt 2 notitle, \
     for [i=1:words(omegas)] ratio using (sel("excluded", real(word(omegas,i)), column("nu"))):"query_ratio" \
       with linespoints pt 7 ps 1.2 lc i title sprintf('excluded, {/Symbol w} = %s', word(omegas,i)), \
     for [i=1:words(omegas)] ratio using (sel("random", real(word(omegas,i)), column("nu"))):"query_ratio" \
       with linespoints pt 6 ps 1.4 dt 3 lc i title sprintf('random, {/Symbol w} = %s', word(omegas,i))
unset multiplot
