# Fig. 08: T*/N and L* against omega.
file = 'fig08-optimal.csv'
fig = 'Fig. 8'
what = 'optimal'
load 'plots/lib/best_vs_omega.gp'
