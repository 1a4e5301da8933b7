# Made by sap_bench; render with: gnuplot pareto_ball.gp
set terminal pngcairo size 560,420 noenhanced font "sans,10"
set output "pareto_ball.png"
set grid
set key outside below horizontal
set style fill transparent solid 0.6 noborder
$P0S0 << EOD
32.0026077 0 0
EOD
$P0S1 << EOD
35.6207856 0 0
EOD
$P0S2 << EOD
32.7897443 8.82990512e-06 0
EOD
$P0S3 << EOD
12.6994052 0.0078799545 0
EOD
$P0S4 << EOD
35.2229976 0.328064823 0
EOD
$P0S5 << EOD
41.9166596 1.72396981 0
EOD
$P0S6 << EOD
15.4541734 0.0273955165 0
EOD
$P0S7 << EOD
9.68308538 0.0797553822 0
EOD
$P0S8 << EOD
5.36987681 0.175651095 0
EOD
$P0S9 << EOD
1216.80662 0.233779096 0
EOD
$P0S10 << EOD
135.632611 0 0
EOD
$P0S11 << EOD
89.6001554 0 0
EOD
$P0S12 << EOD
176991.949 0 0
EOD
$P0S13 << EOD
3989.91178 0 0
EOD
set multiplot layout 1,1
set title "ball n=2^17 f75"
set xlabel "ms per frame (mean)"
set ylabel "error: (missed + extra) / true pairs"
set logscale x 2
unset logscale y
set yrange [-0.02:1.983]
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
