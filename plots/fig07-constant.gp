# Fig. 07: T*/N and L* against omega.
file = 'fig07-constant.csv'
what = 'Constant particles per cell (q = 1),'
load 'plots/lib/best_vs_omega.gp'
