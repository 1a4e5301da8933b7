# Made by sap_bench; render with: gnuplot coherence.gp
set terminal pngcairo size 1120,840 noenhanced font "sans,10"
set output "coherence.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0.001 3.10900147 0
0.01 3.36370988 0
0.05 8.56060729 0
0.2 20.6179534 0
0.5 25.7024201 0
EOD
$P0S1 << EOD
0.001 27.5843253 0
0.01 26.3727785 0
0.05 26.0135118 0
0.2 26.333569 0
0.5 26.6172748 0
EOD
$P0S2 << EOD
0.001 4.78931929 0
0.01 5.30571182 0
0.05 9.86773741 0
0.2 19.9585015 0
0.5 36.0757028 0
EOD
$P0S3 << EOD
0.001 44.0389784 0
0.01 46.2743218 0
0.05 44.7246892 0
0.2 65.2489985 0
0.5 207.682275 0
EOD
$P1S0 << EOD
0.001 3.54771506 0
0.01 11.035717 0
0.05 19.4963052 0
0.2 34.2121747 0
0.5 33.7473999 0
EOD
$P1S1 << EOD
0.001 34.9230806 0
0.01 34.3555221 0
0.05 35.7072999 0
0.2 33.8439547 0
0.5 34.7377786 0
EOD
$P1S2 << EOD
0.001 5.91745141 0
0.01 8.806894 0
0.05 18.1437572 0
0.2 43.1297803 0
0.5 62.8047879 0
EOD
$P1S3 << EOD
0.001 81.5791228 0
0.01 80.9389315 0
0.05 91.9566088 0
0.2 204.395194 0
0.5 1040.73597 0
EOD
$P2S0 << EOD
0.001 23.1897598 0
0.01 27.8218425 0
0.05 93.0823033 0
0.2 193.765068 0
0.5 204.154738 0
EOD
$P2S1 << EOD
0.001 218.505845 0
0.01 308.663997 0
0.05 279.93257 0
0.2 249.752066 0
0.5 214.548258 0
EOD
$P2S2 << EOD
0.001 60.9457619 0
0.01 55.6282933 0
0.05 107.816739 0
0.2 235.711872 0
0.5 303.936774 0
EOD
$P2S3 << EOD
0.001 521.640997 0
0.01 625.07914 0
0.05 516.124925 0
0.2 704.747487 0
0.5 1993.0421 0
EOD
$P3S0 << EOD
0.001 27.6899537 0
0.01 79.0403318 0
0.05 192.585474 0
0.2 326.139239 0
0.5 317.217451 0
EOD
$P3S1 << EOD
0.001 342.0009 0
0.01 335.832561 0
0.05 316.409721 0
0.2 331.250247 0
0.5 328.601412 0
EOD
$P3S2 << EOD
0.001 54.3722689 0
0.01 81.3795053 0
0.05 204.269633 0
0.2 430.185241 0
0.5 656.434897 0
EOD
$P3S3 << EOD
0.001 835.96384 0
0.01 825.344105 0
0.05 862.702934 0
0.2 2242.37562 0
0.5 9566.86039 0
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
