# Made by sap_bench; render with: gnuplot busy.gp
set terminal pngcairo size 1120,840 noenhanced font "sans,10"
set output "busy.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0 0.483587 0
1 0.459772 0
2 0.460814 0
EOD
$P0S1 << EOD
0 0.467653 0
1 0.468319 0
2 0.469596 0
EOD
$P0S2 << EOD
0 0.493472 0
1 0.462415 0
2 0.464048 0
EOD
$P0S3 << EOD
0 11.8279 0
1 20.0436 0
2 31.8551 0
EOD
$P1S0 << EOD
0 5.81982 0
1 13.2825 0
2 14.4061 0
EOD
$P1S1 << EOD
0 2.46335 0
1 12.8319 0
2 12.7037 0
EOD
$P1S2 << EOD
0 4.06055 0
1 2.00016 0
2 11.7792 0
EOD
$P1S3 << EOD
0 14.8015 0
1 27.3262 0
2 31.8405 0
EOD
$P2S0 << EOD
0 3.34936 0
1 4.57029 0
2 16.5873 0
EOD
$P2S1 << EOD
0 4.52549 0
1 8.43802 0
2 16.5403 0
EOD
$P2S2 << EOD
0 1.86227 0
1 1.69556 0
2 4.21508 0
EOD
$P2S3 << EOD
0 16.1502 0
1 32.172 0
2 39.941 0
EOD
$P3S0 << EOD
0 10.9766 0
1 14.5294 0
2 26.1431 0
EOD
$P3S1 << EOD
0 10.0181 0
1 14.6835 0
2 26.1985 0
EOD
$P3S2 << EOD
0 7.79909 0
1 2.05899 0
2 24.0827 0
EOD
$P3S3 << EOD
0 19.4326 0
1 49.7938 0
2 47.2774 0
EOD
set multiplot layout 2,2
set title "Median frame, n=2^12"
set xlabel "busy loops"
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("0" 0, "1" 1, "2" 2) rotate by -30
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 passive", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 unset", \
     $P0S2 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 passive", \
     $P0S3 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 unset"
set title "Median frame, n=2^14"
set xlabel "busy loops"
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("0" 0, "1" 1, "2" 2) rotate by -30
unset label
plot $P1S0 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 passive", \
     $P1S1 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 unset", \
     $P1S2 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 passive", \
     $P1S3 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 unset"
set title "90th percentile frame, n=2^12"
set xlabel "busy loops"
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("0" 0, "1" 1, "2" 2) rotate by -30
unset label
plot $P2S0 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 passive", \
     $P2S1 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 unset", \
     $P2S2 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 passive", \
     $P2S3 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 unset"
set title "90th percentile frame, n=2^14"
set xlabel "busy loops"
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("0" 0, "1" 1, "2" 2) rotate by -30
unset label
plot $P3S0 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 passive", \
     $P3S1 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t1 unset", \
     $P3S2 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 passive", \
     $P3S3 using 1:2 with linespoints lw 2 pt 7 title "sap_broadphase_t2 unset"
unset multiplot
