# Fig. 10: (a) s_h/r_min and (b) m_h against h/L* at each method's optimum.
load 'plots/lib/style.gp'
set multiplot layout 1,2 title 'Fig. 10: the levels of each method''s best grid (L = L^*), Top-Down, {/Symbol w} = 100, {/Symbol a} = -3'
set xlabel 'h/L^*'
set logscale y
set key top left
set ylabel 's_h/r_{min}'
set title '(a) cell sizes s_h'
plot d('fig10-profile-linear.csv') u 2:3 w lp ls 1 t 'Linear', d('fig10-profile-exponential.csv') u 2:3 w lp ls 2 t 'Exponential', \
     d('fig10-profile-constant.csv') u 2:3 w lp ls 3 t 'Constant particles/cell', d('fig10-profile-optimal.csv') u 2:3 w lp ls 4 t 'Optimal'
set ylabel 'm_h'
set title '(b) particles per cell m_h'
set key bottom left
plot d('fig10-profile-linear.csv') u 2:4 w lp ls 1 t 'Linear', d('fig10-profile-exponential.csv') u 2:4 w lp ls 2 t 'Exponential', \
     d('fig10-profile-constant.csv') u 2:4 w lp ls 3 t 'Constant particles/cell', d('fig10-profile-optimal.csv') u 2:4 w lp ls 4 t 'Optimal'
unset multiplot
