# ns per particle (build + pair finding) against N for every tool, on one
# thread (solid) and on `threads` (dashed) (plots/peers_threads.sh).
set terminal pngcairo enhanced size 1000,700 font 'Helvetica,12'
set output out
set datafile separator ','
set logscale xy
set xlabel 'N (figure-11 packing: {/Symbol a} = -3, {/Symbol w} = 100, {/Symbol n} = 0.6, excluded volume)'
set ylabel 'wall time per particle (ns)'
set grid
set key outside right box noenhanced
set format y '10^{%L}'
tools = 'hgrid lammps_multi lammps_bin cgal embree bullet'
color(k) = word('#1b9e77 #d95f02 #7570b3 #e7298a #66a61e #e6ab02', k)
sel(tool, t) = sprintf("< awk -F, '$3 == \"%s\" && $2 == %d' %s | sort -t, -k1 -g", tool, t, in)
plot for [k = 1:words(tools)] sel(word(tools, k), 1) using 1:($5 * 1e9) with linespoints lw 2 pt 7 \
       lc rgb color(k) title sprintf('%s, 1 thread', word(tools, k)), \
     for [k = 1:words(tools)] sel(word(tools, k), threads) using 1:($5 * 1e9) with linespoints lw 2 dt 2 pt 6 \
       lc rgb color(k) title sprintf('%s, %d threads/ranks', word(tools, k), threads)
