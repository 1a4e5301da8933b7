# Made by sap_bench; render with: gnuplot pareto_uniform_d0.35.gp
set terminal pngcairo size 560,420 noenhanced font "sans,10"
set output "pareto_uniform_d0.35.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
23.3917457 0 0
EOD
$P0S1 << EOD
36.3894324 0 0
EOD
$P0S2 << EOD
21.9925839 6.26979295e-07 0
EOD
$P0S3 << EOD
23.8753011 0.00488730361 0
EOD
$P0S4 << EOD
34.9286014 0.328450314 0
EOD
$P0S5 << EOD
40.2424236 1.72189173 0
EOD
$P0S6 << EOD
17.2855869 0.0475024593 0
EOD
$P0S7 << EOD
8.28731319 0.139287212 0
EOD
$P0S8 << EOD
4.89481431 0.311011198 0
EOD
$P0S9 << EOD
1081.25879 0.315181551 0
EOD
$P0S10 << EOD
141.654015 0 0
EOD
$P0S11 << EOD
128.917813 0 0
EOD
$P0S12 << EOD
17482.2489 0 0
EOD
$P0S13 << EOD
5679.5464 0 0
EOD
set multiplot layout 1,1
set title "uniform d=0.35 n=2^17"
set xlabel "ms per frame (mean)"
set ylabel "error: (missed + extra) / true pairs"
set logscale x 2
unset logscale y
set yrange [-0.02:1.98]
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
