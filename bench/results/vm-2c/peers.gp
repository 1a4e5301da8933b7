# Made by sap_bench; render with: gnuplot peers.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "peers.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0 38.417222 0
1 43.75469 0
2 427.014859 0
3 531.34378 0
4 95.407389 0
5 117.537519 0
EOD
$P0S1 << EOD
0 41.974645 0
1 55.167581 0
2 679.879601 0
3 959.829793 0
4 215.864445 0
5 127.585224 0
EOD
$P0S2 << EOD
0 206.287711 0
1 277.907137 0
2 2344.54138 0
3 3196.87637 0
4 1134.33486 0
5 41.575732 0
EOD
$P0S3 << EOD
0 345.073771 0
1 501.785406 0
2 6269.7441 0
3 10144.1207 0
4 2769.74947 0
5 12488.6384 0
EOD
$P0S4 << EOD
0 138.391223 0
1 160.691927 0
2 1652.4249 0
3 1872.24737 0
4 686.566653 0
5 457.628959 0
EOD
$P1S0 << EOD
0 18.864449 0
1 26.680148 0
2 183.46061 0
3 265.899903 0
4 196.092869 0
5 55.529549 0
EOD
$P1S1 << EOD
0 35.167184 0
1 51.082013 0
2 610.190721 0
3 919.926138 0
4 210.302214 0
5 126.591448 0
EOD
$P1S2 << EOD
0 206.336974 0
1 279.731377 0
2 2351.46071 0
3 3209.37214 0
4 1138.13542 0
5 41.819334 0
EOD
$P1S3 << EOD
0 491.635059 0
1 973.000585 0
2 11666.5555 0
3 18130.3305 0
4 4713.3227 0
5 1552.35627 0
EOD
$P1S4 << EOD
0 42.371885 0
1 76.18581 0
2 407.279776 0
3 714.199928 0
4 227.780014 0
5 105.195888 0
EOD
set multiplot layout 1,2
set title "One-shot"
set xlabel ""
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("uniform d=0.05 n=2^17" 0, "uniform d=0.35 n=2^17" 1, "uniform d=0.05 n=2^20" 2, "uniform d=0.35 n=2^20" 3, "ball n=2^19 f75" 4, "plane u=y 750^2 f225" 5) rotate by -30
unset label
plot $P0S0 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase", \
     $P0S1 using 1:2 with points pt 7 ps 1.5 title "grid_t2", \
     $P0S2 using 1:2 with points pt 7 ps 1.5 title "cgal", \
     $P0S3 using 1:2 with points pt 7 ps 1.5 title "bullet_dbvt", \
     $P0S4 using 1:2 with points pt 7 ps 1.5 title "fcl_dynamic_aabb"
set title "Steady state"
set xlabel ""
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("uniform d=0.05 n=2^17" 0, "uniform d=0.35 n=2^17" 1, "uniform d=0.05 n=2^20" 2, "uniform d=0.35 n=2^20" 3, "ball n=2^19 f75" 4, "plane u=y 750^2 f225" 5) rotate by -30
unset label
plot $P1S0 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase", \
     $P1S1 using 1:2 with points pt 7 ps 1.5 title "grid_t2", \
     $P1S2 using 1:2 with points pt 7 ps 1.5 title "cgal", \
     $P1S3 using 1:2 with points pt 7 ps 1.5 title "bullet_dbvt", \
     $P1S4 using 1:2 with points pt 7 ps 1.5 title "fcl_dynamic_aabb"
unset multiplot
