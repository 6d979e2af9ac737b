# Figure 11: T/N measured (symbols) vs the paper's model (solid) and the
# excluded-volume model (dashed) against nu; alpha = -3.
# gnuplot -e "in='results/fig11.csv'; out='paper_figs/fig11-measured-vs-model-nu.png'; fmt='png'" plots/fig11.gp
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 7.7in,4.2in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 1150,630 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set key outside right top box
set xlabel 'packing fraction {/Symbol n}'
set ylabel 'T / N  (K = 0.2)'
set xrange [0:0.65]
set yrange [0:*]
set grid
set title sprintf('Fig. 11: {/Symbol a} = -3, d = 3, optimal Top-Down sizes (%s)', scale_label)
sel(p, w, v) = (strcol("placement") eq p && abs(column("omega") - w) < 1e-9) ? v : NaN
omegas = exists("series") ? series : "2 10 50 100"
plot for [i=1:words(omegas)] in using (sel("excluded", real(word(omegas,i)), column("nu"))):"model_T_over_N" \
       with lines lw 2 lc i title sprintf('paper model, {/Symbol w} = %s', word(omegas,i)), \
     for [i=1:words(omegas)] in using (sel("excluded", real(word(omegas,i)), column("nu"))):"model_excluded_T_over_N" \
       with lines lw 2 dt 2 lc i title sprintf('excluded-volume model, {/Symbol w} = %s', word(omegas,i)), \
     for [i=1:words(omegas)] in using (sel("excluded", real(word(omegas,i)), column("nu"))):"T_over_N" \
       with points pt 7 ps 1.2 lc i title sprintf('excluded volume, {/Symbol w} = %s', word(omegas,i)), \
     for [i=1:words(omegas)] in using (sel("random", real(word(omegas,i)), column("nu"))):"T_over_N" \
       with points pt 6 ps 1.6 lc i title sprintf('random centres, {/Symbol w} = %s', word(omegas,i))
