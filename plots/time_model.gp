# The time model against measurement. Left: predicted against measured query
# wall time over the calibration scenes (filled: fitted; open: held-out
# packings), for the single-K fit W = c0 N + c_cell A + c_test C and for the
# time model (docs/MODEL.md section 9). Right: on the figure-11-like
# packings, build + query time with the optimal sizes for K = 0.2 over that
# with the time-optimal sizes (> 1: the time model's sizes are faster).
# Run by plots/calibration.sh:
# gnuplot -e "scenes='results/calibration-scenes.csv'; ratio='results/calibration-ratio.csv'; out='paper_figs/time-model.png'" plots/time_model.gp
set terminal pngcairo enhanced size 1500,620 font 'Helvetica,12'
set output out
set datafile separator ','
set datafile columnheaders
set multiplot layout 1,2

fit_(v) = column("holdout") == 0 ? v : NaN
held(v) = column("holdout") == 1 ? v : NaN
ns(c) = 1e9 * column(c) / column("n")
set title 'calibration scenes: predicted vs measured query time'
set logscale xy
set xlabel 'measured query time / N  [ns]  (fastest uncounted run)'
set ylabel 'predicted / N  [ns]'
set key top left box opaque
set grid
plot x with lines lc rgb 'black' dt 2 title 'predicted = measured', \
     scenes using (fit_(ns("seconds"))):(ns("W_fit")) with points pt 7 ps 1.0 lc rgb '#d62728' \
       title 'single-K fit (fitted scenes)', \
     scenes using (held(ns("seconds"))):(ns("W_fit")) with points pt 6 ps 1.3 lc rgb '#d62728' \
       title 'single-K fit (held out)', \
     scenes using (fit_(ns("seconds"))):(ns("time_model_query")) with points pt 5 ps 1.0 lc rgb '#1f77b4' \
       title 'time model (fitted scenes)', \
     scenes using (held(ns("seconds"))):(ns("time_model_query")) with points pt 4 ps 1.3 lc rgb '#1f77b4' \
       title 'time model (held out)'

unset logscale
set title 'fig.-11-like packings (3D, {/Symbol a} = -3, N = 10^5): sizes for K = 0.2 vs time-optimal sizes'
set xlabel 'packing fraction {/Symbol n}'
set ylabel 'build + query time (K = 0.2 sizes) / (time-optimal sizes)'
set xrange [0.05:0.65]
set yrange [*:*]
set key below horizontal maxrows 3 box spacing 1.1
set bmargin 8
sel(p, w, v) = (strcol("placement") eq p && abs(column("omega") - w) < 1e-9) ? v : NaN
omegas = "2 10 50 100"
plot 1 with lines lc rgb 'black' dt 2 notitle, \
     for [i=1:words(omegas)] ratio using (sel("excluded", real(word(omegas,i)), column("nu"))):"build_query_ratio_time" \
       with linespoints pt 7 ps 1.2 lc i title sprintf('excluded, {/Symbol w} = %s', word(omegas,i)), \
     for [i=1:words(omegas)] ratio using (sel("random", real(word(omegas,i)), column("nu"))):"build_query_ratio_time" \
       with linespoints pt 6 ps 1.4 dt 3 lc i title sprintf('random, {/Symbol w} = %s', word(omegas,i))
unset multiplot
