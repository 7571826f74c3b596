/* Benchmark (not a test): Delaunay tetrahedralization by delmesh, CGAL and TetGen (METRICS.md
 * "Speed and memory").
 *
 *   bench                         all sizes (BENCH_SIZES="100000,1000000" by default) and both
 *                                 distributions, 3 repetitions, alternating the three programs
 *   bench --child TOOL DIST N     one run (TOOL delmesh|cgal|tetgen, DIST cube|shell): prints
 *                                 "<seconds> <tetrahedra>"
 *
 * Each run is a separate process (fork + exec of this program), so its peak resident memory
 * (wait4, ru_maxrss) is its own. The time is measured inside the child around the call
 * (CLOCK_MONOTONIC), input generation excluded, conversion of the result to index arrays
 * included for all three, destruction excluded for all three. Reported: medians of the
 * repetitions, points per second, and the ratios reference / delmesh (> 1: delmesh is faster,
 * smaller). */

#include "bench_util.h"
#include "points.h"
#include "ref.h"

#include <delmesh.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REPETITIONS 3
#define MAX_SIZES 8
#define SHELL_THICKNESS 0.01

enum { DELMESH, CGAL, TETGEN, TOOLS };
static const char *const tool_names[TOOLS] = {"delmesh", "cgal", "tetgen"};
enum { CUBE, SHELL, DISTRIBUTIONS };
static const char *const distribution_names[DISTRIBUTIONS] = {"cube", "shell"};

static int lookup(const char *name, const char *const *names, int count) {
  for (int i = 0; i < count; i++)
    if (strcmp(name, names[i]) == 0) return i;
  return -1;
}

/* ---- child: one run ------------------------------------------------------------------------- */

static int child(int tool, int distribution, size_t n) {
  /* The same points for every tool (fixed seeds). */
  double *xyz = distribution == CUBE ? points_uniform_cube(n, 0xBE7C0000u + n)
                                     : points_thin_shell(n, SHELL_THICKNESS, 0xBE750000u + n);
  if (!xyz) {
    fprintf(stderr, "bench: out of memory generating %zu points\n", n);
    return 1;
  }
  double seconds = 0;
  size_t count = 0;
  if (tool == DELMESH) {
    DelmeshMesh *mesh = NULL;
    double t0 = bench_seconds_now();
    DelmeshStatus s = delmesh_delaunay_tetrahedralize(xyz, n, &mesh);
    const uint32_t *tets = s == DELMESH_OK ? delmesh_mesh_tetrahedra(mesh) : NULL;
    count = s == DELMESH_OK ? delmesh_mesh_tetrahedron_count(mesh) : 0;
    seconds = bench_seconds_now() - t0;
    if (s != DELMESH_OK || !tets) {
      fprintf(stderr, "bench: delmesh failed (status %d): %s\n", (int)s, delmesh_last_error_message());
      return 1;
    }
    /* The mesh is not freed: the process ends here, like the references' structures. */
  } else {
    uint32_t *tets = NULL;
    RefTiming timing = {0};
    int rc = tool == CGAL ? ref_cgal_delaunay(xyz, n, &tets, &count, &timing)
                          : ref_tetgen_delaunay(xyz, n, &tets, &count, &timing);
    if (rc != 0) {
      fprintf(stderr, "bench: %s failed: %s\n", tool_names[tool], ref_last_error());
      return 1;
    }
    seconds = timing.seconds;
    free(tets);
  }
  printf("%.6f %zu\n", seconds, count);
  free(xyz);
  return 0;
}

/* ---- parent: the table ---------------------------------------------------------------------- */

static size_t parse_sizes(size_t *sizes) {
  const char *env = getenv("BENCH_SIZES");
  const char *text = env && env[0] ? env : "100000,1000000";
  size_t count = 0;
  while (*text && count < MAX_SIZES) {
    char *end;
    unsigned long long v = strtoull(text, &end, 10);
    if (end == text || v < 4) {
      fprintf(stderr, "bench: bad BENCH_SIZES \"%s\" (comma-separated counts >= 4)\n", env);
      return 0;
    }
    sizes[count++] = (size_t)v;
    text = *end == ',' ? end + 1 : end;
    if (*end && *end != ',') {
      fprintf(stderr, "bench: bad BENCH_SIZES \"%s\"\n", env);
      return 0;
    }
  }
  return count;
}

int main(int argc, char **argv) {
  if (argc == 5 && strcmp(argv[1], "--child") == 0) {
    int tool = lookup(argv[2], tool_names, TOOLS);
    int distribution = lookup(argv[3], distribution_names, DISTRIBUTIONS);
    size_t n = (size_t)strtoull(argv[4], NULL, 10);
    if (tool < 0 || distribution < 0 || n < 4) return 2;
    return child(tool, distribution, n);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s   (BENCH_SIZES=n1,n2,... to choose the sizes)\n", argv[0]);
    return 2;
  }

  size_t sizes[MAX_SIZES];
  size_t size_count = parse_sizes(sizes);
  if (!size_count) return 2;

  printf("delmesh %s vs CGAL Delaunay_triangulation_3 (bulk insertion, spatial sort) vs TetGen \"QzJ\"\n",
         delmesh_version_string());
  printf("each run in its own process; %d repetitions, alternating; medians; shell = unit sphere, thickness %g\n\n",
         REPETITIONS, SHELL_THICKNESS);

  typedef struct Row {
    size_t n;
    int distribution;
    double seconds[TOOLS], peak_mb[TOOLS];
    size_t tetrahedra[TOOLS];
    int ok;
  } Row;
  Row rows[MAX_SIZES * DISTRIBUTIONS];
  size_t row_count = 0;
  int failures = 0;

  for (size_t s = 0; s < size_count; s++)
    for (int d = 0; d < DISTRIBUTIONS; d++) {
      Row *row = &rows[row_count++];
      double times[TOOLS][REPETITIONS], mems[TOOLS][REPETITIONS];
      row->n = sizes[s];
      row->distribution = d;
      row->ok = 1;
      for (int rep = 0; rep < REPETITIONS; rep++)
        for (int k = 0; k < TOOLS; k++) {
          int tool = (k + rep) % TOOLS; /* rotate who goes first */
          char size_arg[32];
          snprintf(size_arg, sizeof size_arg, "%zu", sizes[s]);
          char *args[] = {argv[0], (char *)"--child", (char *)tool_names[tool],
                          (char *)distribution_names[d], size_arg, NULL};
          BenchRun r = bench_spawn(args);
          printf("  run %zu %-5s rep %d %-7s: ", sizes[s], distribution_names[d], rep + 1, tool_names[tool]);
          if (!r.ok) {
            printf("FAILED\n");
            row->ok = 0;
            failures++;
            continue;
          }
          printf("%8.3f s %8.1f MB %10zu tetrahedra\n", r.seconds, r.peak_mb, r.count);
          times[tool][rep] = r.seconds;
          mems[tool][rep] = r.peak_mb;
          row->tetrahedra[tool] = r.count;
        }
      if (!row->ok) continue;
      for (int tool = 0; tool < TOOLS; tool++) {
        row->seconds[tool] = bench_median(times[tool], REPETITIONS);
        row->peak_mb[tool] = bench_median(mems[tool], REPETITIONS);
      }
    }

  printf("\n%9s %-5s | %-38s | %-23s | %-26s | %-23s |\n", "", "", "points per second (median)",
         "time ratio (>1: faster)", "peak memory, MB (median)", "mem. ratio (>1: smaller)");
  printf("%9s %-5s | %12s %12s %12s | %11s %11s | %8s %8s %8s | %11s %11s | %s\n", "points", "dist",
         "delmesh", "CGAL", "TetGen", "CGAL/ours", "TetGen/ours", "delmesh", "CGAL", "TetGen",
         "CGAL/ours", "TetGen/ours", "tetrahedra: delmesh / CGAL / TetGen");
  for (size_t i = 0; i < row_count; i++) {
    const Row *r = &rows[i];
    if (!r->ok) {
      printf("%9zu %-5s | failed\n", r->n, distribution_names[r->distribution]);
      continue;
    }
    printf("%9zu %-5s | %12.0f %12.0f %12.0f | %11.2f %11.2f | %8.1f %8.1f %8.1f | %11.2f %11.2f | %zu / %zu / %zu\n",
           r->n, distribution_names[r->distribution], (double)r->n / r->seconds[DELMESH],
           (double)r->n / r->seconds[CGAL], (double)r->n / r->seconds[TETGEN],
           r->seconds[CGAL] / r->seconds[DELMESH], r->seconds[TETGEN] / r->seconds[DELMESH],
           r->peak_mb[DELMESH], r->peak_mb[CGAL], r->peak_mb[TETGEN],
           r->peak_mb[CGAL] / r->peak_mb[DELMESH], r->peak_mb[TETGEN] / r->peak_mb[DELMESH],
           r->tetrahedra[DELMESH], r->tetrahedra[CGAL], r->tetrahedra[TETGEN]);
  }
  return failures ? 1 : 0;
}
