# Fig. 04: T*/N and L* against omega.
file = 'fig04-linear.csv'
what = 'Linear'
load 'plots/lib/best_vs_omega.gp'
