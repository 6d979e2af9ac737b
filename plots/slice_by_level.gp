# Sections of the particles cut by the plane z = A/2, coloured by their
# level of insertion (1 = finest) in the recommended grid; the periodic box
# [0, box]^2 clips the particles that cross its sides.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 6.4in,6in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 960,900 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set size ratio -1
set xrange [0:box]
set yrange [0:box]
set xlabel 'x'
set ylabel 'y'
set palette defined (1 '#0072B2', 2 '#56B4E9', 3 '#009E73', 4 '#F0E442', 5 '#E69F00', 6 '#D55E00', 7 '#CC79A7', 8 '#000000')
set cbrange [0.5:levels + 0.5]
set cbtics 1
set cblabel 'level of insertion'
set style fill solid 0.85 noborder
set title sprintf('Slice z = A/2: excluded volume, {/Symbol a} = -3, {/Symbol w} = 100, {/Symbol n} = 0.6, N = %s, %d levels (K = 0.2)', n, levels)
plot in using 1:2:3:4 with circles lc palette notitle
