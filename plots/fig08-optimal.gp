# Fig. 08: T*/N and L* against omega.
file = 'fig08-optimal.csv'
what = 'Optimal'
load 'plots/lib/best_vs_omega.gp'
