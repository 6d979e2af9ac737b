# Figs. 4, 5, 7, 8: (a) T*/N and (b) L* against omega; set `file`, `fig` and `what` first.
load 'plots/lib/style.gp'
set multiplot layout 1,2 title fig.': the model''s least cost over the number of levels, '.what.' cell sizes (d = 3, {/Symbol n} = 0.7, K = 0.2)'
set logscale x
set xlabel '{/Symbol w} = r_{max}/r_{min}'
set ylabel 'T^*/N'
set title '(a) least predicted cost T^*/N = min_L T/N'
set key top left
plot d(file) u 1:2 w lp ls 1 t 'Top-Down, {/Symbol a} = 0', \
     '' u 1:4 w lp ls 2 t 'Top-Down, {/Symbol a} = -3', \
     '' u 1:6 w lp ls 3 dt 2 t 'Bottom-Up, {/Symbol a} = 0', \
     '' u 1:8 w lp ls 4 dt 2 t 'Bottom-Up, {/Symbol a} = -3'
set ylabel 'L^*'
set title '(b) the number of levels L^* that gives it'
plot d(file) u 1:3 w lp ls 1 t 'Top-Down, {/Symbol a} = 0', \
     '' u 1:5 w lp ls 2 t 'Top-Down, {/Symbol a} = -3', \
     '' u 1:7 w lp ls 3 dt 2 t 'Bottom-Up, {/Symbol a} = 0', \
     '' u 1:9 w lp ls 4 dt 2 t 'Bottom-Up, {/Symbol a} = -3'
unset multiplot
