# Made by sap_bench; render with: gnuplot fig2_candidates.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "fig2_candidates.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
32768 0.688833 0
65536 1.450555 0
131072 2.981369 0
262144 6.034022 0
524288 12.683529 0
1048576 36.948109 0
EOD
$P0S1 << EOD
32768 0.667472 0
65536 1.33971 0
131072 2.691217 0
262144 5.228445 0
524288 10.72491 0
1048576 25.653243 0
EOD
$P0S2 << EOD
32768 0.690516 0
65536 1.43444 0
131072 2.992415 0
262144 6.242472 0
524288 13.012467 0
1048576 45.244742 0
EOD
$P0S3 << EOD
32768 0.661342 0
65536 1.328663 0
131072 2.713129 0
262144 5.626517 0
524288 10.821603 0
1048576 28.95643 0
EOD
$P0S4 << EOD
32768 0.686179 0
65536 1.451266 0
131072 2.960587 0
262144 6.098048 0
524288 13.260796 0
1048576 35.827375 0
EOD
$P0S5 << EOD
32768 0.662203 0
65536 1.370626 0
131072 2.669294 0
262144 5.353251 0
524288 11.024475 0
1048576 28.098965 0
EOD
$P0S6 << EOD
32768 0.685708 0
65536 1.44098 0
131072 2.995599 0
262144 6.081914 0
524288 13.049903 0
1048576 41.069561 0
EOD
$P0S7 << EOD
32768 0.654852 0
65536 1.327772 0
131072 2.706019 0
262144 5.363466 0
524288 11.005377 0
1048576 27.716698 0
EOD
$P1S0 << EOD
32768 1.03200284 0
65536 1.08273806 0
131072 1.10781442 0
262144 1.15407583 0
524288 1.18262335 0
1048576 1.44028999 0
EOD
$P1S1 << EOD
32768 1.04411333 0
65536 1.07961161 0
131072 1.10293871 0
262144 1.10947359 0
524288 1.20245282 0
1048576 1.56251106 0
EOD
$P1S2 << EOD
32768 1.03620642 0
65536 1.05883443 0
131072 1.10912736 0
262144 1.13912985 0
524288 1.20285057 0
1048576 1.27504251 0
EOD
$P1S3 << EOD
32768 1.04711904 0
65536 1.08526163 0
131072 1.10701329 0
262144 1.13395219 0
524288 1.18577519 0
1048576 1.4817624 0
EOD
set multiplot layout 1,2
set title "Candidates time"
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
set title "Candidates speedup"
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
