# Equilibrium from both sides: error of T/N against the excluded-volume
# model after hard-sphere Monte Carlo, starting from packings made by
# compression and by sequential addition (results/equilibrated-compressed.csv,
# written by `bash plots/equilibrated.sh compressed`). Variables: in, out, fmt.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 9in,5.4in font 'Helvetica,10' } \
else { set terminal pngcairo enhanced size 1350,810 font 'Helvetica,11' }
set output out
set datafile separator ','
set datafile commentschars '#'
set grid lc rgb '#dddddd'
set logscale x
set xrange [60:2e6]
set xtics ('as made' 100, '10^3' 1e3, '10^4' 1e4, '10^5' 1e5, '10^6' 1e6)
set yrange [-8.5:1.5]
set ytics 1
set xlabel 'Monte Carlo sweeps'
set ylabel 'T/N measured / model - 1  (%)'
set style line 1 lc rgb '#0072B2' lw 2 pt 7 ps 0.8
set style line 2 lc rgb '#0072B2' lw 2 pt 6 ps 0.8 dt 2
set style line 3 lc rgb '#D55E00' lw 2 pt 5 ps 0.8
set style line 4 lc rgb '#D55E00' lw 2 pt 4 ps 0.8 dt 2
set style line 9 lc rgb '#999999' lw 1 dt 3
# Columns: 1 boundary, 2 alpha, 3 omega, 5 n, 6 sweeps, 12 error_excluded, 15 seed, 16 method.
x(s) = s > 0 ? s : 100
pick(b, a, w, n, seed, m) = (strcol(1) eq b && $2 == a && $3 == w && $5 == n && $15 == seed && strcol(16) eq m) \
                            ? 100 * $12 : NaN
set multiplot layout 2, 3 title 'Equilibrium from both sides: {/Symbol n} = 0.6, excluded-volume model (Percus-Yevick)'
panel(b, a, w, n) = sprintf('%s, {/Symbol a} = %g, {/Symbol w} = %g, N = %g', b, a, w, n)
do for [p = 1:6] {
  b = (p == 3 || p == 4) ? 'walls' : 'periodic'
  a = (p == 6) ? -2 : -3
  w = (p == 1) ? 100 : 10
  n = (p == 1 || p == 5 || p == 6) ? 30000 : (p == 4 ? 10000 : 3000)
  set title panel(b, a, w, n)
  if (p == 1) { set key bottom right box opaque samplen 3 } else { unset key }
  plot 3 ls 9 notitle, -3 ls 9 notitle, 0 lc rgb '#bbbbbb' notitle, \
       in using (x($6)):(pick(b, a, w, n, 1, 'growth')) with linespoints ls 1 title 'compression, seed 1', \
       in using (x($6)):(pick(b, a, w, n, 2, 'growth')) with linespoints ls 2 title 'compression, seed 2', \
       in using (x($6)):(pick(b, a, w, n, 1, 'auto')) with linespoints ls 3 title 'sequential addition, seed 1', \
       in using (x($6)):(pick(b, a, w, n, 2, 'auto')) with linespoints ls 4 title 'sequential addition, seed 2'
}
unset multiplot
