# Plots of the penetration-depth benchmark, from pd_bench.csv (gnuplot 5).
# Usage: gnuplot -e "csv='results/pd_bench.csv'; outdir='results'" pd_plots.gp
# Writes:
#   pd_bench.png            one panel per family: median time per query (x) against the
#                           99th-percentile relative error (y), one point per method
#   pd_bench_verts_100.png  the same for the 100-vertex family, larger, with labels
#   pd_bench_scaling.png    median time per query against vertices per hull (verts_*)
# Errors of exactly 0 are drawn at 1e-17 (the bottom of the axis).

if (!exists("csv")) csv = 'results/pd_bench.csv'
if (!exists("outdir")) outdir = 'results'

set datafile separator ","
families = system("awk -F, 'NR>1 && !s[$1]++ {printf \"%s \", $1}' ".csv)
methods = system("awk -F, 'NR>1 && $2!=\"exact\" && !s[$2]++ {printf \"%s \", $2}' ".csv)
scaling = system("awk -F, 'NR>1 && $1 ~ /^verts_/ && !s[$1]++ {printf \"%s \", $1}' ".csv)
nf = words(families)
nm = words(methods)

clampErr(y) = (y < 1e-17 ? 1e-17 : y)
pick(f, m, v) = (strcol(1) eq f && strcol(2) eq m) ? v : NaN
nominal(f) = real(substr(f, 7, strlen(f)))

# Fixed point types and colours per method (same in every plot; re-applied after each reset).
styles = "set style line 1 lc rgb '#d62728' pt 7 ps 1.4; set style line 2 lc rgb '#ff7f0e' pt 5 ps 1.3; set style line 3 lc rgb '#8c564b' pt 9 ps 1.3; set style line 4 lc rgb '#1f77b4' pt 11 ps 1.3; set style line 5 lc rgb '#17becf' pt 13 ps 1.3; set style line 6 lc rgb '#9467bd' pt 4 ps 1.3; set style line 7 lc rgb '#e377c2' pt 6 ps 1.3; set style line 8 lc rgb '#2ca02c' pt 8 ps 1.3; set style line 9 lc rgb '#bcbd22' pt 10 ps 1.3; set style line 10 lc rgb '#7f7f7f' pt 12 ps 1.3; set style line 11 lc rgb '#000000' pt 1 ps 1.5; set style line 12 lc rgb '#aec7e8' pt 3 ps 1.5"
eval(styles)

# ---- one panel per family --------------------------------------------------------------------
cols = 5
rows = int((nf + 1 + cols - 1) / cols)
set terminal pngcairo noenhanced size 2000, 420 * rows font "DejaVu Sans,10"
set output outdir.'/pd_bench.png'
set multiplot layout rows, cols title "Penetration depth: median time per query against 99th-percentile relative error (lower left is better)"
set logscale xy
set format x "1e%T"
set format y "1e%T"
set xlabel "median time per query (µs)"
set ylabel "p99 relative error"
set grid
unset key
do for [i = 1:nf] {
  f = word(families, i)
  set title f
  plot [][1e-17:10] for [j = 1:nm] csv using (pick(f, word(methods, j), $7)):(clampErr($11)) every ::1 with points ls j notitle
}
# The legend, in a panel of its own.
unset title
unset border
unset tics
unset xlabel
unset ylabel
unset grid
unset logscale
set key center center vertical maxrows 12 font ",12"
plot [0:1][0:1] for [j = 1:nm] NaN with points ls j title word(methods, j)
unset multiplot

# ---- the 100-vertex family, labelled ---------------------------------------------------------
reset
eval(styles)
set datafile separator ","
set terminal pngcairo noenhanced size 1100, 800 font "DejaVu Sans,11"
set output outdir.'/pd_bench_verts_100.png'
set title "Random 100-vertex hulls: speed against error (lower left is better)"
set logscale xy
set format x "1e%T"
set format y "1e%T"
set xlabel "median time per query (µs)"
set ylabel "99th-percentile relative error"
set grid
set key outside right
plot [][1e-17:10] for [j = 1:nm] csv using (pick("verts_100", word(methods, j), $7)):(clampErr($11)) every ::1 with points ls j title word(methods, j), \
     csv using (strcol(1) eq "verts_100" && strcol(2) ne "exact" ? $7 : NaN):(clampErr($11)):2 every ::1 with labels offset 0, 1 font ",9" notitle

# ---- scaling with the vertex count -----------------------------------------------------------
reset
eval(styles)
set datafile separator ","
set terminal pngcairo noenhanced size 1100, 800 font "DejaVu Sans,11"
set output outdir.'/pd_bench_scaling.png'
set title "Time per query against vertices per hull (random ellipsoid hulls, median)"
set logscale xy
set format y "1e%T"
set xlabel "vertices per hull"
set ylabel "median time per query (µs)"
set grid
set key outside right
set xtics (8, 30, 100, 300, 1000, 3000)
# Rows of one method in the scaling families, in file order (increasing vertex count), so that
# the line joins them (rows filtered out with NaN would break it).
rowsOf(m) = sprintf("< awk -F, '$1 ~ /^verts_/ && $2 == \"%s\" && $7 != \"\"' %s", m, csv)
timed = system("awk -F, 'NR>1 && $1 ~ /^verts_/ && $2 != \"exact\" && $7 != \"\" && !s[$2]++ {printf \"%s \", $2}' ".csv)
slot(m) = sum [j = 1:nm] (word(methods, j) eq m ? j : 0)
plot for [k = 1:words(timed)] rowsOf(word(timed, k)) using (nominal(strcol(1))):7 with linespoints ls slot(word(timed, k)) title word(timed, k)
