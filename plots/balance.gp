# Simulated load balance of the threaded query (plots/balance.sh): imbalance
# (simulated time over a perfect split, minus 1) against nu, one panel per
# placement, a line per omega and thread count.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 10in,4.3in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 1400,600 font 'Helvetica,12' }
set output out
set datafile separator ','
set multiplot layout 1,2 title sprintf('Simulated imbalance of the threaded query, figure-11 packings ({/Symbol a} = -3), N = %s', n)
set xlabel 'packing fraction {/Symbol n}'
set ylabel 'imbalance (simulated time / ideal - 1)'
set logscale y
set yrange [1e-4:*]
set grid
set key top left box opaque font ',9' maxrows 6
if (!exists("omegas")) omegas = '2 10 50 100'
threads = '8 64 256'
pt(t) = t == 8 ? 7 : (t == 64 ? 5 : 9)
dt(t) = t == 8 ? 1 : (t == 64 ? 2 : 3)
do for [pl in 'excluded random'] {
  set title pl eq 'excluded' ? 'excluded volume' : 'random centres'
  plot for [t in threads] for [w in omegas] \
    '< awk -F, -v pl='.pl.' -v w='.w.' -v t='.t.' ''!/^#/ && $1 == pl && $2 == w && $5 == t'' '.in \
    using 3:($7 > 1e-4 ? $7 : 1e-4) with linespoints dt dt(int(t)) pt pt(int(t)) \
    title sprintf('P = %s, {/Symbol w} = %s', t, w)
}
unset multiplot
