# Fig. 9: T/N against L for the four methods.
load 'plots/lib/style.gp'
set logscale y
set yrange [10:100]
set xlabel 'L'
set ylabel 'T/N'
set title 'Fig. 9: the model''s cost of each method''s sizes against the number of levels, Top-Down, {/Symbol w} = 100, {/Symbol a} = -3, d = 3, {/Symbol n} = 0.7, K = 0.2'
plot d('fig09-methods-vs-L.csv') u 1:2 w lp ls 1 t 'Linear', '' u 1:3 w lp ls 2 t 'Exponential', \
     '' u 1:4 w lp ls 3 t 'Constant particles/cell', '' u 1:5 w lp ls 4 t 'Optimal'
