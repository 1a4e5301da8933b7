# Made by sap_bench; render with: gnuplot pareto.gp
set terminal pngcairo size 1680,840 noenhanced font "sans,10"
set output "pareto.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
18.711783 0 0
EOD
$P0S1 << EOD
18.123879 3.16043639e-05 0
EOD
$P0S2 << EOD
31.852641 0 0
EOD
$P0S3 << EOD
33.132132 3.16043639e-05 0
EOD
$P0S4 << EOD
30.978733 0 0
EOD
$P0S5 << EOD
0.906306 0 0
EOD
$P0S6 << EOD
2.314548 0 0
EOD
$P1S0 << EOD
24.893144 0 0
EOD
$P1S1 << EOD
25.36157 6.22292472e-06 0
EOD
$P1S2 << EOD
43.550436 0 0
EOD
$P1S3 << EOD
43.092486 6.22292472e-06 0
EOD
$P1S4 << EOD
44.795866 0 0
EOD
$P1S5 << EOD
3.8849 0 0
EOD
$P1S6 << EOD
13.501814 0 0
EOD
$P2S0 << EOD
20.402534 0 0
EOD
$P2S1 << EOD
19.485512 2.98854491e-06 0
EOD
$P2S2 << EOD
34.095743 0 0
EOD
$P2S3 << EOD
33.008368 2.98854491e-06 0
EOD
$P2S4 << EOD
33.462171 0 0
EOD
$P2S5 << EOD
36.005319 0 0
EOD
$P2S6 << EOD
56.734589 0 0
EOD
$P3S0 << EOD
12.693023 0 0
EOD
$P3S1 << EOD
11.952803 0 0
EOD
$P3S2 << EOD
20.814556 0 0
EOD
$P3S3 << EOD
20.355625 0 0
EOD
$P3S4 << EOD
23.684028 0 0
EOD
$P3S5 << EOD
23.393447 0 0
EOD
$P3S6 << EOD
25.806431 0 0
EOD
$P4S0 << EOD
27.985637 0 0
EOD
$P4S1 << EOD
38.569107 2.21252525 0
EOD
$P4S2 << EOD
24.696502 0 0
EOD
$P4S3 << EOD
27.811488 2.21252525 0
EOD
$P4S4 << EOD
7.02869 0 0
EOD
$P4S5 << EOD
6.596939 0 0
EOD
$P4S6 << EOD
11.642102 0 0
EOD
set multiplot layout 2,3
set title "uniform d=0.05 n=2^17"
set xlabel "ms per frame"
set ylabel "error (missed + extra) / true"
unset logscale x
unset logscale y
set yrange [-0.05:0.1]
set xtics autofreq
unset label
plot $P0S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P0S1 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P0S2 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P0S3 using 1:2 with points pt 7 ps 1.5 title "keys_only_sequential", \
     $P0S4 using 1:2 with points pt 7 ps 1.5 title "skin_0.1", \
     $P0S5 using 1:2 with points pt 7 ps 1.5 title "skin_0.3", \
     $P0S6 using 1:2 with points pt 7 ps 1.5 title "skin_1.0"
set title "uniform d=0.35 n=2^17"
set xlabel "ms per frame"
set ylabel "error (missed + extra) / true"
unset logscale x
unset logscale y
set yrange [-0.05:0.1]
set xtics autofreq
unset label
plot $P1S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P1S1 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P1S2 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P1S3 using 1:2 with points pt 7 ps 1.5 title "keys_only_sequential", \
     $P1S4 using 1:2 with points pt 7 ps 1.5 title "skin_0.1", \
     $P1S5 using 1:2 with points pt 7 ps 1.5 title "skin_0.3", \
     $P1S6 using 1:2 with points pt 7 ps 1.5 title "skin_1.0"
set title "ball n=2^17 f75"
set xlabel "ms per frame"
set ylabel "error (missed + extra) / true"
unset logscale x
unset logscale y
set yrange [-0.05:0.1]
set xtics autofreq
unset label
plot $P2S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P2S1 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P2S2 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P2S3 using 1:2 with points pt 7 ps 1.5 title "keys_only_sequential", \
     $P2S4 using 1:2 with points pt 7 ps 1.5 title "skin_0.1", \
     $P2S5 using 1:2 with points pt 7 ps 1.5 title "skin_0.3", \
     $P2S6 using 1:2 with points pt 7 ps 1.5 title "skin_1.0"
set title "plane u=y 362^2 f225"
set xlabel "ms per frame"
set ylabel "error (missed + extra) / true"
unset logscale x
unset logscale y
set yrange [-0.05:0.1]
set xtics autofreq
unset label
plot $P3S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P3S1 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P3S2 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P3S3 using 1:2 with points pt 7 ps 1.5 title "keys_only_sequential", \
     $P3S4 using 1:2 with points pt 7 ps 1.5 title "skin_0.1", \
     $P3S5 using 1:2 with points pt 7 ps 1.5 title "skin_0.3", \
     $P3S6 using 1:2 with points pt 7 ps 1.5 title "skin_1.0"
set title "lattice n=125000"
set xlabel "ms per frame"
set ylabel "error (missed + extra) / true"
unset logscale x
unset logscale y
set yrange [-0.05:2.544]
set xtics autofreq
unset label
plot $P4S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P4S1 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P4S2 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P4S3 using 1:2 with points pt 7 ps 1.5 title "keys_only_sequential", \
     $P4S4 using 1:2 with points pt 7 ps 1.5 title "skin_0.1", \
     $P4S5 using 1:2 with points pt 7 ps 1.5 title "skin_0.3", \
     $P4S6 using 1:2 with points pt 7 ps 1.5 title "skin_1.0"
unset multiplot
