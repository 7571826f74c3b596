/* Benchmark (not a test): the optimization after refinement alone, delmesh's sliver
 * perturbation and exudation (its default optimization) against CGAL Mesh_3's perturb_mesh_3 + exude_mesh_3 (the default
 * optimizers of make_mesh_3), on the same shapes with the same criteria (METRICS.md "Speed and
 * memory", "Quality").
 *
 *   bench_optimize                            every shape at three sizes, 3 repetitions,
 *                                             alternating (BENCH_OPTIMIZE_LEVELS=1|2|3 keeps the
 *                                             coarser levels only)
 *   bench_optimize --child RUN SHAPE LEVEL FILE
 *                                             one run (RUN: delmesh-none, delmesh-default, cgal);
 *                                             prints "<seconds> <cells>", writes its quality
 *                                             figures to FILE
 *
 * Criteria at level L (0, 1, 2) as bench_mesh: facet angle 30°, facet size = cell size =
 * h0 / 2^L, facet distance h / 5, radius-edge ratio 2, relative error 1e-6; ~2·10^4, ~1.5·10^5
 * and ~10^6 cells.
 *
 * delmesh has no separate optimization call in its C API: its optimization time is the median
 * of whole runs with the default optimization minus the median of whole runs with optimization 0
 * (refinement is deterministic, so both refine the same mesh). CGAL's is measured around its two
 * calls on the refined complex (ref_mesh3.h, REF_OPTIMIZE_SEPARATE), no time limit on either
 * side (0: CGAL's own default for perturb_mesh_3 and exude_mesh_3; make_mesh_3 would stop each
 * after the refinement's time). Each run is its own process (bench_util.h). Reported: medians,
 * ratio CGAL / delmesh (> 1: delmesh is faster), refined cells, min dihedral angle and the count
 * of cells below 10° after optimization on both sides (quality.h). */
#define _POSIX_C_SOURCE 200809L

#include "bench_util.h"
#include "mesh_run.h"
#include "quality.h"
#include "ref_mesh3.h"
#include "shapes.h"

#include <delmesh.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define REPETITIONS 3
#define LEVELS 3

enum { OURS_NONE, OURS_DEFAULT, CGAL, RUNS };
static const char *const run_names[RUNS] = {"delmesh-none", "delmesh-default", "cgal"};

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

/* What a child writes to its figures file besides the "<seconds> <cells>" line. */
typedef struct Figures {
  size_t refined_cells, cells;
  double min_dihedral_before, min_dihedral;
  size_t below10_before, below10;
  double perturb_seconds, exude_seconds; /* CGAL only */
} Figures;

static int run_delmesh(const Shape *s, double h, int optimize, double *seconds, Figures *f) {
  RefMeshCriteria criteria = {30, h, h / 5, 2, h};
  DelmeshMesh *mesh = NULL;
  double t0 = bench_seconds_now();
  DelmeshStatus st = mesh_run(s, &criteria, 1e-6, optimize ? MESH_RUN_DEFAULT : MESH_RUN_REFINE, &mesh);
  *seconds = bench_seconds_now() - t0;
  if (st != DELMESH_OK) {
    fprintf(stderr, "bench_optimize: delmesh failed (status %d): %s\n", (int)st, delmesh_last_error_message());
    return 1;
  }
  size_t n = delmesh_mesh_tetrahedron_count(mesh);
  QualitySummary q = quality_tetrahedra(delmesh_mesh_vertices(mesh), delmesh_mesh_tetrahedra(mesh), n);
  f->cells = n;
  f->min_dihedral = q.min_dihedral;
  f->below10 = q.dihedral_below[1];
  /* Nothing is freed: the process ends here. */
  return 0;
}

static int run_cgal(const Shape *s, double h, double *seconds, Figures *f) {
  RefMeshCriteria criteria = {30, h, h / 5, 2, h};
  RefMesh refined, mesh;
  RefMeshTiming timing;
  memset(&refined, 0, sizeof refined);
  memset(&mesh, 0, sizeof mesh);
  memset(&timing, 0, sizeof timing);
  RefMeshOptions options = {REF_OPTIMIZE_SEPARATE, 0.0, &refined};
  int rc = s->implicit
               ? ref_cgal_mesh_implicit_optimized(s->implicit, NULL, s->bbox, 1e-6, &criteria, &options, &mesh, &timing)
               : ref_cgal_mesh_labeled_optimized(s->label, NULL, s->bbox, 1e-6, &criteria, &options, &mesh, &timing);
  if (rc != 0) {
    fprintf(stderr, "bench_optimize: CGAL failed: %s\n", ref_last_error());
    return 1;
  }
  *seconds = timing.perturb_seconds + timing.exude_seconds;
  QualitySummary before = quality_tetrahedra(refined.xyz, refined.tets, refined.tet_count);
  QualitySummary after = quality_tetrahedra(mesh.xyz, mesh.tets, mesh.tet_count);
  f->refined_cells = refined.tet_count;
  f->cells = mesh.tet_count;
  f->min_dihedral_before = before.min_dihedral;
  f->below10_before = before.dihedral_below[1];
  f->min_dihedral = after.min_dihedral;
  f->below10 = after.dihedral_below[1];
  f->perturb_seconds = timing.perturb_seconds;
  f->exude_seconds = timing.exude_seconds;
  return 0;
}

static int child(int run, size_t c, int level, const char *path) {
  Shape s = shape_get(cases[c].id);
  double seconds = 0, h = level_size(c, level);
  Figures f;
  memset(&f, 0, sizeof f);
  int rc = run == CGAL ? run_cgal(&s, h, &seconds, &f) : run_delmesh(&s, h, run == OURS_DEFAULT, &seconds, &f);
  if (rc != 0) return rc;
  FILE *out = fopen(path, "w");
  if (!out) return 1;
  fprintf(out, "%zu %zu %.17g %.17g %zu %zu %.9f %.9f\n", f.refined_cells, f.cells, f.min_dihedral_before,
          f.min_dihedral, f.below10_before, f.below10, f.perturb_seconds, f.exude_seconds);
  if (fclose(out) != 0) return 1;
  printf("%.6f %zu\n", seconds, f.cells);
  return 0;
}

static int read_figures(const char *path, Figures *f) {
  FILE *in = fopen(path, "r");
  if (!in) return 0;
  int ok = fscanf(in, "%zu %zu %lf %lf %zu %zu %lf %lf", &f->refined_cells, &f->cells, &f->min_dihedral_before,
                  &f->min_dihedral, &f->below10_before, &f->below10, &f->perturb_seconds, &f->exude_seconds) == 8;
  fclose(in);
  return ok;
}

static int lookup_case(const char *key) {
  for (size_t c = 0; c < CASES; c++)
    if (strcmp(key, cases[c].key) == 0) return (int)c;
  return -1;
}

static int lookup_run(const char *name) {
  for (int r = 0; r < RUNS; r++)
    if (strcmp(name, run_names[r]) == 0) return r;
  return -1;
}

int main(int argc, char **argv) {
  if (argc == 6 && strcmp(argv[1], "--child") == 0) {
    int run = lookup_run(argv[2]), c = lookup_case(argv[3]), level = atoi(argv[4]);
    if (run < 0 || c < 0 || level < 0 || level >= LEVELS) return 2;
    return child(run, (size_t)c, level, argv[5]);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s   (BENCH_OPTIMIZE_LEVELS=1..3 limits the sizes)\n", argv[0]);
    return 2;
  }
  const char *env = getenv("BENCH_OPTIMIZE_LEVELS");
  int levels = env && env[0] ? atoi(env) : LEVELS;
  if (levels < 1 || levels > LEVELS) levels = LEVELS;
  char path[] = "/tmp/bench_optimize_XXXXXX";
  int fd = mkstemp(path);
  if (fd < 0) {
    perror("bench_optimize: mkstemp");
    return 1;
  }
  close(fd);

  printf("delmesh %s perturbation + exudation vs CGAL Mesh_3 perturb_mesh_3 + exude_mesh_3 (sequential, no time limits)\n",
         delmesh_version_string());
  printf("each run in its own process; %d repetitions, alternating; medians. delmesh's time = run with its default\n"
         "optimization - run with optimization 0; CGAL's = its two calls on the refined complex.\n\n",
         REPETITIONS);
  printf("%-10s %6s | %-17s | %-26s | %-29s | %9s | %-15s | %-11s\n", "", "", "refined cells", "delmesh, s (median)",
         "CGAL, s (median)", "time", "min dihedral", "cells < 10°");
  printf("%-10s %6s | %8s %8s | %8s %8s %8s | %9s %9s %9s | %9s | %7s %7s | %5s %5s\n", "shape", "h", "delmesh", "CGAL",
         "none", "default", "passes", "perturb", "exude", "total", "CGAL/ours", "delmesh", "CGAL", "ours", "CGAL");
  int failures = 0;
  for (size_t c = 0; c < CASES; c++)
    for (int level = 0; level < levels; level++) {
      double times[RUNS][REPETITIONS], perturb[REPETITIONS], exude[REPETITIONS];
      Figures fig[RUNS];
      memset(fig, 0, sizeof fig);
      int ok = 1;
      char level_arg[8];
      snprintf(level_arg, sizeof level_arg, "%d", level);
      for (int rep = 0; rep < REPETITIONS && ok; rep++)
        for (int k = 0; k < RUNS && ok; k++) {
          int run = (k + rep) % RUNS; /* alternate who goes first */
          char *args[] = {argv[0], (char *)"--child", (char *)run_names[run], (char *)cases[c].key, level_arg, path,
                          NULL};
          BenchRun r = bench_spawn(args);
          ok = r.ok && read_figures(path, &fig[run]);
          times[run][rep] = r.seconds;
          if (run == CGAL) perturb[rep] = fig[run].perturb_seconds, exude[rep] = fig[run].exude_seconds;
        }
      if (!ok) {
        printf("%-10s %6g | failed\n", cases[c].key, level_size(c, level));
        failures++;
        continue;
      }
      double none = bench_median(times[OURS_NONE], REPETITIONS), def = bench_median(times[OURS_DEFAULT], REPETITIONS);
      double ours = def - none, theirs = bench_median(times[CGAL], REPETITIONS);
      printf("%-10s %6g | %8zu %8zu | %8.3f %8.3f %8.3f | %9.3f %9.3f %9.3f | %9.2f | %7.3f %7.3f | %5zu %5zu\n",
             cases[c].key, level_size(c, level), fig[OURS_NONE].cells, fig[CGAL].refined_cells, none, def, ours,
             bench_median(perturb, REPETITIONS), bench_median(exude, REPETITIONS), theirs,
             ours > 0 ? theirs / ours : 0.0, fig[OURS_DEFAULT].min_dihedral, fig[CGAL].min_dihedral,
             fig[OURS_DEFAULT].below10, fig[CGAL].below10);
      fflush(stdout);
    }
  unlink(path);
  return failures ? 1 : 0;
}
