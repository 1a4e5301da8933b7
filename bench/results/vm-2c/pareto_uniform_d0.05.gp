# Made by sap_bench; render with: gnuplot pareto_uniform_d0.05.gp
set terminal pngcairo size 560,420 noenhanced font "sans,10"
set output "pareto_uniform_d0.05.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
20.4884774 0 0
EOD
$P0S1 << EOD
36.5472287 0 0
EOD
$P0S2 << EOD
26.9660086 2.23661609e-06 0
EOD
$P0S3 << EOD
28.5817746 0.00923498783 0
EOD
$P0S4 << EOD
25.5412904 0.329583274 0
EOD
$P0S5 << EOD
21.8024211 1.74482671 0
EOD
$P0S6 << EOD
16.843015 0.0475817707 0
EOD
$P0S7 << EOD
9.143227 0.140164257 0
EOD
$P0S8 << EOD
6.11751475 0.31205715 0
EOD
$P0S9 << EOD
469.944595 0.317038094 0
EOD
$P0S10 << EOD
64.0526439 0 0
EOD
$P0S11 << EOD
64.4602304 0 0
EOD
$P0S12 << EOD
7403.74301 0 0
EOD
$P0S13 << EOD
3430.22401 0 0
EOD
set multiplot layout 1,1
set title "uniform d=0.05 n=2^17"
set xlabel "ms per frame (mean)"
set ylabel "error: (missed + extra) / true pairs"
set logscale x 2
unset logscale y
set yrange [-0.02:2.007]
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
