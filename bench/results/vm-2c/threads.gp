# Made by sap_bench; render with: gnuplot threads.gp
set terminal pngcairo size 560,420 noenhanced font "sans,10"
set output "threads.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
131072 1.91585081 0
524288 1.96413539 0
1048576 1.97128127 0
EOD
$P0S1 << EOD
131072 1.04056463 0
524288 2.12705186 0
1048576 1.43992377 0
EOD
$P0S2 << EOD
131072 1.00031215 0
524288 2.00634869 0
1048576 2.24409486 0
EOD
$P0S3 << EOD
131072 1.68894066 0
524288 1.94271246 0
1048576 2.04208326 0
EOD
$P0S4 << EOD
131072 1.00719338 0
524288 1.01735271 0
1048576 1.01928698 0
EOD
$P0S5 << EOD
131072 1.45784316 0
524288 1.94382642 0
1048576 2.01838669 0
EOD
$P0S6 << EOD
131072 1.92329886 0
524288 1.94625776 0
1048576 1.97418061 0
EOD
$P0S7 << EOD
131072 1.26454265 0
524288 1.33740724 0
1048576 2.02825393 0
EOD
$P0S8 << EOD
131072 1.83239729 0
524288 1.90739518 0
1048576 2.56864172 0
EOD
$P0S9 << EOD
131072 1.95306796 0
524288 1.98017755 0
1048576 1.96345717 0
EOD
$P0S10 << EOD
131072 1.00759338 0
524288 0.999685216 0
1048576 1.02357361 0
EOD
$P0S11 << EOD
131072 1.79643953 0
524288 1.89046573 0
1048576 1.95838847 0
EOD
set multiplot layout 1,1
set title "Speedup, 2 threads over 1"
set xlabel "n (boxes)"
set ylabel "speedup"
set logscale x 2
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "keys d=0.05", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "sort d=0.05", \
     $P0S2 using 1:2 with linespoints lw 2 pt 7 title "candidates d=0.05", \
     $P0S3 using 1:2 with linespoints lw 2 pt 7 title "pairing d=0.05", \
     $P0S4 using 1:2 with linespoints lw 2 pt 7 title "output d=0.05", \
     $P0S5 using 1:2 with linespoints lw 2 pt 7 title "total d=0.05", \
     $P0S6 using 1:2 with linespoints lw 2 pt 7 title "keys d=0.35", \
     $P0S7 using 1:2 with linespoints lw 2 pt 7 title "sort d=0.35", \
     $P0S8 using 1:2 with linespoints lw 2 pt 7 title "candidates d=0.35", \
     $P0S9 using 1:2 with linespoints lw 2 pt 7 title "pairing d=0.35", \
     $P0S10 using 1:2 with linespoints lw 2 pt 7 title "output d=0.35", \
     $P0S11 using 1:2 with linespoints lw 2 pt 7 title "total d=0.35"
unset multiplot
