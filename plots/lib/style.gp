# Shared look of the hgridlab figures; `datadir` is set by make_figures.sh.
set datafile separator ','
set key box opaque samplen 2 spacing 1.1
set grid lc rgb '#dddddd'
set style line 1 lc rgb '#0072B2' lw 2 pt 7 ps 0.6
set style line 2 lc rgb '#D55E00' lw 2 pt 5 ps 0.6
set style line 3 lc rgb '#009E73' lw 2 pt 9 ps 0.7
set style line 4 lc rgb '#CC79A7' lw 2 pt 11 ps 0.7
set style line 5 lc rgb '#E69F00' lw 2 pt 13 ps 0.8
d(f) = datadir.'/'.f
