# Plot of the nearest-neighbour benchmark, from nearest_bench.csv (gnuplot 5).
# Usage: gnuplot -e "csv='results/nearest_bench.csv'; outdir='results'" nearest_plots.gp
# Writes nearest_bench.png: the time of one query against the number of elements, one line per
# method, on log-log axes.

if (!exists("csv")) csv = 'results/nearest_bench.csv'
if (!exists("outdir")) outdir = 'results'

set datafile separator ","
methods = system("awk -F, 'NR>1 && !s[$2]++ {printf \"%s \", $2}' ".csv)
rows(m) = sprintf("< awk -F, '$2 == \"%s\"' '%s'", m, csv)

set terminal pngcairo size 900,600 font ",11" noenhanced
set output outdir.'/nearest_bench.png'
set title "Nearest neighbour on the Panda's 7 joints (bench/nearest_bench.cpp)"
set xlabel "elements in the tree"
set ylabel "ns per query"
set logscale xy
set grid
set key top left
plot for [i=1:words(methods)] rows(word(methods, i)) using 1:3 with linespoints lw 2 pt 7 title word(methods, i)
