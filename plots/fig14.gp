# Fig. 14 (ours; the paper reports the full DPM test in words only): kinetic
# energy of the 2D free-cooling run against time, optimal HGrid and linked
# cell, with the Haff-law fit E0 / (1 + t/t0)^2 (Haff 1983).
# gnuplot -e "in='results/dpm_free_cooling-energy.csv'; out='x.png'; fmt='png'; scale_label='default'" plots/fig14.gp
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 6in,4.2in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 900,630 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set key top right box opaque
set logscale xy
set xlabel 'time t (units: r_{min} = 1, initial velocity std = 1)'
set ylabel 'kinetic energy E(t) / E(0)'
set grid
set title sprintf('Free cooling, d = 2, N = %s, {/Symbol a} = -3, {/Symbol w} = 20, {/Symbol n} = 0.4 (%s)', n_label, scale_label)
stats in using "E_optimal" nooutput
E0 = STATS_max
plot in using "t":(column("E_optimal") / E0) every ::1 with lines lw 2 lc rgb '#0072B2' title 'optimal HGrid', \
     in using "t":(column("E_linked_cell") / E0) every ::1 with lines lw 2 dt 2 lc rgb '#D55E00' title 'linked cell', \
     in using "t":(column("E_haff") / E0) every ::1 with lines lw 1 lc rgb 'black' title "Haff's law fit"
