# Benchmarks (issue 4): sap_bench and Google Benchmark microbenchmarks.
