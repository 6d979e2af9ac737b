# Fig. 3: single level (linked cell), T/N against omega.
load 'plots/lib/style.gp'
set logscale xy
set format y '10^{%L}'
set xlabel '{/Symbol w} = r_{max}/r_{min}'
set ylabel 'T/N'
set key top left
set title 'Fig. 3: the model''s cost of a single level (the linked cell) against the size ratio, d = 3, {/Symbol n} = 0.7, K = 0.2'
plot d('fig03-single-level.csv') u 1:2 w l ls 1 t '{/Symbol a} = 0', '' u 1:3 w l ls 2 t '{/Symbol a} = -1', \
     '' u 1:4 w l ls 3 t '{/Symbol a} = -2', '' u 1:5 w l ls 4 t '{/Symbol a} = -3'
