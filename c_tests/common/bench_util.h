/* What the benchmarks share (METRICS.md "Speed and memory"): each run is a separate process,
 * so that its peak resident memory is its own, and the figures are medians of repetitions. */
#ifndef DELMESH_C_TESTS_BENCH_UTIL_H
#define DELMESH_C_TESTS_BENCH_UTIL_H

#include <stddef.h>

typedef struct BenchRun {
  double seconds;  /* as the child measured it */
  double peak_mb;  /* the child's peak resident memory (wait4) */
  size_t count;    /* the child's output count (tetrahedra) */
  int ok;
} BenchRun;

/* Monotonic wall clock, in seconds. */
double bench_seconds_now(void);

/* Runs this program (/proc/self/exe) again with `args` (args[0] = its name, NULL-terminated)
 * and reads the one line "<seconds> <count>" it prints; ok = 0 if it fails. */
BenchRun bench_spawn(char *const args[]);

/* Median of `count` values (sorted in place). */
double bench_median(double *values, int count);

#endif
