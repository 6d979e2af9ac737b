# Fig. 07: T*/N and L* against omega.
file = 'fig07-constant.csv'
fig = 'Fig. 7'
what = 'constant-particles-per-cell (q = 1)'
load 'plots/lib/best_vs_omega.gp'
