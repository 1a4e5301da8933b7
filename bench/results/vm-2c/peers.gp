# Made by sap_bench; render with: gnuplot peers.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "peers.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0 321.814594 0
1 713.108885 0
2 11537.8406 0
4 4734.6234 0
5 20242.5686 0
6 961.704058 0
EOD
$P0S1 << EOD
0 60.457904 0
1 99.765011 0
2 946.669566 0
3 1753.5624 0
4 370.942473 0
5 65.050862 0
6 79.055704 0
EOD
$P0S2 << EOD
0 188.775042 0
1 224.643307 0
2 2767.12419 0
3 3211.07339 0
4 525.293108 0
5 152.818058 0
6 110.271909 0
EOD
$P0S3 << EOD
0 133.352618 0
1 184.793006 0
2 2068.73387 0
3 2499.95972 0
4 999.354502 0
5 507.509526 0
6 136.790016 0
EOD
$P0S4 << EOD
0 42.747973 0
1 59.014438 0
2 1474.54136 0
3 1479.13357 0
4 340.46812 0
5 155.935138 0
6 37.981836 0
EOD
$P0S5 << EOD
0 40.366844 0
1 43.724461 0
2 365.725881 0
3 423.039242 0
4 140.646132 0
5 82.26068 0
6 32.718955 0
EOD
$P0S6 << EOD
0 27.31302 0
1 38.377709 0
2 506.176591 0
3 500.749807 0
4 195.474537 0
5 112.037498 0
6 30.036732 0
EOD
$P0S7 << EOD
0 34.185303 0
1 43.441903 0
2 528.470964 0
3 520.704338 0
4 157.656863 0
5 91.577135 0
6 33.891164 0
EOD
$P1S0 << EOD
0 609.128154 0
1 1597.26885 0
2 10647.4472 0
4 10544.8304 0
5 19380.3408 0
6 75.047919 0
EOD
$P1S1 << EOD
0 60.457904 0
1 99.765011 0
2 946.669566 0
3 1753.5624 0
4 370.942473 0
5 65.050862 0
6 79.055704 0
EOD
$P1S2 << EOD
0 188.775042 0
1 224.643307 0
2 2767.12419 0
3 3211.07339 0
4 525.293108 0
5 152.818058 0
6 110.271909 0
EOD
$P1S3 << EOD
0 55.008417 0
1 117.949044 0
2 636.881521 0
3 1022.93067 0
4 451.373014 0
5 223.01515 0
6 23.030082 0
EOD
$P1S4 << EOD
0 42.747973 0
1 59.014438 0
2 1474.54136 0
3 1479.13357 0
4 340.46812 0
5 155.935138 0
6 37.981836 0
EOD
$P1S5 << EOD
0 20.040986 0
1 31.726084 0
2 125.044972 0
3 112.402132 0
4 178.993114 0
5 151.95751 0
6 18.82397 0
EOD
$P1S6 << EOD
0 32.873037 0
1 46.52075 0
2 510.604344 0
3 536.984339 0
4 159.796523 0
5 127.865309 0
6 32.595849 0
EOD
$P1S7 << EOD
0 25.732633 0
1 39.554888 0
2 238.8375 0
3 369.96817 0
4 108.167886 0
5 73.489215 0
6 31.504204 0
EOD
set multiplot layout 1,2
set title "One-shot (best knob of each library)"
set xlabel ""
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("uniform d=0.05 n=2^17" 0, "uniform d=0.35 n=2^17" 1, "uniform d=0.05 n=2^20" 2, "uniform d=0.35 n=2^20" 3, "ball n=2^19 f75" 4, "plane u=y 750^2 f225" 5, "lattice n=125000" 6) rotate by -30
unset label
plot $P0S0 using 1:2 with points pt 7 ps 1.5 title "bullet", \
     $P0S1 using 1:2 with points pt 7 ps 1.5 title "cgal", \
     $P0S2 using 1:2 with points pt 7 ps 1.5 title "cgal_tbb", \
     $P0S3 using 1:2 with points pt 7 ps 1.5 title "fcl", \
     $P0S4 using 1:2 with points pt 7 ps 1.5 title "grid", \
     $P0S5 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase", \
     $P0S6 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase_no_skin_t1", \
     $P0S7 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase_no_skin_t2"
set title "Steady state (best knob of each library)"
set xlabel ""
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("uniform d=0.05 n=2^17" 0, "uniform d=0.35 n=2^17" 1, "uniform d=0.05 n=2^20" 2, "uniform d=0.35 n=2^20" 3, "ball n=2^19 f75" 4, "plane u=y 750^2 f225" 5, "lattice n=125000" 6) rotate by -30
unset label
plot $P1S0 using 1:2 with points pt 7 ps 1.5 title "bullet", \
     $P1S1 using 1:2 with points pt 7 ps 1.5 title "cgal", \
     $P1S2 using 1:2 with points pt 7 ps 1.5 title "cgal_tbb", \
     $P1S3 using 1:2 with points pt 7 ps 1.5 title "fcl", \
     $P1S4 using 1:2 with points pt 7 ps 1.5 title "grid", \
     $P1S5 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase", \
     $P1S6 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase_no_skin_t1", \
     $P1S7 using 1:2 with points pt 7 ps 1.5 title "sap_broadphase_no_skin_t2"
unset multiplot
