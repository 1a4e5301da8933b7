# Made by sap_bench; render with: gnuplot peers.gp
set terminal pngcairo size 1120,420 noenhanced font "sans,10"
set output "peers.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0 5.625847 0
1 6.139951 0
2 32.2736515 0
3 42.185087 0
4 11.467596 0
5 25.207003 0
6 9.833327 0
EOD
$P0S1 << EOD
0 1.1050475 0
1 1.733187 0
2 5.4639845 0
3 10.0880115 0
4 3.4188595 0
5 0.992313 0
6 1.5549075 0
EOD
$P0S2 << EOD
0 6.575474 0
1 6.983856 0
2 31.2248615 0
3 31.622157 0
4 6.25278 0
5 2.939111 0
6 1.7461815 0
EOD
$P0S3 << EOD
0 2.6028515 0
1 3.102597 0
2 11.154565 0
3 17.829885 0
4 7.742399 0
5 8.2355215 0
6 5.2283915 0
EOD
$P0S4 << EOD
0 1.180045 0
1 2.2146475 0
2 7.154325 0
3 9.8164745 0
4 2.561989 0
5 4.4722335 0
6 2.2164365 0
EOD
$P0S5 << EOD
0 0.343649 0
1 0.626877 0
2 2.325619 0
3 4.7837255 0
4 1.5236295 0
5 0.788174 0
6 1.1332755 0
EOD
$P0S6 << EOD
0 0.2945505 0
1 0.5324525 0
2 1.921761 0
3 4.672273 0
4 1.3664245 0
5 0.7436395 0
6 1.0470415 0
EOD
$P0S7 << EOD
0 0.975466 0
1 0.929092 0
2 4.4628395 0
3 6.311407 0
4 1.9424905 0
5 1.4296245 0
6 1.2041205 0
EOD
$P1S0 << EOD
0 4.172157 0
1 6.037916 0
2 23.121946 0
3 51.910799 0
4 23.7486345 0
5 27.1818705 0
6 1.561355 0
EOD
$P1S1 << EOD
0 1.1050475 0
1 1.733187 0
2 5.4639845 0
3 10.0880115 0
4 3.4188595 0
5 0.992313 0
6 1.5549075 0
EOD
$P1S2 << EOD
0 6.575474 0
1 6.983856 0
2 31.2248615 0
3 31.622157 0
4 6.25278 0
5 2.939111 0
6 1.7461815 0
EOD
$P1S3 << EOD
0 0.8807405 0
1 1.7421795 0
2 3.3266885 0
3 10.17954 0
4 4.4656655 0
5 3.9527795 0
6 2.0153795 0
EOD
$P1S4 << EOD
0 1.180045 0
1 2.2146475 0
2 7.154325 0
3 9.8164745 0
4 2.561989 0
5 4.4722335 0
6 2.2164365 0
EOD
$P1S5 << EOD
0 0.7081025 0
1 1.1388265 0
2 3.513229 0
3 6.2781285 0
4 2.7368265 0
5 2.200681 0
6 0.764304 0
EOD
$P1S6 << EOD
0 0.388344 0
1 0.7177255 0
2 2.1863545 0
3 5.048469 0
4 1.677336 0
5 0.8986795 0
6 1.0618705 0
EOD
$P1S7 << EOD
0 0.382983 0
1 0.660161 0
2 2.150236 0
3 5.5536555 0
4 1.5829715 0
5 0.902938 0
6 1.012451 0
EOD
set multiplot layout 1,2
set title "One-shot (best knob of each library)"
set xlabel ""
set ylabel "ms per frame"
unset logscale x
set logscale y
set yrange [*:*]
set xtics ("uniform d=0.05 n=2^12" 0, "uniform d=0.35 n=2^12" 1, "uniform d=0.05 n=2^14" 2, "uniform d=0.35 n=2^14" 3, "ball n=2^13 f15" 4, "plane u=y 100^2 f45" 5, "lattice n=4096" 6) rotate by -30
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
set xtics ("uniform d=0.05 n=2^12" 0, "uniform d=0.35 n=2^12" 1, "uniform d=0.05 n=2^14" 2, "uniform d=0.35 n=2^14" 3, "ball n=2^13 f15" 4, "plane u=y 100^2 f45" 5, "lattice n=4096" 6) rotate by -30
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
