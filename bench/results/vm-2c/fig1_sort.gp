# Made by sap_bench; render with: gnuplot fig1_sort.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "fig1_sort.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
32768 0.979726 0
65536 1.738783 0
131072 3.295605 0
262144 6.515176 0
524288 14.617611 0
1048576 35.61524 0
2097152 72.507417 0
EOD
$P0S1 << EOD
32768 0.763414 0
65536 1.011681 0
131072 2.645569 0
262144 4.991464 0
524288 10.107113 0
1048576 23.34149 0
2097152 47.474956 0
EOD
$P1S0 << EOD
32768 1.28334822 0
65536 1.71870679 0
131072 1.24570745 0
262144 1.30526355 0
524288 1.44626967 0
1048576 1.52583404 0
2097152 1.52727718 0
EOD
set multiplot layout 1,2
set title "Sorting time, d = 0.35"
set xlabel "n (boxes)"
set ylabel "ms per frame"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "sequential", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "parallel"
set title "Sorting speedup"
set xlabel "n (boxes)"
set ylabel "sequential / parallel"
set logscale x 2
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P1S0 using 1:2 with linespoints lw 2 pt 7 title "speedup"
unset multiplot
