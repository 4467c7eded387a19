# Plot of the load-time benchmark, from load_bench.csv (gnuplot 5).
# Usage: gnuplot -e "csv='results/load_bench.csv'; outdir='results'" load_plots.gp
# Writes load_bench.png: load time against the number of items loaded, one line per kind, on
# log-log axes with a dotted line of slope 1 (linear growth) for reference; and
# load_bench_hand.png: the non-convex hand's and comb's pieces and excess (mm) against triangles.

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
     [200:100000] 1e-4 * x with lines dt 3 lc rgb '#7f7f7f' title "slope 1 (linear)"

set output outdir.'/load_bench_hand.png'
set key bottom right
set xrange [500:200000]
set title "Non-convex hand and comb: pieces and excess against triangles (bench/load_bench.cpp)"
set xlabel "triangles"
set ylabel "pieces"
set y2label "excess (mm): how far the pieces stick out of the mesh"
unset logscale y
set ytics nomirror
set y2tics
set yrange [0:*]
set y2range [0:*]
plot for [k in "hand comb"] csv using 2:(pick(k, $5)) with linespoints lw 2 pt 7 title k." pieces", \
     for [k in "hand comb"] csv using 2:(pick(k, 1000 * $6)) axes x1y2 with linespoints lw 2 pt 5 dt 2 title k." excess (mm)"
