# Fig. 6: constant ratio q of particles per cell, T/N against L; inset min T vs q.
load 'plots/lib/style.gp'
set multiplot
set logscale y
set xlabel 'L'
set ylabel 'T/N'
set yrange [10:1000]
set title 'Fig. 6: the model''s cost against L, cell sizes in a constant ratio q (Top-Down, {/Symbol w} = 100, {/Symbol a} = -3)'
set key top left
plot d('fig06-constant-q.csv') u 1:2 w lp ls 1 t 'q = 0.5', '' u 1:3 w lp ls 2 t 'q = 1', \
     '' u 1:4 w lp ls 3 t 'q = 2', '' u 1:5 w lp ls 4 t 'q = 5'
set origin 0.5, 0.45
set size 0.45, 0.42
unset title
set logscale x
set autoscale y
unset logscale y
set xlabel 'q' offset 0,0.5
set ylabel 'min_L T/N' offset 1,0
set key off
set yrange [11:16]
plot d('fig06-inset-min-vs-q.csv') u 1:2 w lp ls 2
unset multiplot
