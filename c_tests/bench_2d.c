/* Benchmark (not a test): planar triangulation by delmesh and CGAL (METRICS.md "Speed and
 * memory").
 *
 *   bench_2d                      every case, 3 repetitions, alternating the two programs
 *   bench_2d --child TOOL CASE    one run (TOOL delmesh|cgal): prints "<seconds> <triangles>"
 *
 * Cases:
 *   delaunay  Delaunay triangulation of BENCH_2D_POINTS (default 1000000) uniform random points
 *             in the unit square: delmesh_triangulate_2d DELAUNAY vs CGAL
 *             Delaunay_triangulation_2 built from (point, index) pairs (spatial sort);
 *   star      quality meshing at 25 degrees, no size bound, of a star-shaped polygon with
 *             10^4 edges (r = 1 + 0.3 sin(12 t)): delmesh_triangulate_2d QUALITY vs CGAL's
 *             refine_Delaunay_mesh_2 (Delaunay_mesh_size_criteria_2, shape bound sin^2 25 deg);
 *   holes     the same on the unit square pierced by a 100 x 100 grid of square holes (4 10^4 + 4
 *             edges, 10^4 hole seeds);
 *   conform   conforming Delaunay triangulation of a random star polygon of 10^4 edges (sorted
 *             random angles, radii uniform in [0.3, 1]: many acute angles) and 10^4 random
 *             points in [-0.2, 0.2]^2: delmesh_triangulate_2d CONFORMING (Pebay) vs CGAL's
 *             make_conforming_Delaunay_2; the count column gives vertices, not triangles.
 *
 * Each run is a separate process (fork + exec of this program), so its peak resident memory is
 * its own. The time is measured inside the child around the call, input generation excluded,
 * export of the triangles as index arrays included for both, destruction excluded for both;
 * CGAL's quality time includes building its constrained triangulation, as delmesh's does.
 * Reported: medians of the repetitions, ratios CGAL / delmesh (> 1: delmesh is faster,
 * smaller), triangle counts, and for the quality cases the smallest angle and the triangles
 * below 25 degrees of one more (untimed) run of each. */

#include "bench_util.h"
#include "prng.h"
#include "ref_cgal2d.h"

#include <delmesh.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define REPETITIONS 3
#define MIN_ANGLE 25.0
#define STAR_EDGES 10000
#define HOLE_GRID 100

enum { DELMESH, CGAL, TOOLS };
static const char *const tool_names[TOOLS] = {"delmesh", "cgal"};
enum { CASE_DELAUNAY, CASE_STAR, CASE_HOLES, CASE_CONFORM, CASES };
static const char *const case_names[CASES] = {"delaunay", "star", "holes", "conform"};

static int lookup(const char *name, const char *const *names, int count) {
  for (int i = 0; i < count; i++)
    if (strcmp(name, names[i]) == 0) return i;
  return -1;
}

/* ---- inputs --------------------------------------------------------------------------------- */

typedef struct Pslg {
  double *xy;
  size_t n_points;
  uint32_t *segments;
  size_t n_segments;
  double *holes;
  size_t n_holes;
} Pslg;

static void pslg_free(Pslg *p) {
  free(p->xy);
  free(p->segments);
  free(p->holes);
}

static size_t delaunay_points(void) {
  const char *env = getenv("BENCH_2D_POINTS");
  size_t n = env && env[0] ? (size_t)strtoull(env, NULL, 10) : 1000000;
  return n < 3 ? 3 : n;
}

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The inputs of `which` (the same for both tools); 0 when out of memory. */
static int make_input(int which, Pslg *p) {
  memset(p, 0, sizeof *p);
  if (which == CASE_DELAUNAY) {
    size_t n = delaunay_points();
    p->xy = malloc(2 * n * sizeof *p->xy);
    if (!p->xy) return 0;
    Prng g = prng_new(0x2D00BE7Cu + n);
    for (size_t i = 0; i < 2 * n; i++) p->xy[i] = prng_uniform(&g);
    p->n_points = n;
    return 1;
  }
  if (which == CASE_STAR) {
    size_t n = STAR_EDGES;
    p->xy = malloc(2 * n * sizeof *p->xy);
    p->segments = malloc(2 * n * sizeof *p->segments);
    if (!p->xy || !p->segments) return 0;
    for (size_t i = 0; i < n; i++) {
      double t = 2.0 * 3.14159265358979323846 * (double)i / (double)n;
      double r = 1.0 + 0.3 * sin(12.0 * t);
      p->xy[2 * i] = r * cos(t);
      p->xy[2 * i + 1] = r * sin(t);
      p->segments[2 * i] = (uint32_t)i;
      p->segments[2 * i + 1] = (uint32_t)((i + 1) % n);
    }
    p->n_points = p->n_segments = n;
    return 1;
  }
  if (which == CASE_CONFORM) {
    size_t n = STAR_EDGES;
    p->xy = malloc(4 * n * sizeof *p->xy);
    p->segments = malloc(2 * n * sizeof *p->segments);
    double *angle = malloc(n * sizeof *angle);
    if (!p->xy || !p->segments || !angle) return free(angle), 0;
    Prng g = prng_new(0xC0F0u);
    for (size_t i = 0; i < n; i++) angle[i] = 2.0 * 3.14159265358979323846 * prng_uniform(&g);
    qsort(angle, n, sizeof *angle, compare_doubles);
    for (size_t i = 0; i < n; i++) {
      double r = 0.3 + 0.7 * prng_uniform(&g);
      p->xy[2 * i] = r * cos(angle[i]);
      p->xy[2 * i + 1] = r * sin(angle[i]);
      p->segments[2 * i] = (uint32_t)i;
      p->segments[2 * i + 1] = (uint32_t)((i + 1) % n);
    }
    for (size_t i = 2 * n; i < 4 * n; i++) p->xy[i] = 0.4 * prng_uniform(&g) - 0.2;
    free(angle);
    p->n_points = 2 * n;
    p->n_segments = n;
    return 1;
  }
  /* holes: the unit square, and in each of the HOLE_GRID^2 cells a square hole of half its side. */
  size_t holes = (size_t)HOLE_GRID * HOLE_GRID, n = 4 + 4 * holes;
  p->xy = malloc(2 * n * sizeof *p->xy);
  p->segments = malloc(2 * n * sizeof *p->segments);
  p->holes = malloc(2 * holes * sizeof *p->holes);
  if (!p->xy || !p->segments || !p->holes) return 0;
  static const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  size_t v = 0, s = 0;
  for (size_t square = 0; square <= holes; square++) {
    double cx = 0.5, cy = 0.5, half = 0.5;
    if (square > 0) {
      size_t i = (square - 1) % HOLE_GRID, j = (square - 1) / HOLE_GRID;
      double cell = 1.0 / HOLE_GRID;
      cx = ((double)i + 0.5) * cell;
      cy = ((double)j + 0.5) * cell;
      half = 0.25 * cell;
      p->holes[2 * (square - 1)] = cx;
      p->holes[2 * (square - 1) + 1] = cy;
    }
    for (int k = 0; k < 4; k++) {
      p->xy[2 * (v + (size_t)k)] = cx + (2 * corner[k][0] - 1) * half;
      p->xy[2 * (v + (size_t)k) + 1] = cy + (2 * corner[k][1] - 1) * half;
      p->segments[2 * s] = (uint32_t)(v + (size_t)k);
      p->segments[2 * s + 1] = (uint32_t)(v + (size_t)(k + 1) % 4);
      s++;
    }
    v += 4;
  }
  p->n_points = v;
  p->n_segments = s;
  p->n_holes = holes;
  return 1;
}

/* ---- runs ----------------------------------------------------------------------------------- */

typedef struct Outcome {
  double seconds;
  size_t triangles;
  double min_angle; /* quality cases: degrees */
  size_t below;     /* quality cases: triangles with an angle below MIN_ANGLE */
} Outcome;

/* The smallest angle of the triangle a b c (2D), in degrees, at its shortest edge. */
static double smallest_angle(const double *a, const double *b, const double *c) {
  double l[3], x, y;
  l[0] = (b[0] - c[0]) * (b[0] - c[0]) + (b[1] - c[1]) * (b[1] - c[1]);
  l[1] = (c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1]);
  l[2] = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
  int k = l[0] <= l[1] && l[0] <= l[2] ? 0 : l[1] <= l[2] ? 1 : 2;
  x = l[(k + 1) % 3];
  y = l[(k + 2) % 3];
  double cosine = (x + y - l[k]) / (2.0 * sqrt(x * y));
  cosine = cosine > 1 ? 1 : cosine < -1 ? -1 : cosine;
  return acos(cosine) * 180.0 / 3.14159265358979323846;
}

/* One run of `tool` on case `which`; 0 on failure (reported on stderr). */
static int run(int tool, int which, const Pslg *p, Outcome *out) {
  memset(out, 0, sizeof *out);
  out->min_angle = 180.0;
  if (tool == DELMESH) {
    DelmeshOptions2d options;
    memset(&options, 0, sizeof options);
    options.mode = which == CASE_DELAUNAY  ? DELMESH_MODE2D_DELAUNAY
                   : which == CASE_CONFORM ? DELMESH_MODE2D_CONFORMING
                                           : DELMESH_MODE2D_QUALITY;
    if (which == CASE_STAR || which == CASE_HOLES) options.min_angle_degrees = MIN_ANGLE;
    options.holes = p->holes;
    options.n_holes = p->n_holes;
    DelmeshMesh *mesh = NULL;
    double t0 = bench_seconds_now();
    DelmeshStatus s = delmesh_triangulate_2d(p->xy, p->n_points, p->segments, p->n_segments,
                                             &options, &mesh);
    const uint32_t *tri = s == DELMESH_OK ? delmesh_mesh_triangles(mesh) : NULL;
    out->triangles = s != DELMESH_OK      ? 0
                     : which == CASE_CONFORM ? delmesh_mesh_vertex_count(mesh)
                                             : delmesh_mesh_triangle_count(mesh);
    out->seconds = bench_seconds_now() - t0;
    if (s != DELMESH_OK || (!tri && out->triangles)) {
      fprintf(stderr, "bench_2d: delmesh failed (status %d): %s\n", (int)s,
              delmesh_last_error_message());
      return 0;
    }
    if (which == CASE_STAR || which == CASE_HOLES) {
      const double *v = delmesh_mesh_vertices(mesh); /* x y z per vertex */
      for (size_t t = 0; t < out->triangles; t++) {
        double a = smallest_angle(&v[3 * tri[3 * t]], &v[3 * tri[3 * t + 1]], &v[3 * tri[3 * t + 2]]);
        if (a < out->min_angle) out->min_angle = a;
        if (a < MIN_ANGLE) out->below++;
      }
    }
    delmesh_mesh_free(mesh);
    return 1;
  }
  RefTiming timing = {0};
  if (which == CASE_DELAUNAY) {
    uint32_t *tri = NULL;
    if (ref_cgal_delaunay_2d(p->xy, p->n_points, &tri, &out->triangles, &timing) != 0) {
      fprintf(stderr, "bench_2d: CGAL failed: %s\n", ref_last_error());
      return 0;
    }
    free(tri);
  } else if (which == CASE_CONFORM) {
    RefConforming2d m;
    if (ref_cgal_conforming_2d(p->xy, p->n_points, p->segments, p->n_segments, &m, &timing) != 0) {
      fprintf(stderr, "bench_2d: CGAL failed: %s\n", ref_last_error());
      return 0;
    }
    out->triangles = m.vertex_count;
  } else {
    RefMesh2d m;
    if (ref_cgal_mesh_2d(p->xy, p->n_points, p->segments, p->n_segments, p->holes, p->n_holes,
                         MIN_ANGLE, &m, &timing) != 0) {
      fprintf(stderr, "bench_2d: CGAL failed: %s\n", ref_last_error());
      return 0;
    }
    out->triangles = m.triangle_count;
    out->min_angle = m.min_angle_degrees;
    out->below = m.below_bound;
  }
  out->seconds = timing.seconds;
  return 1;
}

static int child(int tool, int which) {
  Pslg p;
  if (!make_input(which, &p)) {
    fprintf(stderr, "bench_2d: out of memory generating the input\n");
    pslg_free(&p);
    return 1;
  }
  Outcome o;
  int ok = run(tool, which, &p, &o);
  if (ok) printf("%.6f %zu\n", o.seconds, o.triangles);
  pslg_free(&p);
  return ok ? 0 : 1;
}

/* ---- parent: the table ---------------------------------------------------------------------- */

int main(int argc, char **argv) {
  if (argc == 4 && strcmp(argv[1], "--child") == 0) {
    int tool = lookup(argv[2], tool_names, TOOLS);
    int which = lookup(argv[3], case_names, CASES);
    if (tool < 0 || which < 0) return 2;
    return child(tool, which);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s   (BENCH_2D_POINTS=n for the Delaunay case)\n", argv[0]);
    return 2;
  }
  printf("delmesh %s vs CGAL 2D: Delaunay_triangulation_2 (%zu random points), "
         "refine_Delaunay_mesh_2 at %g degrees\n",
         delmesh_version_string(), delaunay_points(), MIN_ANGLE);
  printf("each run in its own process; %d repetitions, alternating; medians\n\n", REPETITIONS);

  typedef struct Row {
    double seconds[TOOLS], peak_mb[TOOLS];
    size_t triangles[TOOLS];
    Outcome quality[TOOLS];
    int ok;
  } Row;
  Row rows[CASES];
  int failures = 0;
  for (int c = 0; c < CASES; c++) {
    Row *row = &rows[c];
    double times[TOOLS][REPETITIONS], mems[TOOLS][REPETITIONS];
    memset(row, 0, sizeof *row);
    row->ok = 1;
    for (int rep = 0; rep < REPETITIONS; rep++)
      for (int k = 0; k < TOOLS; k++) {
        int tool = (k + rep) % TOOLS; /* rotate who goes first */
        char *args[] = {argv[0], (char *)"--child", (char *)tool_names[tool],
                        (char *)case_names[c], NULL};
        BenchRun r = bench_spawn(args);
        printf("  run %-8s rep %d %-7s: ", case_names[c], rep + 1, tool_names[tool]);
        if (!r.ok) {
          printf("FAILED\n");
          row->ok = 0;
          failures++;
          continue;
        }
        printf("%8.3f s %8.1f MB %10zu triangles\n", r.seconds, r.peak_mb, r.count);
        fflush(stdout);
        times[tool][rep] = r.seconds;
        mems[tool][rep] = r.peak_mb;
        row->triangles[tool] = r.count;
      }
    if (!row->ok) continue;
    for (int tool = 0; tool < TOOLS; tool++) {
      row->seconds[tool] = bench_median(times[tool], REPETITIONS);
      row->peak_mb[tool] = bench_median(mems[tool], REPETITIONS);
    }
    if (c == CASE_STAR || c == CASE_HOLES) {
      Pslg p;
      if (!make_input(c, &p)) {
        row->ok = 0;
        failures++;
      } else {
        for (int tool = 0; tool < TOOLS; tool++)
          if (!run(tool, c, &p, &row->quality[tool])) {
            row->ok = 0;
            failures++;
          }
      }
      pslg_free(&p);
    }
  }

  printf("\n%-8s | %-21s | %-9s | %-19s | %-9s | %-21s | %s\n", "", "seconds (median)",
         "time", "peak memory, MB", "memory", "triangles", "quality: min angle, below 25 deg");
  printf("%-8s | %10s %10s | %9s | %9s %9s | %9s | %10s %10s | %s\n", "case", "delmesh", "CGAL",
         "CGAL/ours", "delmesh", "CGAL", "CGAL/ours", "delmesh", "CGAL", "delmesh / CGAL");
  for (int c = 0; c < CASES; c++) {
    const Row *r = &rows[c];
    if (!r->ok) {
      printf("%-8s | failed\n", case_names[c]);
      continue;
    }
    printf("%-8s | %10.3f %10.3f | %9.2f | %9.1f %9.1f | %9.2f | %10zu %10zu |", case_names[c],
           r->seconds[DELMESH], r->seconds[CGAL], r->seconds[CGAL] / r->seconds[DELMESH],
           r->peak_mb[DELMESH], r->peak_mb[CGAL], r->peak_mb[CGAL] / r->peak_mb[DELMESH],
           r->triangles[DELMESH], r->triangles[CGAL]);
    if (c == CASE_DELAUNAY || c == CASE_CONFORM)
      printf(" -\n");
    else
      printf(" %.1f deg, %zu / %.1f deg, %zu\n", r->quality[DELMESH].min_angle,
             r->quality[DELMESH].below, r->quality[CGAL].min_angle, r->quality[CGAL].below);
  }
  return failures ? 1 : 0;
}
