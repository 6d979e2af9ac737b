# Narrow-phase checks per particle by level of the searching particle:
# measured, the paper's model (random centres), the excluded-volume model.
if (!exists("fmt")) fmt = 'png'
if (fmt eq 'pdf') { set terminal pdfcairo enhanced size 6in,4.2in font 'Helvetica,11' } \
else { set terminal pngcairo enhanced size 900,630 font 'Helvetica,12' }
set output out
set datafile separator ','
set datafile columnheaders
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set key top right box opaque
set xlabel 'level h of the searching particle'
set ylabel 'narrow-phase checks / N'
set yrange [0:*]
set grid ytics
set title sprintf('Excluded volume, {/Symbol a} = -3, {/Symbol w} = 100, {/Symbol n} = 0.6, N = %s', n)
plot in using "measured":xtic(1) title 'measured' lc rgb '#333333', \
     '' using "paper_model" title 'paper model (random centres)' lc rgb '#d95f02', \
     '' using "excluded_model" title 'excluded-volume model (Percus-Yevick)' lc rgb '#1b9e77'
