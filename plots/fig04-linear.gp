# Fig. 04: T*/N and L* against omega.
file = 'fig04-linear.csv'
fig = 'Fig. 4'
what = 'linear'
load 'plots/lib/best_vs_omega.gp'
