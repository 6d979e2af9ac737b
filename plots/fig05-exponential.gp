# Fig. 05: T*/N and L* against omega.
file = 'fig05-exponential.csv'
what = 'Exponential'
load 'plots/lib/best_vs_omega.gp'
