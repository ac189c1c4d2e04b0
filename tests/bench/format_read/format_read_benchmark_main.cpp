// The main of format_read_benchmark: one file per format beside it registers its benchmarks.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
