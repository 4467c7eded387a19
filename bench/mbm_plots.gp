# Plot of the MotionBenchMaker benchmark, from the mbm_bench.csv that mbm_bench writes in its
# output folder (gnuplot 5; mbm_bench runs it; bench/run_mbm_bench.sh keeps the plot of its
# certified run as bench/results/mbm_bench.png).
# Usage: gnuplot -e "csv='OUT/mbm_bench.csv'; outdir='OUT'" mbm_plots.gp
# Writes mbm_bench.png: one panel per planner; per scene the median planning time (bar) and
# the 90th percentile (point), one colour per checker, log scale. A missing bar: no run.

if (!exists("csv")) csv = 'results/mbm/mbm_bench.csv'
if (!exists("outdir")) outdir = 'results/mbm'

set datafile separator ","
scenes = system("awk -F, 'NR>1 && !s[$1]++ {printf \"%s \", $1}' ".csv)
planners = system("awk -F, 'NR>1 && !s[$3]++ {printf \"%s \", $3}' ".csv)
ns = words(scenes)
nl = words(planners)

pick(s, c, l, v) = (strcol(1) eq s && strcol(2) eq c && strcol(3) eq l) ? v : NaN

set style line 1 lc rgb '#d62728'
set style line 2 lc rgb '#1f77b4'
set style fill solid 0.8 border -1
set boxwidth 0.35

set terminal pngcairo noenhanced size 120 * ns + 200, 330 * nl + 60 font "DejaVu Sans,10"
set output outdir.'/mbm_bench.png'
set multiplot layout nl, 1 title "MotionBenchMaker, Panda: planning time, ours (deepcheck) against FCL meshes (bar median, point p90; lower is better)"
set logscale y
set format y "%g"
set grid ytics
set ylabel "time (s)"
set xrange [0.4:ns + 0.6]
set xtics scale 0
set xtics ()
do for [i = 1:ns] { set xtics add (word(scenes, i) i) }
set key top left font ",9"
do for [j = 1:nl] {
  l = word(planners, j)
  set title "planner ".l
  plot for [i = 1:ns] csv using (i - 0.18):(pick(word(scenes, i), 'deepcheck', l, $6)) every ::1 \
         with boxes ls 1 title (i == 1 ? 'deepcheck median' : ''), \
       for [i = 1:ns] csv using (i + 0.18):(pick(word(scenes, i), 'fcl', l, $6)) every ::1 \
         with boxes ls 2 title (i == 1 ? 'fcl median' : ''), \
       for [i = 1:ns] csv using (i - 0.18):(pick(word(scenes, i), 'deepcheck', l, $7)) every ::1 \
         with points pt 7 lc rgb '#7f0000' title (i == 1 ? 'deepcheck p90' : ''), \
       for [i = 1:ns] csv using (i + 0.18):(pick(word(scenes, i), 'fcl', l, $7)) every ::1 \
         with points pt 7 lc rgb '#0b3d66' title (i == 1 ? 'fcl p90' : '')
}
unset multiplot
