# Made by sap_bench; render with: gnuplot threads.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "threads.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
1 1 0
2 1.39806941 0
EOD
$P0S1 << EOD
1 1 0
2 1.66489073 0
EOD
$P0S2 << EOD
1 1 0
2 1.50390942 0
EOD
$P0S3 << EOD
1 1 0
2 1.90013023 0
EOD
$P0S4 << EOD
1 1 0
2 1.73837373 0
EOD
$P0S5 << EOD
1 1 0
2 1.91013566 0
EOD
$P1S0 << EOD
1 1.04608843 0
2 1.01927909 0
EOD
$P1S1 << EOD
1 0.909487971 0
2 1.14027497 0
EOD
$P1S2 << EOD
1 1.12103189 0
2 1.0759663 0
EOD
$P1S3 << EOD
1 0.999011025 0
2 1.08173686 0
EOD
$P1S4 << EOD
1 0.860361599 0
2 0.870425637 0
EOD
$P1S5 << EOD
1 0.878791747 0
2 0.989373355 0
EOD
set multiplot layout 1,2
set title "Whole-frame speedup over 1 thread (steady)"
set xlabel "threads"
set ylabel "speedup"
unset logscale x
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.05 n=2^17", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.35 n=2^17", \
     $P0S2 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.05 n=2^20", \
     $P0S3 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.35 n=2^20", \
     $P0S4 using 1:2 with linespoints lw 2 pt 7 title "ball n=2^17", \
     $P0S5 using 1:2 with linespoints lw 2 pt 7 title "plane u=y n=131044"
set title "First frame of a fresh engine / steady frame"
set xlabel "threads"
set ylabel "ratio"
unset logscale x
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P1S0 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.05 n=2^17", \
     $P1S1 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.35 n=2^17", \
     $P1S2 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.05 n=2^20", \
     $P1S3 using 1:2 with linespoints lw 2 pt 7 title "uniform d=0.35 n=2^20", \
     $P1S4 using 1:2 with linespoints lw 2 pt 7 title "ball n=2^17", \
     $P1S5 using 1:2 with linespoints lw 2 pt 7 title "plane u=y n=131044"
unset multiplot
