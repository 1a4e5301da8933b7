# Made by sap_bench; render with: gnuplot fig3_pairing.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "fig3_pairing.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
32768 4.116434 0
65536 9.160136 0
131072 19.567634 0
262144 44.513926 0
524288 118.411117 0
1048576 293.178711 0
EOD
$P0S1 << EOD
32768 2.484981 0
65536 5.259702 0
131072 10.968301 0
262144 23.102785 0
524288 51.36291 0
1048576 112.923135 0
EOD
$P0S2 << EOD
32768 5.023852 0
65536 10.858178 0
131072 25.256914 0
262144 65.826723 0
524288 169.672846 0
1048576 405.872816 0
EOD
$P0S3 << EOD
32768 2.965845 0
65536 6.141813 0
131072 13.953906 0
262144 30.581873 0
524288 62.938863 0
1048576 145.570598 0
EOD
$P0S4 << EOD
32768 5.870149 0
65536 13.129071 0
131072 30.739698 0
262144 71.965782 0
524288 195.742178 0
1048576 458.66621 0
EOD
$P0S5 << EOD
32768 3.324548 0
65536 7.205151 0
131072 15.425932 0
262144 34.405923 0
524288 73.341775 0
1048576 164.826208 0
EOD
$P0S6 << EOD
32768 6.329631 0
65536 13.455495 0
131072 29.889325 0
262144 69.284909 0
524288 220.713718 0
1048576 517.427329 0
EOD
$P0S7 << EOD
32768 3.626937 0
65536 7.679597 0
131072 15.990561 0
262144 35.701488 0
524288 83.172867 0
1048576 182.461542 0
EOD
$P1S0 << EOD
32768 1.65652534 0
65536 1.74156939 0
131072 1.78401687 0
262144 1.92677749 0
524288 2.30538178 0
1048576 2.5962679 0
EOD
$P1S1 << EOD
32768 1.69390241 0
65536 1.76791088 0
131072 1.81002466 0
262144 2.15247519 0
524288 2.69583589 0
1048576 2.78815105 0
EOD
$P1S2 << EOD
32768 1.76569837 0
65536 1.82217847 0
131072 1.99272874 0
262144 2.0916684 0
524288 2.66890429 0
1048576 2.78272622 0
EOD
$P1S3 << EOD
32768 1.74517258 0
65536 1.75210952 0
131072 1.86918552 0
262144 1.94067286 0
524288 2.65367452 0
1048576 2.83581583 0
EOD
set multiplot layout 1,2
set title "Pairing time"
set xlabel "n (boxes)"
set ylabel "ms per frame"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "seq d=0.05", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "par d=0.05", \
     $P0S2 using 1:2 with linespoints lw 2 pt 7 title "seq d=0.15", \
     $P0S3 using 1:2 with linespoints lw 2 pt 7 title "par d=0.15", \
     $P0S4 using 1:2 with linespoints lw 2 pt 7 title "seq d=0.25", \
     $P0S5 using 1:2 with linespoints lw 2 pt 7 title "par d=0.25", \
     $P0S6 using 1:2 with linespoints lw 2 pt 7 title "seq d=0.35", \
     $P0S7 using 1:2 with linespoints lw 2 pt 7 title "par d=0.35"
set title "Pairing speedup"
set xlabel "n (boxes)"
set ylabel "sequential / parallel"
set logscale x 2
unset logscale y
set yrange [*:*]
set xtics autofreq
unset label
plot $P1S0 using 1:2 with linespoints lw 2 pt 7 title "d=0.05", \
     $P1S1 using 1:2 with linespoints lw 2 pt 7 title "d=0.15", \
     $P1S2 using 1:2 with linespoints lw 2 pt 7 title "d=0.25", \
     $P1S3 using 1:2 with linespoints lw 2 pt 7 title "d=0.35"
unset multiplot
