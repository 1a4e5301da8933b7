# Made by sap_bench; render with: gnuplot pareto_lattice.gp
set terminal pngcairo size 560,420 noenhanced font "sans,10"
set output "pareto_lattice.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
0.774119375 0 0
EOD
$P0S1 << EOD
1.39097863 0 0
EOD
$P0S2 << EOD
0.739854938 2.21252525 0
EOD
$P0S3 << EOD
2.11143737 2.21252525 0
EOD
$P0S4 << EOD
1.54747381 2.21252525 0
EOD
$P0S5 << EOD
1.4294915 2.21252525 0
EOD
$P0S6 << EOD
0.465146687 0 0
EOD
$P0S7 << EOD
0.302048938 0 0
EOD
$P0S8 << EOD
0.222519562 0 0
EOD
$P0S9 << EOD
61.2387477 0 0
EOD
$P0S10 << EOD
156.057985 0 0
EOD
$P0S11 << EOD
101.766885 0 0
EOD
$P0S12 << EOD
12800.7778 0 0
EOD
$P0S13 << EOD
6177.92111 9.07029478e-05 0
EOD
set multiplot layout 1,1
set title "lattice n=125000"
set xlabel "ms per frame (mean)"
set ylabel "error: (missed + extra) / true pairs"
set logscale x 2
unset logscale y
set yrange [-0.02:2.544]
set xtics ("0.01" 0.01, "0.1" 0.1, "1" 1, "10" 10, "100" 100, "1000" 1000, "1e+04" 10000) rotate by -30
unset label
plot $P0S0 using 1:2 with points pt 7 ps 1.5 title "exact", \
     $P0S1 using 1:2 with points pt 7 ps 1.5 title "exact_sequential", \
     $P0S2 using 1:2 with points pt 7 ps 1.5 title "keys_only", \
     $P0S3 using 1:2 with points pt 7 ps 1.5 title "keys_16bit", \
     $P0S4 using 1:2 with points pt 7 ps 1.5 title "fat_margin_0.05", \
     $P0S5 using 1:2 with points pt 7 ps 1.5 title "fat_margin_0.2", \
     $P0S6 using 1:2 with points pt 7 ps 1.5 title "subsample_every_2", \
     $P0S7 using 1:2 with points pt 7 ps 1.5 title "subsample_every_4", \
     $P0S8 using 1:2 with points pt 5 ps 1.5 title "subsample_every_8", \
     $P0S9 using 1:2 with points pt 5 ps 1.5 title "bullet_dbvt_raw_cache", \
     $P0S10 using 1:2 with points pt 5 ps 1.5 title "fcl_dynamic_aabb_raw", \
     $P0S11 using 1:2 with points pt 5 ps 1.5 title "fcl_dynamic_aabb_array_raw", \
     $P0S12 using 1:2 with points pt 5 ps 1.5 title "fcl_sap_raw", \
     $P0S13 using 1:2 with points pt 5 ps 1.5 title "fcl_interval_tree_raw"
unset multiplot
