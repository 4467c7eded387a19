# Plot of the planning benchmark, from plan_bench.csv (gnuplot 5; plan_bench runs it).
# Usage: gnuplot -e "csv='results/plan_bench.csv'; outdir='results'" plan_plots.gp
# Writes plan_bench.png: one column of panels per problem; top row the median planning time
# (OMPL's "time": RRT* and BIT* use the whole time limit), bottom row the median time to the
# first exact solution; bars per planner, one colour per checker, log scale. A missing bar: no
# run of that planner and checker solved the problem.

if (!exists("csv")) csv = 'results/plan_bench.csv'
if (!exists("outdir")) outdir = 'results'

set datafile separator ","
problems = system("awk -F, 'NR>1 && !s[$1]++ {printf \"%s \", $1}' ".csv)
planners = system("awk -F, 'NR>1 && !s[$3]++ {printf \"%s \", $3}' ".csv)
np = words(problems)
nl = words(planners)

pick(p, c, l, v) = (strcol(1) eq p && strcol(2) eq c && strcol(3) eq l) ? v : NaN

set style line 1 lc rgb '#d62728'
set style line 2 lc rgb '#1f77b4'
set style fill solid 0.8 border -1
set boxwidth 0.35

set terminal pngcairo noenhanced size 420 * np + 120, 760 font "DejaVu Sans,10"
set output outdir.'/plan_bench.png'
set multiplot layout 2, np title "Planning benchmark: median time, ours (deepcheck) against FCL meshes (lower is better)"
set logscale y
set format y "%g"
set grid ytics
set xrange [0.4:nl + 0.6]
set xtics rotate by -30 scale 0
set xtics ()
do for [j = 1:nl] { set xtics add (word(planners, j) j) }
set key top left font ",9"
do for [row = 1:2] {
  col = (row == 1 ? 6 : 7)
  set ylabel (row == 1 ? "median time (s)" : "median time to first solution (s)")
  do for [i = 1:np] {
    p = word(problems, i)
    set title p
    plot for [j = 1:nl] csv using (j - 0.18):(pick(p, 'deepcheck', word(planners, j), column(col))) every ::1 \
           with boxes ls 1 title (j == 1 ? 'deepcheck' : ''), \
         for [j = 1:nl] csv using (j + 0.18):(pick(p, 'fcl', word(planners, j), column(col))) every ::1 \
           with boxes ls 2 title (j == 1 ? 'fcl' : '')
  }
}
unset multiplot
