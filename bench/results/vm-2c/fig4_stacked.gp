# Made by sap_bench; render with: gnuplot fig4_stacked.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "fig4_stacked.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0.05 19.641314 0
0.1 18.894474 0
0.15 20.411068 0
0.2 19.481967 0
0.25 19.335128 0
0.3 24.418869 0
0.35 21.204474 0
EOD
$P0S1 << EOD
0.05 30.679439 19.641314
0.1 30.049342 18.894474
0.15 32.106509 20.411068
0.2 30.391892 19.481967
0.25 30.292653 19.335128
0.3 43.899403 24.418869
0.35 35.593837 21.204474
EOD
$P0S2 << EOD
0.05 85.277745 30.679439
0.1 88.713096 30.049342
0.15 99.115939 32.106509
0.2 98.774821 30.391892
0.25 102.466343 30.292653
0.3 139.630293 43.899403
0.35 123.913513 35.593837
EOD
$P0S3 << EOD
0.05 86.491487 85.277745
0.1 90.85677 88.713096
0.15 102.453497 99.115939
0.2 103.447562 98.774821
0.25 108.599643 102.466343
0.3 147.102291 139.630293
0.35 133.029213 123.913513
EOD
$P1S0 << EOD
0.05 42.53035 0
0.1 42.541437 0
0.15 42.61083 0
0.2 47.638116 0
0.25 47.177043 0
0.3 48.422663 0
0.35 47.941428 0
EOD
$P1S1 << EOD
0.05 71.112514 42.53035
0.1 70.256542 42.541437
0.15 78.365998 42.61083
0.2 95.796937 47.638116
0.25 89.003177 47.177043
0.3 108.761876 48.422663
0.35 99.950217 47.941428
EOD
$P1S2 << EOD
0.05 186.785584 71.112514
0.1 198.559111 70.256542
0.15 225.088476 78.365998
0.2 255.136796 95.796937
0.25 269.608091 89.003177
0.3 326.010277 108.761876
0.35 325.86845 99.950217
EOD
$P1S3 << EOD
0.05 189.127412 186.785584
0.1 203.128288 198.559111
0.15 232.312726 225.088476
0.2 265.630142 255.136796
0.25 284.74187 269.608091
0.3 346.497006 326.010277
0.35 350.630168 325.86845
EOD
set multiplot layout 1,2
set title "Parallel phases, n = 2^19"
set xlabel "density d"
set ylabel "ms per frame"
unset logscale x
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
set label "2.1x" at first 0.05, graph 0.92 center
set label "2.1x" at first 0.1, graph 0.92 center
set label "2.1x" at first 0.15, graph 0.92 center
set label "2.1x" at first 0.2, graph 0.92 center
set label "2.2x" at first 0.25, graph 0.92 center
set label "1.6x" at first 0.3, graph 0.92 center
set label "2x" at first 0.35, graph 0.92 center
plot $P0S0 using 1:3:2 with filledcurves title "keys + sort", \
     $P0S1 using 1:3:2 with filledcurves title "candidates", \
     $P0S2 using 1:3:2 with filledcurves title "pairing", \
     $P0S3 using 1:3:2 with filledcurves title "output"
set title "Parallel phases, n = 2^20"
set xlabel "density d"
set ylabel "ms per frame"
unset logscale x
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
set label "2.2x" at first 0.05, graph 0.92 center
set label "2.4x" at first 0.1, graph 0.92 center
set label "2.5x" at first 0.15, graph 0.92 center
set label "2.3x" at first 0.2, graph 0.92 center
set label "2.3x" at first 0.25, graph 0.92 center
set label "2.1x" at first 0.3, graph 0.92 center
set label "2.4x" at first 0.35, graph 0.92 center
plot $P1S0 using 1:3:2 with filledcurves title "keys + sort", \
     $P1S1 using 1:3:2 with filledcurves title "candidates", \
     $P1S2 using 1:3:2 with filledcurves title "pairing", \
     $P1S3 using 1:3:2 with filledcurves title "output"
unset multiplot
