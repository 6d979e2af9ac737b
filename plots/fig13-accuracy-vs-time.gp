# Fig. 13 (not in the paper): time to choose the sizes with L* against how far
# T lies above the optimum; alpha = 0, -3 and omega = 10, 100, 1000, Top-Down.
# Time-optimal: the sizes minimising a machine's predicted seconds (the time
# model of results/calibration.json, N = 10^6), costed in the paper's T.
load 'plots/lib/style.gp'
set logscale xy
set format xy '10^{%L}'
set xlabel 'time to compute sizes and L^* [s]'
set ylabel '(T - T_{opt}) / T_{opt}   (optimal: plotted at 10^{-12})'
set title 'Fig. 13 (beyond the paper): cost above the optimum against the time to choose the sizes (d = 3, {/Symbol n} = 0.7, K = 0.2)'
set key top right
f(y) = y > 1e-12 ? y : 1e-12
plot for [i=0:4] d('fig13-accuracy-time.csv') u ($1 == i ? $4 : NaN):(f($6)) w p ls (i+1) ps 1.2 \
     t word('Linear Exponential Constant Optimal Time-optimal', i+1)
