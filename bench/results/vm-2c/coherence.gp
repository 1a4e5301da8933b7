# Made by sap_bench; render with: gnuplot coherence.gp
set terminal pngcairo size 1120,840 noenhanced font "sans,10"
set output "coherence.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0.001 3.51396429 0
0.01 3.276211 0
0.05 7.950512 0
0.2 21.0570875 0
0.5 38.6349864 0
EOD
$P0S1 << EOD
0.001 36.1765776 0
0.01 31.7809365 0
0.05 33.7760632 0
0.2 30.3447677 0
0.5 33.6033239 0
EOD
$P0S2 << EOD
0.001 5.22242512 0
0.01 5.48300453 0
0.05 20.3081391 0
0.2 32.6793774 0
0.5 43.8565885 0
EOD
$P0S3 << EOD
0.001 43.6570124 0
0.01 50.3710345 0
0.05 48.1190254 0
0.2 66.4134018 0
0.5 227.540053 0
EOD
$P1S0 << EOD
0.001 3.80373688 0
0.01 14.4853998 0
0.05 33.7436763 0
0.2 34.51464 0
0.5 41.3534089 0
EOD
$P1S1 << EOD
0.001 41.1773924 0
0.01 75.6483294 0
0.05 44.2420949 0
0.2 62.5367797 0
0.5 43.4505979 0
EOD
$P1S2 << EOD
0.001 6.57491224 0
0.01 9.81517988 0
0.05 21.2662228 0
0.2 48.384382 0
0.5 77.6687875 0
EOD
$P1S3 << EOD
0.001 76.1335684 0
0.01 85.3258875 0
0.05 95.2535722 0
0.2 207.481479 0
0.5 1041.24779 0
EOD
$P2S0 << EOD
0.001 23.6475962 0
0.01 26.7881872 0
0.05 64.3318318 0
0.2 186.231101 0
0.5 327.221011 0
EOD
$P2S1 << EOD
0.001 267.962365 0
0.01 283.792672 0
0.05 269.339766 0
0.2 274.350763 0
0.5 273.998084 0
EOD
$P2S2 << EOD
0.001 42.2555915 0
0.01 48.5506024 0
0.05 95.5855934 0
0.2 195.8726 0
0.5 377.748643 0
EOD
$P2S3 << EOD
0.001 450.898137 0
0.01 451.326503 0
0.05 421.117584 0
0.2 615.45472 0
0.5 1876.87608 0
EOD
$P3S0 << EOD
0.001 31.2270314 0
0.01 135.839495 0
0.05 288.060392 0
0.2 394.464381 0
0.5 383.290033 0
EOD
$P3S1 << EOD
0.001 472.138819 0
0.01 385.356502 0
0.05 382.777698 0
0.2 388.704353 0
0.5 371.740051 0
EOD
$P3S2 << EOD
0.001 55.0450107 0
0.01 99.3502212 0
0.05 235.887598 0
0.2 568.166374 0
0.5 805.372373 0
EOD
$P3S3 << EOD
0.001 745.808448 0
0.01 780.483837 0
0.05 877.909758 0
0.2 1904.81382 0
0.5 10210.6326 0
EOD
set multiplot layout 2,2
set title "uniform d=0.05 n=2^17"
set xlabel "motion (mean box edges a frame)"
set ylabel "ms per frame (mean after warm-up)"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics ("0.001" 0.001, "0.01" 0.01, "0.05" 0.05, "0.2" 0.2, "0.5" 0.5) rotate by -30
unset label
plot $P0S0 using 1:2 with linespoints lw 2 pt 7 title "default (automatic skin)", \
     $P0S1 using 1:2 with linespoints lw 2 pt 7 title "no skin", \
     $P0S2 using 1:2 with linespoints lw 2 pt 7 title "best fixed skin", \
     $P0S3 using 1:2 with linespoints lw 2 pt 7 title "FCL dynamic AABB tree"
set title "uniform d=0.35 n=2^17"
set xlabel "motion (mean box edges a frame)"
set ylabel "ms per frame (mean after warm-up)"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics ("0.001" 0.001, "0.01" 0.01, "0.05" 0.05, "0.2" 0.2, "0.5" 0.5) rotate by -30
unset label
plot $P1S0 using 1:2 with linespoints lw 2 pt 7 title "default (automatic skin)", \
     $P1S1 using 1:2 with linespoints lw 2 pt 7 title "no skin", \
     $P1S2 using 1:2 with linespoints lw 2 pt 7 title "best fixed skin", \
     $P1S3 using 1:2 with linespoints lw 2 pt 7 title "FCL dynamic AABB tree"
set title "uniform d=0.05 n=2^20"
set xlabel "motion (mean box edges a frame)"
set ylabel "ms per frame (mean after warm-up)"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics ("0.001" 0.001, "0.01" 0.01, "0.05" 0.05, "0.2" 0.2, "0.5" 0.5) rotate by -30
unset label
plot $P2S0 using 1:2 with linespoints lw 2 pt 7 title "default (automatic skin)", \
     $P2S1 using 1:2 with linespoints lw 2 pt 7 title "no skin", \
     $P2S2 using 1:2 with linespoints lw 2 pt 7 title "best fixed skin", \
     $P2S3 using 1:2 with linespoints lw 2 pt 7 title "FCL dynamic AABB tree"
set title "uniform d=0.35 n=2^20"
set xlabel "motion (mean box edges a frame)"
set ylabel "ms per frame (mean after warm-up)"
set logscale x 2
set logscale y
set yrange [*:*]
set xtics ("0.001" 0.001, "0.01" 0.01, "0.05" 0.05, "0.2" 0.2, "0.5" 0.5) rotate by -30
unset label
plot $P3S0 using 1:2 with linespoints lw 2 pt 7 title "default (automatic skin)", \
     $P3S1 using 1:2 with linespoints lw 2 pt 7 title "no skin", \
     $P3S2 using 1:2 with linespoints lw 2 pt 7 title "best fixed skin", \
     $P3S3 using 1:2 with linespoints lw 2 pt 7 title "FCL dynamic AABB tree"
unset multiplot
