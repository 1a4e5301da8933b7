# Made by sap_bench; render with: gnuplot busy.gp
set terminal pngcairo size 1120,840 noenhanced font "sans,10"
set output "busy.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0 0.427024 0
1 0.412687 0
2 0.422136 0
EOD
$P0S1 << EOD
0 0.504388 0
1 0.524698 0
2 0.522034 0
EOD
$P0S2 << EOD
0 0.440588 0
1 0.427599 0
2 0.437609 0
EOD
$P0S3 << EOD
0 15.4469 0
1 19.9651 0
2 22.8002 0
EOD
$P1S0 << EOD
0 2.31459 0
1 2.42834 0
2 6.27267 0
EOD
$P1S1 << EOD
0 9.87473 0
1 10.2582 0
2 17.6328 0
EOD
$P1S2 << EOD
0 7.08785 0
1 6.23135 0
2 7.93651 0
EOD
$P1S3 << EOD
0 16.0315 0
1 16.3324 0
2 23.845 0
EOD
$P2S0 << EOD
0 0.472221 0
1 0.464669 0
2 0.462276 0
EOD
$P2S1 << EOD
0 0.589414 0
1 0.604747 0
2 0.625047 0
EOD
$P2S2 << EOD
0 0.483858 0
1 0.466141 0
2 0.476066 0
EOD
$P2S3 << EOD
0 19.7284 0
1 34.9233 0
2 24.0867 0
EOD
$P3S0 << EOD
0 14.2347 0
1 14.1877 0
2 14.4374 0
EOD
$P3S1 << EOD
0 22.2149 0
1 18.5053 0
2 26.4576 0
EOD
$P3S2 << EOD
0 11.5758 0
1 11.7134 0
2 15.9279 0
EOD
$P3S3 << EOD
0 27.8158 0
1 23.4836 0
2 39.452 0
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
