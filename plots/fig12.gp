# Figure 12: T/N measured vs model against N; nu = 0.6, omega = 10.
# Open symbols: walls; filled: periodic; lines: model.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 8in,4.6in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 1250,700 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set key outside right top box font ',10'
set logscale x
set format x '10^{%T}'
set xlabel 'N'
set ylabel 'T / N  (K = 0.2)'
set yrange [0:*]
set grid
packings = strstrt(in, 'fig12_growth') > 0 ? ', packings by compression' : ''
set title sprintf('Fig. 12: {/Symbol n} = 0.6, {/Symbol w} = 10, d = 3, optimal Top-Down sizes (%s%s)', scale_label, packings)
sel(b, a, v) = (strcol("boundary") eq b && abs(column("alpha") - a) < 1e-9) ? v : NaN
alphas = exists("series") ? series : "0 -1 -2 -3"
plot for [i=1:words(alphas)] in using (sel("periodic", real(word(alphas,i)), column("n"))):"model_T_over_N" \
       with lines lw 2 lc i title sprintf('paper model, {/Symbol a} = %s', word(alphas,i)), \
     for [i=1:words(alphas)] in using (sel("periodic", real(word(alphas,i)), column("n"))):"model_excluded_T_over_N" \
       with lines lw 2 dt 2 lc i title sprintf('excluded-volume model, periodic, {/Symbol a} = %s', word(alphas,i)), \
     for [i=1:words(alphas)] in using (sel("walls", real(word(alphas,i)), column("n"))):"model_excluded_T_over_N" \
       with lines lw 2 dt 3 lc i title sprintf('excluded-volume model, walls, {/Symbol a} = %s', word(alphas,i)), \
     for [i=1:words(alphas)] in using (sel("walls", real(word(alphas,i)), column("n"))):"T_over_N" \
       with points pt 6 ps 1.4 lc i title sprintf('walls, {/Symbol a} = %s', word(alphas,i)), \
     for [i=1:words(alphas)] in using (sel("periodic", real(word(alphas,i)), column("n"))):"T_over_N" \
       with points pt 7 ps 1.1 lc i title sprintf('periodic, {/Symbol a} = %s', word(alphas,i))
