# Plot of the body penetration-depth benchmark, from body_pd_bench.csv (gnuplot 5).
# Usage: gnuplot -e "csv='results/body_pd_bench.csv'; outdir='results'" body_pd_plots.gp
# Writes body_pd_bench.png: left, median time per query of bodySignedDistance and of the pairwise
# queries it needs against the number of overlapping pairs; right, the pairwise answer's relative
# error against the body answer (median and maximum).

if (!exists("csv")) csv = 'results/body_pd_bench.csv'
if (!exists("outdir")) outdir = 'results'

set datafile separator ","
set terminal pngcairo noenhanced size 1200, 450 font "DejaVu Sans,10"
set output outdir.'/body_pd_bench.png'
set multiplot layout 1, 2 title "Body penetration depth (tiles_N: a box pressed into N touching tiles)"
set logscale xy
set xtics (2, 4, 8, 16)
set grid
set key top left
set xlabel "overlapping pairs"
set ylabel "median time per query (µs)"
plot csv using 2:5 skip 1 with linespoints pt 7 title "bodySignedDistance", \
     csv using 2:6 skip 1 with linespoints pt 5 title "sum of the pairwise queries"
set ylabel "relative error of the deepest pair's depth"
set format y "1e%T"
plot csv using 2:($9 > 0 ? $9 : 1e-17) skip 1 with linespoints pt 7 title "median", \
     csv using 2:($10 > 0 ? $10 : 1e-17) skip 1 with linespoints pt 5 title "max"
unset multiplot
