# Fig. 05: T*/N and L* against omega.
file = 'fig05-exponential.csv'
fig = 'Fig. 5'
what = 'exponential'
load 'plots/lib/best_vs_omega.gp'
