# hgridlab vs its peers: tool time per neighbour build / hgridlab HGrid time,
# against the packing fraction (figure-11 packings: 3D, alpha = -3, omega = 100).
# gnuplot -e "in='results/peers.csv'; out='paper_figs/peers.png'" plots/peers.gp
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 6in,4.2in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 900,630 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set key at graph 0.02, graph 0.98 left top box opaque  # above every curve: the y range leaves room
set xlabel 'packing fraction {/Symbol n}'
set ylabel 'time per build / hgridlab HGrid time'
set logscale y
set grid
set xrange [0:0.65]
set yrange [0.8:1e5]  # room for the key above LAMMPS bin (at most ~2000x)
if (!exists("placement")) placement = 'excluded'
set title sprintf('hgridlab vs peers: {/Symbol a} = -3, {/Symbol w} = 100, d = 3, periodic, %s', placement)
if (!exists("tools")) tools = "lammps_multi lammps_bin cgal embree bullet"
# One tool (and placement) at a time, so that its points are joined by lines.
rows(t) = sprintf("< awk -F, 'NR == 1 || ($4 == \"%s\" && $3 == \"%s\")' '%s'", t, placement, in)
# in2 (plots/peers.sh): MercuryDPM's HGrid, from a run of its own (ratios to
# that run's hgridlab): with hgridlab's sizes and with its default grid.
if (!exists("in2")) in2 = ''
mtools = "mercurydpm mercurydpm_default"
mrows(t) = sprintf("< awk -F, 'NR == 1 || ($4 == \"%s\" && $3 == \"%s\")' '%s'", t, placement, in2)
plot for [i=1:words(tools)] rows(word(tools,i)) using "nu":"ratio_vs_hgrid" \
       with linespoints lw 2 pt 7 lc i title word(tools,i) noenhanced, \
     for [i=1:(in2 eq '' ? 0 : words(mtools))] mrows(word(mtools,i)) using "nu":"ratio_vs_hgrid" \
       with linespoints lw 2 pt 5 lc (words(tools) + i) title word(mtools,i).' (periodic: its ghosts)' noenhanced, \
     10 with lines lw 2 lc rgb 'gray30' dt 4 title 'target for LAMMPS multi (10x)', \
     1 with lines lc rgb 'black' dt 2 title 'hgridlab'
