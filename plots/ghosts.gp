# Ghosts of the decomposed search (plots/ghosts.sh): how many fewer copies
# the level-aware layer sends than one 2 r_max shell, against omega, and the
# ghosts per particle of both.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 10in,4.3in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 1400,600 font 'Helvetica,12' }
set output out
set datafile separator ','
set multiplot layout 1,2 title sprintf('Ghost layer of the decomposed search, random centres, {/Symbol a} = -3, {/Symbol n} = 0.6, N = %s', n)
set logscale x
set xlabel 'size ratio {/Symbol w}'
set grid
set key top left box opaque
sel(p) = '< awk -F, -v p='.p.' ''!/^#/ && $2 == p'' '.in
set title 'shell ghosts / level-aware ghosts'
set ylabel 'ratio'
set logscale y
plot for [p in '2 4'] sel(p) using 1:7 with linespoints pt 7 title 'P = '.p, \
     5 with lines dt 2 lc rgb 'gray' title 'target 5'
set title 'ghosts per particle'
set ylabel 'ghost copies / N'
plot for [p in '2 4'] sel(p) using 1:($5/$3) with linespoints pt 7 title 'level-aware, P = '.p, \
     for [p in '2 4'] sel(p) using 1:($6/$3) with linespoints pt 5 dt 2 title '2 r_{max} shell, P = '.p
unset multiplot
