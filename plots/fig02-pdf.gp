# Fig. 2: the truncated power-law pdf, omega = 3.
load 'plots/lib/style.gp'
set xlabel 'r/r_{min}'
set ylabel 'f(r)'
set title 'Fig. 2: the power-law size distributions f(r) ~ r^{/Symbol a} studied, {/Symbol w} = r_{max}/r_{min} = 3'
plot d('fig02-pdf.csv') u 1:2 w l ls 1 t '{/Symbol a} = 0', '' u 1:3 w l ls 2 t '{/Symbol a} = -1', \
     '' u 1:4 w l ls 3 t '{/Symbol a} = -2', '' u 1:5 w l ls 4 t '{/Symbol a} = -3'
