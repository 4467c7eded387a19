# Plot of the load-time benchmark, from load_bench.csv (gnuplot 5).
# Usage: gnuplot -e "csv='results/load_bench.csv'; outdir='results'" load_plots.gp
# Writes load_bench.png: load time against the number of items loaded, one line per kind, on
# log-log axes with a dotted line of slope 1 (linear growth) for reference.

if (!exists("csv")) csv = 'results/load_bench.csv'
if (!exists("outdir")) outdir = 'results'

set datafile separator ","
kinds = system("awk -F, 'NR>1 && !s[$1]++ {printf \"%s \", $1}' ".csv)
pick(k, v) = (strcol(1) eq k) ? v : NaN

set terminal pngcairo size 900,600 font ",11" noenhanced
set output outdir.'/load_bench.png'
set title "Load time against size (bench/load_bench.cpp)"
set xlabel "items loaded (boxes, links, triangles)"
set ylabel "seconds"
set logscale xy
set grid
set key top left
plot for [i=1:words(kinds)] csv using 2:(pick(word(kinds, i), $3)) with linespoints lw 2 pt 7 title word(kinds, i), \
     [200:10000] 1e-4 * x with lines dt 3 lc rgb '#7f7f7f' title "slope 1 (linear)"
