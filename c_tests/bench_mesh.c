/* Benchmark (not a test): oracle-driven meshing by delmesh and by CGAL Mesh_3 (no perturb, no
 * exude, sequential), on the same shapes with the same criteria (METRICS.md "Speed and memory").
 *
 *   bench_mesh                           every shape at three sizes, 3 repetitions, alternating
 *                                        (BENCH_MESH_LEVELS=1|2|3 keeps the coarser levels only)
 *   bench_mesh --child TOOL SHAPE LEVEL  one run (TOOL delmesh|cgal): prints "<seconds> <cells>"
 *
 * Criteria at level L (0, 1, 2): facet angle 30°, facet size = cell size = h0 / 2^L, facet
 * distance h / 5, radius-edge ratio 2, relative error 1e-6; h0 per shape gives ~2·10^4,
 * ~1.5·10^5 and ~10^6 cells. Each run is its own process (bench_util.h): the time is measured
 * inside it around the meshing call up to the output arrays (destruction excluded), the memory
 * is its peak resident size. Reported: medians, cells per second, ratios CGAL / delmesh
 * (> 1: delmesh is faster, smaller). */
#include "bench_util.h"
#include "mesh_run.h"
#include "ref_mesh3.h"
#include "shapes.h"

#include <delmesh.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REPETITIONS 3
#define LEVELS 3

enum { DELMESH, CGAL, TOOLS };
static const char *const tool_names[TOOLS] = {"delmesh", "cgal"};

/* The benchmarked shapes and their coarsest size h0. */
static const struct {
  ShapeId id;
  const char *key;
  double h0;
} cases[] = {
    {SHAPE_SPHERE, "sphere", 0.1},
    {SHAPE_TORUS, "torus", 0.08},
    {SHAPE_NESTED_SPHERES, "nested", 0.1},
    {SHAPE_TANGLECUBE, "tanglecube", 0.2},
};
#define CASES (sizeof cases / sizeof cases[0])

static double level_size(size_t c, int level) { return cases[c].h0 / (double)(1 << level); }

static int run_delmesh(const Shape *s, double h, double *seconds, size_t *cells) {
  RefMeshCriteria criteria = {30, h, h / 5, 2, h};
  DelmeshMesh *mesh = NULL;
  double t0 = bench_seconds_now();
  DelmeshStatus st = mesh_run(s, &criteria, 1e-6, MESH_RUN_AS_CGAL, &mesh);
  *seconds = bench_seconds_now() - t0;
  if (st != DELMESH_OK) {
    fprintf(stderr, "bench_mesh: delmesh failed (status %d): %s\n", (int)st, delmesh_last_error_message());
    return 1;
  }
  *cells = delmesh_mesh_tetrahedron_count(mesh);
  /* Nothing is freed: the process ends here, like CGAL's structures. */
  return 0;
}

static int run_cgal(const Shape *s, double h, double *seconds, size_t *cells) {
  RefMeshCriteria criteria = {30, h, h / 5, 2, h};
  RefMesh mesh;
  RefTiming timing = {0};
  memset(&mesh, 0, sizeof mesh);
  int rc = s->implicit ? ref_cgal_mesh_implicit(s->implicit, NULL, s->bbox, 1e-6, &criteria, &mesh, &timing)
                       : ref_cgal_mesh_labeled(s->label, NULL, s->bbox, 1e-6, &criteria, &mesh, &timing);
  if (rc != 0) {
    fprintf(stderr, "bench_mesh: CGAL failed: %s\n", ref_last_error());
    return 1;
  }
  *seconds = timing.seconds;
  *cells = mesh.tet_count;
  return 0;
}

static int child(int tool, size_t c, int level) {
  Shape s = shape_get(cases[c].id);
  double seconds = 0;
  size_t cells = 0;
  double h = level_size(c, level);
  int rc = tool == DELMESH ? run_delmesh(&s, h, &seconds, &cells) : run_cgal(&s, h, &seconds, &cells);
  if (rc == 0) printf("%.6f %zu\n", seconds, cells);
  return rc;
}

static int lookup_case(const char *key) {
  for (size_t c = 0; c < CASES; c++)
    if (strcmp(key, cases[c].key) == 0) return (int)c;
  return -1;
}

int main(int argc, char **argv) {
  if (argc == 5 && strcmp(argv[1], "--child") == 0) {
    int tool = strcmp(argv[2], "delmesh") == 0 ? DELMESH : strcmp(argv[2], "cgal") == 0 ? CGAL : -1;
    int c = lookup_case(argv[3]), level = atoi(argv[4]);
    if (tool < 0 || c < 0 || level < 0 || level >= LEVELS) return 2;
    return child(tool, (size_t)c, level);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s   (BENCH_MESH_LEVELS=1..3 limits the sizes)\n", argv[0]);
    return 2;
  }
  const char *env = getenv("BENCH_MESH_LEVELS");
  int levels = env && env[0] ? atoi(env) : LEVELS;
  if (levels < 1 || levels > LEVELS) levels = LEVELS;

  printf("delmesh %s vs CGAL Mesh_3 (make_mesh_3, no_perturb, no_exude, sequential)\n", delmesh_version_string());
  printf("each run in its own process; %d repetitions, alternating; medians\n\n", REPETITIONS);
  printf("%-11s %8s | %-25s | %9s | %-21s | %9s | %s\n", "", "", "cells per second (median)", "time",
         "peak memory, MB", "memory", "");
  printf("%-11s %8s | %12s %12s | %9s | %10s %10s | %9s | %s\n", "shape", "h", "delmesh", "CGAL",
         "CGAL/ours", "delmesh", "CGAL", "CGAL/ours", "cells: delmesh / CGAL");
  int failures = 0;
  for (size_t c = 0; c < CASES; c++)
    for (int level = 0; level < levels; level++) {
      double times[TOOLS][REPETITIONS], mems[TOOLS][REPETITIONS];
      size_t cells[TOOLS] = {0, 0};
      int ok = 1;
      char level_arg[8];
      snprintf(level_arg, sizeof level_arg, "%d", level);
      for (int rep = 0; rep < REPETITIONS && ok; rep++)
        for (int k = 0; k < TOOLS; k++) {
          int tool = (k + rep) % TOOLS; /* alternate who goes first */
          char *args[] = {argv[0], (char *)"--child", (char *)tool_names[tool], (char *)cases[c].key,
                          level_arg, NULL};
          BenchRun r = bench_spawn(args);
          if (!r.ok) {
            ok = 0;
            break;
          }
          times[tool][rep] = r.seconds;
          mems[tool][rep] = r.peak_mb;
          cells[tool] = r.count;
        }
      if (!ok) {
        printf("%-11s %8g | failed\n", cases[c].key, level_size(c, level));
        failures++;
        continue;
      }
      double t[TOOLS], mb[TOOLS];
      for (int tool = 0; tool < TOOLS; tool++) {
        t[tool] = bench_median(times[tool], REPETITIONS);
        mb[tool] = bench_median(mems[tool], REPETITIONS);
      }
      printf("%-11s %8g | %12.0f %12.0f | %9.2f | %10.1f %10.1f | %9.2f | %zu / %zu\n", cases[c].key,
             level_size(c, level), (double)cells[DELMESH] / t[DELMESH], (double)cells[CGAL] / t[CGAL],
             t[CGAL] / t[DELMESH], mb[DELMESH], mb[CGAL], mb[CGAL] / mb[DELMESH], cells[DELMESH], cells[CGAL]);
      fflush(stdout);
    }
  return failures ? 1 : 0;
}
