/* delmesh_tetrahedralize_surface (and _regions, _file) beside TetGen 1.5 -p on closed surfaces:
 * generated hard cases (surfaces.h: Schönhardt's and other twisted prisms, Chazelle's polyhedra,
 * George and Borouchaki's terrain, thin slabs, nested and glued boxes, plain solids) and the
 * corpus's closed surfaces (the .off files of $DELMESH_CORPUS/surfaces and plc that its
 * MANIFEST.tsv describes "closed 2-manifold", and the .smesh files of plc: polygonal facets).
 *
 * Each input goes to TetGen with "pYQ" and "pq1.414YQ" (in a child process: TetGen 1.5.0 aborts
 * on some inputs with -Y, tetgen_child.h) and to delmesh with default options and with
 * max_radius_edge_ratio = 1.414. On every result, delmesh's and TetGen's alike (surface_check.h):
 * - validity: indices, exact positive orientation, face-to-face conformity, surface vertices used;
 * - exact boundary conformity: every input triangle is a face, and the faces between different
 *   labels (tetrahedron / outside included) are exactly the input triangles;
 * - delmesh's facets: the input triangle array itself, in order, vertex for vertex, with the
 *   labels (from, to) of the tetrahedra on each side; the input vertices first, bit for bit;
 *   vertex dimensions 2 (on an input triangle), 3 (Steiner points), -1 (input vertex no triangle
 *   uses);
 * - volume per region against the volume its surface triangles enclose, 1e-12 relative (long
 *   double, compensated sums; the rounding bound is printed beside it);
 * - regions: their number, the region seeds' labels and volume bounds, the holes left empty;
 * - no Steiner point on an input triangle (exact);
 * - quality (METRICS.md), printed: smallest dihedral angle, largest radius-edge ratio, the
 *   tetrahedra with a dihedral angle below 5, 10 and 15 degrees;
 * - with the bound 1.414: every tetrahedron whose radius-edge ratio is above it (1e-9 relative
 *   allowance) has 3 or 4 vertices on the input surface, or is forced by the surface: its
 *   circumcenter, which refinement keeping every input triangle whole must decline, lies in the
 *   diametral ball of an input triangle or edge, within the shortest input edge of an input
 *   vertex, or in no tetrahedron of its label (surface_check.h); the counts are printed; with
 *   volume bounds (region seeds, max_volume), no tetrahedron above its bound.
 * For a polygonal input delmesh's facets are its triangulated polygons: each must lie in one
 * polygon and the facets of a polygon must sum to its area (1e-12 relative); the conformity
 * checks then take those facets as the input triangles (TetGen's: its label-change faces), and
 * the total volume is compared with the polygons'. Files with a polygon that is not planar
 * (exactly) are not piecewise linear complexes: skipped, said so.
 *
 * Compared with TetGen, where its result passed the checks and kept -Y's promise: on every
 * generated case and corpus file without volume bounds, delmesh's Steiner points without
 * refinement <= TetGen's
 * with -pY (both recover the same boundary with interior points only; with refinement the counts are
 * printed, not compared); with the bound 1.414, delmesh's tetrahedron count within 20% of
 * TetGen's -pq1.414Y where TetGen met its volume bounds and made at least 100
 * tetrahedra, but on the files of tet_count_not_held (printed there). Where TetGen fails, delmesh
 * still runs and is checked, without comparison.
 *
 * TetGen's results pass the same checks (that validates the checkers), except for TetGen 1.5.0's
 * own defects with -Y, reported and not asserted: an invalid output (TetGen itself prints "BUG
 * Report! The mesh contain inverted elements."), Steiner points on its own boundary faces (only
 * its regions are asserted then), no result (a failed assert(), a crash, the time limit). Its
 * radius-edge ratios and volume bounds are printed, not asserted: with -Y it declines points that
 * would split the boundary and often stops refining early.
 *
 * Also: a self-test (the checkers pass on TetGen's icosphere and catch damaged copies); every
 * generated input closed, consistently oriented and free of self-intersections (TetGen -d);
 * invalid inputs (an open surface, two intersecting spheres, where TetGen -d must find the same
 * triangles as surfaces.c's exact test, a zero-area triangle, and the corpus's closed files in
 * which TetGen -d finds self-intersections) rejected with DELMESH_ERROR_INVALID_INPUT and a
 * message naming a culprit triangle; determinism (two runs, the same arrays). A table of Steiner
 * points (TetGen's split into those inside and those it left on the input surface), tetrahedra
 * and times closes the run.
 *
 * Usage: test_surface_vs_tetgen [--small]   (--small: corpus files of at most 5000 polygons and
 * Chazelle's polyhedra up to k = 3; otherwise at most 50000, the larger ones belong to
 * bench_surface, and k up to 8). */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "metrics.h"
#include "ref.h"
#include "surface_check.h"
#include "surface_io.h"
#include "surfaces.h"
#include "tetgen_child.h"

#include <delmesh.h>

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#define QUALITY_BOUND 1.414
#define TET_COUNT_SPREAD 0.20 /* |ours / TetGen's - 1| with the bound 1.414 */
#define MIN_COMPARED_TETS 100
#define LARGEST_FILE 50000    /* polygons; 5000 with --small */
#define LARGEST_FILE_SMALL 5000
#define TETGEN_TIME_LIMIT 10  /* seconds; TetGen 1.5.0 -Y loops without end on some Chazelle polyhedra */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- Cases -------------------------------------------------------------------------------------- */

typedef struct Case {
  char name[96];
  const double *xyz;
  size_t n;
  const uint32_t *tris; /* a triangle surface, or NULL: */
  size_t m;
  const uint32_t *corners; /* a polygonal one, read by delmesh from `path` */
  const size_t *offsets;
  size_t polygons;
  const char *path;
  const double *regions;
  size_t n_regions;
  const double *holes;
  size_t n_holes;
  int expected_regions;
  int compared; /* the Steiner comparison applies */
} Case;

enum { TETGEN_PY, TETGEN_PQ, OURS_DEFAULT, OURS_QUALITY, RUNS };
static const char *const run_names[RUNS] = {"TetGen -pY", "TetGen -pq1.414Y", "delmesh default", "delmesh q1.414"};

typedef struct Row {
  char name[96];
  size_t faces;
  int ok[RUNS];
  size_t steiner[RUNS], on_surface[RUNS], tets[RUNS]; /* on_surface: TetGen's Steiner points on its boundary */
  double seconds[RUNS];
} Row;

#define MAX_ROWS 160
static Row rows[MAX_ROWS];
static size_t row_count;

/* One run's result, whoever made it. */
typedef struct Output {
  int ok;
  char error[512];
  double seconds;
  RefSurfaceMesh tetgen;
  DelmeshMesh *mesh;
  SurfaceResult result;
  size_t above_max_volume; /* from the checks: tetrahedra above their region's volume bound */
} Output;

static void output_free(Output *o) {
  ref_surface_mesh_free(&o->tetgen);
  delmesh_mesh_free(o->mesh);
  memset(o, 0, sizeof *o);
}

static void run_tetgen(const Case *c, const char *switches, Output *o) {
  memset(o, 0, sizeof *o);
  RefTiming timing = {0};
  const uint32_t *corners = c->tris ? c->tris : c->corners;
  size_t count = c->tris ? c->m : c->polygons;
  o->ok = tetgen_child_run(c->xyz, c->n, corners, c->tris ? NULL : c->offsets, count, c->regions, c->n_regions,
                           c->holes, c->n_holes, switches, TETGEN_TIME_LIMIT, &o->tetgen, &timing, o->error,
                           sizeof o->error) == 0;
  o->seconds = timing.seconds;
  if (o->ok)
    o->result = (SurfaceResult){o->tetgen.xyz, o->tetgen.vertex_count, o->tetgen.tets, o->tetgen.labels,
                                o->tetgen.tet_count, NULL, NULL, 0};
}

static DelmeshStatus call_delmesh(const Case *c, const DelmeshSurfaceOptions *options, DelmeshMesh **mesh) {
  if (!c->tris) return delmesh_tetrahedralize_surface_file(c->path, options, mesh);
  if (c->n_regions || c->n_holes)
    return delmesh_tetrahedralize_surface_regions(c->xyz, c->n, c->tris, c->m, c->regions, c->n_regions, c->holes,
                                                  c->n_holes, options, mesh);
  return delmesh_tetrahedralize_surface(c->xyz, c->n, c->tris, c->m, options, mesh);
}

static void run_delmesh(const Case *c, double ratio, Output *o) {
  memset(o, 0, sizeof *o);
  DelmeshSurfaceOptions options;
  memset(&options, 0, sizeof options);
  options.max_radius_edge_ratio = ratio;
  double start = now();
  DelmeshStatus st = call_delmesh(c, &options, &o->mesh);
  o->seconds = now() - start;
  o->ok = st == DELMESH_OK;
  if (!o->ok) {
    snprintf(o->error, sizeof o->error, "status %d: %s", (int)st, delmesh_last_error_message());
    o->mesh = NULL;
    return;
  }
  const DelmeshMesh *m = o->mesh;
  o->result = (SurfaceResult){delmesh_mesh_vertices(m), delmesh_mesh_vertex_count(m), delmesh_mesh_tetrahedra(m),
                              delmesh_mesh_tetrahedron_labels(m), delmesh_mesh_tetrahedron_count(m),
                              delmesh_mesh_facets(m), delmesh_mesh_facet_labels(m), delmesh_mesh_facet_count(m)};
}

static int listed(const char *name, const char *const *list, size_t n) {
  for (size_t i = 0; i < n; i++)
    if (strstr(name, list[i])) return 1;
  return 0;
}

/* Corpus files on which the tetrahedron count with the bound 1.414 falls outside the spread: the
 * record of where it does not hold, printed, not asserted. On pipe neither mesher can refine (in
 * both meshes every tetrahedron above the bound is one the surface forces), so the counts compare
 * recovery alone: delmesh keeps 5 interior points there and TetGen adds 18, and the count follows
 * (0.74 of TetGen's). */
static const char *const tet_count_not_held[] = {"surfaces/pipe.off"};
static int tet_count_listed(const Case *c) {
  return listed(c->name, tet_count_not_held, sizeof tet_count_not_held / sizeof tet_count_not_held[0]);
}

static size_t steiner_of(const Case *c, const Output *o) {
  return o->result.vertex_count > c->n ? o->result.vertex_count - c->n : 0;
}

/* ---- The checks of one result ---------------------------------------------------------------------- */

/* Checks one result of case c; returns 1 when it passes. */
static int check_result(const Case *c, int run, Output *o) {
  int ours = run >= OURS_DEFAULT, quality = run == TETGEN_PQ || run == OURS_QUALITY;
  const char *what = run_names[run];
  if (!o->ok) {
    if (ours) return check_case(0, "%s | %s ran: %s", c->name, what, o->error);
    check_note("%s | %s failed: %s", c->name, what, o->error);
    return 0;
  }
  SurfaceInput in = {c->xyz, c->n, c->tris, c->m, c->regions, c->n_regions, c->holes, c->n_holes, c->expected_regions};
  SurfaceResult r = o->result;
  uint32_t *surface = NULL; /* polygonal input: the triangles covering the polygons */
  PolygonCover cover;
  memset(&cover, 0, sizeof cover);
  int covered = 1;
  double polygon_volume = NAN;
  if (!c->tris) {
    size_t count = 0;
    if (ours) {
      surface = malloc((r.facet_count ? r.facet_count : 1) * 3 * sizeof *surface);
      if (surface && r.facets) memcpy(surface, r.facets, 3 * r.facet_count * sizeof *surface);
      count = r.facets ? r.facet_count : 0;
    } else {
      surface = surface_label_change_faces(r.tets, r.labels, r.tet_count, &count);
    }
    if (!surface) return check_case(0, "%s | %s: out of memory", c->name, what);
    in.tris = surface;
    in.m = count;
    covered = surface_check_polygons(c->xyz, c->corners, c->offsets, c->polygons, surface, count, &cover);
    polygon_volume = surface_polygons_volume(c->xyz, c->corners, c->offsets, c->polygons);
  }
  SurfaceReport report;
  if (!surface_check(&in, &r, quality ? QUALITY_BOUND : 0, &report)) {
    free(surface);
    return check_case(0, "%s | %s: out of memory in the checks", c->name, what);
  }
  char text[1024];
  surface_report_describe(&report, c->expected_regions, quality, text, sizeof text);
  o->above_max_volume = report.above_max_volume;
  /* The input vertices first, bit for bit. */
  int prefix = r.vertex_count >= c->n && memcmp(r.xyz, c->xyz, 3 * c->n * sizeof *c->xyz) == 0;
  double volume_error = c->tris ? 0 : metrics_relative_error(report.volume, polygon_volume);
  int ok = surface_report_ok(&report, c->expected_regions, ours && quality, ours) && prefix && covered &&
           volume_error <= SURFACE_VOLUME_TOLERANCE;
  char extra[256] = "";
  if (!c->tris)
    snprintf(extra, sizeof extra, "; %s: %zu facets, %zu outside a polygon, %zu polygons of another area (max %.1e); volume vs polygons %.1e",
             ours ? "facets cover the polygons" : "label-change faces cover the polygons", cover.triangles,
             cover.outside, cover.polygons_off, cover.max_area_error, volume_error);
  if (!prefix) snprintf(extra + strlen(extra), sizeof extra - strlen(extra), "; the input vertices are not first, unchanged");
  if (ours && (!r.facets || !r.facet_labels) && in.m) {
    ok = 0; /* surface_check compares facets only when there are some */
    snprintf(extra + strlen(extra), sizeof extra - strlen(extra), "; NO FACETS reported");
  }
  if (ours) {
    /* Vertex dimensions: 2 for surface vertices, 3 for Steiner points and for input vertices no
     * triangle uses that are vertices of the mesh, -1 for the other input vertices. */
    const int8_t *dimensions = delmesh_mesh_vertex_dimensions(o->mesh);
    unsigned char *on = calloc(c->n ? c->n : 1, 1);
    size_t wrong = 0;
    if (on) {
      for (size_t i = 0; i < 3 * in.m; i++)
        if (in.tris[i] < c->n) on[in.tris[i]] = 1;
      for (size_t i = 0; i < 4 * r.tet_count; i++)
        if (r.tets[i] < c->n && !on[r.tets[i]]) on[r.tets[i]] = 3;
      for (size_t i = 0; i < r.vertex_count; i++) {
        int expected = i >= c->n || on[i] == 3 ? 3 : on[i] ? 2 : -1;
        if (!dimensions || dimensions[i] != expected) wrong++;
      }
    }
    free(on);
    if (wrong || !on) {
      ok = 0;
      snprintf(extra + strlen(extra), sizeof extra - strlen(extra), "; %zu vertices of the wrong dimension", wrong);
    }
  }
  if (ours) {
    ok = check_case(ok, "%s | %s: %zu tetrahedra, %.3f s: %s%s", c->name, what, r.tet_count, o->seconds, text, extra);
  } else if (!report.valid) {
    /* TetGen's own defect (1.5.0 says "BUG Report! The mesh contain inverted elements."). */
    check_note("%s | %s: TetGen's output is invalid (TetGen's defect, not asserted): %s%s", c->name, what, text, extra);
    ok = 0;
  } else if (o->tetgen.boundary_steiner > 0) {
    /* TetGen says it put Steiner points on its boundary faces (-Y did not hold): the surface
     * checks cannot pass; the others must. */
    int core = (c->expected_regions <= 0 || report.regions == c->expected_regions) && report.seeds_wrong == 0 &&
               report.holes_covered == 0 && prefix;
    ok = check_case(core,
                    "%s | %s: %zu tetrahedra, %.3f s: TetGen put %zu Steiner points on its boundary faces (-Y did not hold: "
                    "surface checks reported, not asserted; regions asserted): %s%s",
                    c->name, what, r.tet_count, o->seconds, o->tetgen.boundary_steiner, text, extra);
  } else {
    /* TetGen's quality and volume bounds are reported, not asserted: with -Y, TetGen 1.5.0 does
     * not insert a point whose insertion would split the boundary, and so often stops early. */
    ok = check_case(ok, "%s | %s: %zu tetrahedra, %.3f s: %s%s", c->name, what, r.tet_count, o->seconds, text, extra);
  }
  free(surface);
  return ok;
}

/* ---- One case ------------------------------------------------------------------------------------- */

static void run_case(const Case *c) {
  Row *row = row_count < MAX_ROWS ? &rows[row_count++] : NULL;
  if (row) {
    memset(row, 0, sizeof *row);
    snprintf(row->name, sizeof row->name, "%s", c->name);
    row->faces = c->tris ? c->m : c->polygons;
  }
  Output out[RUNS];
  run_tetgen(c, "pYQ", &out[TETGEN_PY]);
  if (!out[TETGEN_PY].ok && strstr(out[TETGEN_PY].error, "did not finish")) {
    memset(&out[TETGEN_PQ], 0, sizeof out[TETGEN_PQ]); /* it would not either: the test's time matters */
    snprintf(out[TETGEN_PQ].error, sizeof out[TETGEN_PQ].error, "not run (-pY did not finish)");
  } else {
    run_tetgen(c, "pq1.414YQ", &out[TETGEN_PQ]);
  }
  run_delmesh(c, 0, &out[OURS_DEFAULT]);
  run_delmesh(c, QUALITY_BOUND, &out[OURS_QUALITY]);
  int passed[RUNS];
  for (int k = 0; k < RUNS; k++) {
    passed[k] = check_result(c, k, &out[k]);
    if (row) {
      row->ok[k] = out[k].ok;
      row->steiner[k] = out[k].ok ? steiner_of(c, &out[k]) : 0;
      row->on_surface[k] = out[k].ok && k < OURS_DEFAULT ? out[k].tetgen.boundary_steiner : 0;
      row->tets[k] = out[k].result.tet_count;
      row->seconds[k] = out[k].seconds;
    }
  }
  /* Comparisons with TetGen's results that passed the checks and kept -Y's promise. */
  int py = passed[TETGEN_PY] && out[TETGEN_PY].tetgen.boundary_steiner == 0;
  int pq = passed[TETGEN_PQ] && out[TETGEN_PQ].tetgen.boundary_steiner == 0;
  if (out[TETGEN_PY].ok && out[OURS_DEFAULT].ok)
    check_note("%s | Steiner points: delmesh %zu (q1.414: %zu), TetGen -pY %zu (-pq1.414Y: %s)", c->name,
               steiner_of(c, &out[OURS_DEFAULT]), out[OURS_QUALITY].ok ? steiner_of(c, &out[OURS_QUALITY]) : 0,
               steiner_of(c, &out[TETGEN_PY]), out[TETGEN_PQ].ok ? "ok" : "failed");
  if (c->compared && py && out[OURS_DEFAULT].ok) {
    size_t ours = steiner_of(c, &out[OURS_DEFAULT]), theirs = steiner_of(c, &out[TETGEN_PY]);
    check_case(ours <= theirs, "%s | Steiner points without refinement: delmesh %zu <= TetGen -pY %zu", c->name, ours,
               theirs);
  }
  /* Tetrahedron counts are compared where TetGen met its volume bounds (-Y often stops short of
   * them) and made at least MIN_COMPARED_TETS (below that, triangulations of the same points
   * differ by more than the spread: the icosahedron has 15 or 20 tetrahedra without a point). */
  if (pq && out[OURS_QUALITY].ok && out[TETGEN_PQ].above_max_volume == 0 &&
      out[TETGEN_PQ].result.tet_count >= MIN_COMPARED_TETS) {
    double ratio = (double)out[OURS_QUALITY].result.tet_count / (double)out[TETGEN_PQ].result.tet_count;
    if (tet_count_listed(c))
      check_note("%s | tetrahedra with the bound 1.414: delmesh %zu, TetGen -pq1.414Y %zu: ratio %.3f (not asserted: "
                 "listed in tet_count_not_held)",
                 c->name, out[OURS_QUALITY].result.tet_count, out[TETGEN_PQ].result.tet_count, ratio);
    else
      check_case(fabs(ratio - 1) <= TET_COUNT_SPREAD,
                 "%s | tetrahedra with the bound 1.414: delmesh %zu, TetGen -pq1.414Y %zu: ratio %.3f within 1 +- %g",
                 c->name, out[OURS_QUALITY].result.tet_count, out[TETGEN_PQ].result.tet_count, ratio,
                 TET_COUNT_SPREAD);
  }
  for (int k = 0; k < RUNS; k++) output_free(&out[k]);
}

/* Whether a region seed (x, y, z, label, max volume) bounds volumes: those refine, and the
 * Steiner comparison is for recovery alone. */
static int volume_bounds(const double *regions, size_t n_regions) {
  for (size_t r = 0; r < n_regions; r++)
    if (regions[5 * r + 4] > 0) return 1;
  return 0;
}

static Case case_of_surface(const Surface *s, int generated) {
  Case c;
  memset(&c, 0, sizeof c);
  snprintf(c.name, sizeof c.name, "%s", s->name);
  c.xyz = s->xyz, c.n = s->n, c.tris = s->tris, c.m = s->m;
  c.regions = s->regions, c.n_regions = s->n_regions, c.holes = s->holes, c.n_holes = s->n_holes;
  c.expected_regions = s->expected_regions;
  c.compared = generated && !volume_bounds(s->regions, s->n_regions);
  return c;
}

/* ---- Self-test of the checkers --------------------------------------------------------------------- */

static void self_test(void) {
  Surface s;
  if (!surface_icosphere(&s, 2)) {
    check_case(0, "self-test: out of memory");
    return;
  }
  Case c = case_of_surface(&s, 0);
  Output o;
  run_tetgen(&c, "pq1.414YQ", &o);
  if (!check_case(o.ok && o.tetgen.steiner_count > 0, "self-test: TetGen -pq1.414Y meshed the level-2 icosphere with Steiner points%s%s",
                  o.ok ? "" : ": ", o.ok ? "" : o.error)) {
    output_free(&o);
    surface_free(&s);
    return;
  }
  SurfaceInput in = {s.xyz, s.n, s.tris, s.m, NULL, 0, NULL, 0, 1};
  size_t nt = o.tetgen.tet_count, nv = o.tetgen.vertex_count;
  /* Facets as delmesh reports them: the input triangles (outward), region 1 inside. */
  int32_t *facet_labels = malloc(2 * s.m * sizeof *facet_labels);
  uint32_t *facets = malloc(3 * s.m * sizeof *facets);
  uint32_t *tets = malloc(4 * nt * sizeof *tets);
  int32_t *labels = malloc(nt * sizeof *labels);
  double *xyz = malloc(3 * nv * sizeof *xyz);
  if (!facet_labels || !facets || !tets || !labels || !xyz) {
    check_case(0, "self-test: out of memory");
  } else {
    for (size_t t = 0; t < s.m; t++) facet_labels[2 * t] = 1, facet_labels[2 * t + 1] = 0;
    SurfaceReport r;
    char text[1024];
    /* Each damage is made to fresh copies. */
    enum { CLEAN, FLIPPED, REMOVED, RELABELED, ON_SURFACE, FACETS_SWAPPED, FACET_LABEL, DAMAGES };
    static const char *const what[DAMAGES] = {
        "TetGen's mesh passes every check (facets = input triangles, labels (1, 0))",
        "a tetrahedron with two vertices swapped is invalid",
        "a tetrahedron with a surface face removed: a triangle missing and the volume off",
        "a tetrahedron relabeled 2: two regions and label-change faces inside",
        "a Steiner point moved onto an input vertex is on the surface",
        "two facets swapped are misplaced",
        "a facet with its labels swapped is mislabeled"};
    /* A tetrahedron with a face on the surface, and the first Steiner point. */
    size_t boundary_tet = 0;
    for (size_t t = 0; t < nt && boundary_tet == 0; t++) {
      int on = 0;
      for (int k = 0; k < 4; k++) on += o.tetgen.tets[4 * t + k] < s.n;
      if (on >= 3) boundary_tet = t + 1;
    }
    for (int d = 0; d < DAMAGES; d++) {
      memcpy(tets, o.tetgen.tets, 4 * nt * sizeof *tets);
      memcpy(labels, o.tetgen.labels, nt * sizeof *labels);
      memcpy(xyz, o.tetgen.xyz, 3 * nv * sizeof *xyz);
      memcpy(facets, s.tris, 3 * s.m * sizeof *facets);
      for (size_t t = 0; t < s.m; t++) facet_labels[2 * t] = 1, facet_labels[2 * t + 1] = 0;
      size_t count = nt;
      if (d == FLIPPED) {
        uint32_t x = tets[0];
        tets[0] = tets[1];
        tets[1] = x;
      } else if (d == REMOVED && boundary_tet) {
        memmove(tets + 4 * (boundary_tet - 1), tets + 4 * boundary_tet, 4 * (nt - boundary_tet) * sizeof *tets);
        memmove(labels + (boundary_tet - 1), labels + boundary_tet, (nt - boundary_tet) * sizeof *labels);
        count--;
      } else if (d == RELABELED) {
        labels[nt / 2] = 2;
      } else if (d == ON_SURFACE) {
        memcpy(xyz + 3 * s.n, s.xyz, 3 * sizeof *xyz);
      } else if (d == FACETS_SWAPPED) {
        uint32_t t3[3];
        memcpy(t3, facets, sizeof t3);
        memcpy(facets, facets + 3, sizeof t3);
        memcpy(facets + 3, t3, sizeof t3);
      } else if (d == FACET_LABEL) {
        facet_labels[4] = 0, facet_labels[5] = 1;
      }
      SurfaceResult res = {xyz, nv, tets, labels, count, facets, facet_labels, s.m};
      int computed = surface_check(&in, &res, QUALITY_BOUND, &r);
      surface_report_describe(&r, 1, 0, text, sizeof text);
      int caught;
      switch (d) {
        case CLEAN: caught = surface_report_ok(&r, 1, 0, 1); break;
        case FLIPPED: caught = !r.valid; break;
        case REMOVED: caught = boundary_tet && r.missing >= 1 && r.volume_error > SURFACE_VOLUME_TOLERANCE; break;
        case RELABELED: caught = r.regions == 2 && r.extra > 0; break;
        case ON_SURFACE: caught = r.surface_steiner == 1; break;
        case FACETS_SWAPPED: caught = r.facets_misplaced == 2 && r.facets_mislabeled == 0; break;
        default: caught = r.facets_mislabeled == 1 && r.facets_misplaced == 0; break;
      }
      check_case(computed && caught, "self-test: %s: %s", what[d], text);
    }
    /* The polygon cover: the icosphere's triangles cover themselves; one dropped does not. */
    PolygonCover cover;
    size_t offsets_count = s.m + 1;
    size_t *offsets = malloc(offsets_count * sizeof *offsets);
    if (offsets) {
      for (size_t f = 0; f <= s.m; f++) offsets[f] = 3 * f;
      int whole = surface_check_polygons(s.xyz, s.tris, offsets, s.m, s.tris, s.m, &cover);
      int partial = surface_check_polygons(s.xyz, s.tris, offsets, s.m, s.tris, s.m - 1, &cover);
      check_case(whole && !partial && cover.polygons_off == 1,
                 "self-test: the polygon cover check accepts the triangles themselves and misses one dropped");
      free(offsets);
    }
  }
  free(facet_labels);
  free(facets);
  free(tets);
  free(labels);
  free(xyz);
  output_free(&o);
  surface_free(&s);
}

/* ---- Invalid inputs ---------------------------------------------------------------------------------- */

/* Whether `message` contains one of the culprits as a whole number. */
static int names_culprit(const char *message, const uint32_t *culprits, size_t count) {
  for (const char *p = message; *p;) {
    if (!isdigit((unsigned char)*p)) {
      p++;
      continue;
    }
    char *end;
    unsigned long long v = strtoull(p, &end, 10);
    /* Not part of a word or of a decimal number ("triangle 13." is fine, "0.13" is not). */
    int whole = (p == message || (!isalnum((unsigned char)p[-1]) && p[-1] != '.')) &&
                !(*end == '.' && isdigit((unsigned char)end[1])) && !isalpha((unsigned char)*end);
    for (size_t i = 0; whole && i < count; i++)
      if (v == culprits[i]) return 1;
    p = end;
  }
  return 0;
}

/* delmesh must refuse the surface with DELMESH_ERROR_INVALID_INPUT, naming a culprit. */
static void expect_invalid(const char *name, const char *defect, const double *xyz, size_t n, const uint32_t *tris,
                           size_t m, const uint32_t *culprit, size_t culprit_count) {
  SurfaceEdges e;
  surface_edges(tris, m, n, &e);
  DelmeshMesh *mesh = NULL;
  DelmeshStatus st = delmesh_tetrahedralize_surface(xyz, n, tris, m, NULL, &mesh);
  const char *message = delmesh_last_error_message();
  char list[160];
  size_t len = 0;
  list[0] = '\0';
  for (size_t i = 0; i < culprit_count && len < sizeof list - 16; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%u", i ? " " : "", culprit[i]);
  if (culprit_count > 12) snprintf(list + len, sizeof list - len, " ... (%zu)", culprit_count);
  check_case(st == DELMESH_ERROR_INVALID_INPUT && names_culprit(message, culprit, culprit_count),
             "invalid input, %s (%s; %zu triangles, %zu open edges): status %d (expected %d), message \"%s\" names one of the triangles {%s}",
             name, defect, m, e.open, (int)st, (int)DELMESH_ERROR_INVALID_INPUT, message, list);
  delmesh_mesh_free(mesh);
}

static void invalid_case(int (*make)(Surface *)) {
  Surface s;
  if (!make(&s)) {
    check_case(0, "invalid input: out of memory");
    return;
  }
  if (strcmp(s.defect, "self-intersecting") == 0) {
    /* TetGen -d on the same surface: the triangles it finds intersecting, beside ours. */
    uint32_t *found = NULL;
    size_t count = 0;
    char error[512];
    if (tetgen_child_intersections(s.xyz, s.n, s.tris, s.m, TETGEN_TIME_LIMIT, &found, &count, error, sizeof error) == 0) {
      size_t common = 0;
      for (size_t i = 0, j = 0; i < count && j < s.culprit_count;)
        if (found[i] == s.culprits[j])
          common++, i++, j++;
        else if (found[i] < s.culprits[j])
          i++;
        else
          j++;
      check_case(count == s.culprit_count && common == count,
                 "%s: TetGen -d finds the same %zu intersecting triangles as surfaces.c's exact test (%zu; %zu common)",
                 s.name, count, s.culprit_count, common);
    } else {
      check_note("%s: TetGen -d failed: %s", s.name, error);
    }
    free(found);
  }
  expect_invalid(s.name, s.defect, s.xyz, s.n, s.tris, s.m, s.culprits, s.culprit_count);
  surface_free(&s);
}

/* ---- Determinism ---------------------------------------------------------------------------------------- */

static int same_array(const void *a, const void *b, size_t bytes) {
  return bytes == 0 || (a && b && memcmp(a, b, bytes) == 0);
}

static void determinism(const Surface *s, double ratio) {
  Case c = case_of_surface(s, 0);
  Output a, b;
  run_delmesh(&c, ratio, &a);
  run_delmesh(&c, ratio, &b);
  int same = a.ok && b.ok;
  if (same) {
    const DelmeshMesh *x = a.mesh, *y = b.mesh;
    size_t nv = delmesh_mesh_vertex_count(x), nt = delmesh_mesh_tetrahedron_count(x), nf = delmesh_mesh_facet_count(x);
    same = nv == delmesh_mesh_vertex_count(y) && nt == delmesh_mesh_tetrahedron_count(y) &&
           nf == delmesh_mesh_facet_count(y) &&
           same_array(delmesh_mesh_vertices(x), delmesh_mesh_vertices(y), 3 * nv * sizeof(double)) &&
           same_array(delmesh_mesh_tetrahedra(x), delmesh_mesh_tetrahedra(y), 4 * nt * sizeof(uint32_t)) &&
           same_array(delmesh_mesh_tetrahedron_labels(x), delmesh_mesh_tetrahedron_labels(y), nt * sizeof(int32_t)) &&
           same_array(delmesh_mesh_facets(x), delmesh_mesh_facets(y), 3 * nf * sizeof(uint32_t)) &&
           same_array(delmesh_mesh_facet_labels(x), delmesh_mesh_facet_labels(y), 2 * nf * sizeof(int32_t));
  }
  check_case(same, "determinism, %s, %s: two runs give the same vertices, tetrahedra, labels and facets%s%s", s->name,
             ratio > 0 ? "bound 1.414" : "default options", a.ok && b.ok ? "" : ": ", a.ok ? (b.ok ? "" : b.error) : a.error);
  output_free(&a);
  output_free(&b);
}

/* ---- The corpus ------------------------------------------------------------------------------------------ */

/* Whether the manifest's description says "closed 2-manifold" (any case, not "NOT closed"). */
static int closed_manifold(const char *description) {
  for (const char *p = description; *p; p++)
    if (strncasecmp(p, "closed 2-manifold", 17) == 0) return 1;
  return 0;
}

static void corpus_cases(int small) {
  const char *corpus = getenv("DELMESH_CORPUS");
  char path[4096];
  snprintf(path, sizeof path, "%s/MANIFEST.tsv", corpus && corpus[0] ? corpus : ".");
  FILE *manifest = corpus && corpus[0] ? fopen(path, "r") : NULL;
  if (!manifest) {
    check_note("corpus cases skipped: %s", corpus && corpus[0] ? "no MANIFEST.tsv in $DELMESH_CORPUS" : "DELMESH_CORPUS is not set");
    return;
  }
  char *line = NULL;
  size_t capacity = 0;
  size_t limit = small ? LARGEST_FILE_SMALL : LARGEST_FILE;
  while (getline(&line, &capacity, manifest) >= 0) {
    char *tab = strchr(line, '\t'), *description = strrchr(line, '\t');
    if (!tab || !description) continue;
    *tab = '\0';
    const char *file = line, *slash = strchr(file, '/');
    const char *dot = strrchr(file, '.');
    int surfaces = strncmp(file, "surfaces/", 9) == 0, plc = strncmp(file, "plc/", 4) == 0;
    if (!slash || strchr(slash + 1, '/') || !dot || (!surfaces && !plc)) continue; /* one level only */
    int off = strcmp(dot, ".off") == 0, smesh = strcmp(dot, ".smesh") == 0;
    if (!(off || (plc && smesh)) || !closed_manifold(description + 1)) continue;
    snprintf(path, sizeof path, "%s/%s", corpus, file);
    SurfaceFile f;
    char error[512];
    if (!surface_file_read(path, &f, error, sizeof error)) {
      check_case(0, "corpus %s: read: %s", file, error);
      continue;
    }
    size_t nonplanar = f.all_triangles ? 0 : surface_polygons_nonplanar(f.xyz, f.corners, f.offsets, f.polygon_count);
    if (nonplanar) {
      check_note("corpus %s: %zu of its %zu polygons are not planar (exactly): not a piecewise linear complex, skipped",
                 file, nonplanar, f.polygon_count);
      surface_file_free(&f);
      continue;
    }
    if (f.polygon_count > limit) {
      check_note("corpus %s: %zu polygons > %zu: left to bench_surface", file, f.polygon_count, limit);
      surface_file_free(&f);
      continue;
    }
    if (f.all_triangles && off) {
      /* A file can be a closed 2-manifold and still intersect itself: then it is an invalid input. */
      uint32_t *found = NULL;
      size_t count = 0;
      if (tetgen_child_intersections(f.xyz, f.n, f.corners, f.polygon_count, TETGEN_TIME_LIMIT, &found, &count, error,
                                     sizeof error) != 0) {
        check_note("corpus %s: TetGen -d failed (%s): taken as valid", file, error);
      } else if (count > 0) {
        check_note("corpus %s: TetGen -d finds %zu triangles intersecting others: an invalid input", file, count);
        expect_invalid(file, "self-intersecting (TetGen -d)", f.xyz, f.n, f.corners, f.polygon_count, found, count);
        free(found);
        surface_file_free(&f);
        continue;
      }
      free(found);
    }
    Case c;
    memset(&c, 0, sizeof c);
    snprintf(c.name, sizeof c.name, "%s", file);
    c.xyz = f.xyz, c.n = f.n;
    if (f.all_triangles && off) {
      c.tris = f.corners, c.m = f.polygon_count;
    } else {
      c.corners = f.corners, c.offsets = f.offsets, c.polygons = f.polygon_count, c.path = path;
    }
    c.regions = f.regions, c.n_regions = f.n_regions, c.holes = f.holes, c.n_holes = f.n_holes;
    c.expected_regions = 1; /* every closed file of the corpus is one connected solid */
    c.compared = !volume_bounds(f.regions, f.n_regions);
    run_case(&c);
    surface_file_free(&f);
  }
  free(line);
  fclose(manifest);
}

/* ---- Table ------------------------------------------------------------------------------------------------- */

static void print_table(void) {
  printf("\n%-34s %6s | %-15s | %-15s | %-17s | %-17s | %-13s | %-13s\n", "", "", "TetGen Steiner", "ours Steiner",
         "tets ours/TetGen", "tets ours/TetGen", "TetGen s", "ours s");
  printf("%-34s %6s | %7s %7s | %7s %7s | %17s | %17s | %6s %6s | %6s %6s\n", "case", "faces", "pY", "pq1.414", "default",
         "q1.414", "default / pY", "q1.414 / pq1.414", "pY", "pq", "dflt", "q");
  char cell[RUNS][48];
  for (size_t i = 0; i < row_count; i++) {
    const Row *r = &rows[i];
    for (int k = 0; k < RUNS; k++) {
      if (r->ok[k] && r->on_surface[k] > 0)
        snprintf(cell[k], sizeof cell[k], "%zu+%zus", r->steiner[k] - r->on_surface[k], r->on_surface[k]);
      else if (r->ok[k])
        snprintf(cell[k], sizeof cell[k], "%zu", r->steiner[k]);
      else
        snprintf(cell[k], sizeof cell[k], "fail");
    }
    char t1[32], t2[32];
    snprintf(t1, sizeof t1, "%zu/%zu", r->tets[OURS_DEFAULT], r->tets[TETGEN_PY]);
    snprintf(t2, sizeof t2, "%zu/%zu", r->tets[OURS_QUALITY], r->tets[TETGEN_PQ]);
    printf("%-34.34s %6zu | %7s %7s | %7s %7s | %17s | %17s | %6.3f %6.3f | %6.3f %6.3f\n", r->name, r->faces,
           cell[TETGEN_PY], cell[TETGEN_PQ], cell[OURS_DEFAULT], cell[OURS_QUALITY], t1, t2, r->seconds[TETGEN_PY],
           r->seconds[TETGEN_PQ], r->seconds[OURS_DEFAULT], r->seconds[OURS_QUALITY]);
  }
  printf("a+bs: a Steiner points inside, b on the input surface (TetGen's -Y did not hold there)\n\n");
  fflush(stdout);
}

/* ---- Main ------------------------------------------------------------------------------------------------- */

static void generated_case(int ok, Surface *s) {
  if (!ok) {
    check_case(0, "generating a surface: out of memory");
    return;
  }
  SurfaceEdges e;
  int closed = surface_edges(s->tris, s->m, s->n, &e);
  uint32_t *found = NULL;
  size_t found_count = 0;
  char error[512] = "";
  int checked = tetgen_child_intersections(s->xyz, s->n, s->tris, s->m, TETGEN_TIME_LIMIT, &found, &found_count, error,
                                           sizeof error) == 0;
  free(found);
  check_case(closed && e.misoriented == 0 && checked && found_count == 0,
             "%s: input of %zu vertices, %zu triangles: closed (%zu edges, %zu in 3+ triangles), consistently oriented, "
             "no self-intersection (TetGen -d: %s)",
             s->name, s->n, s->m, e.edges, e.nonmanifold, checked ? (found_count ? "some" : "none") : error);
  Case c = case_of_surface(s, 1);
  run_case(&c);
  surface_free(s);
}

/* Whether vertex v is a corner of one of the `count` tetrahedra `tets`. */
static int referenced(const uint32_t *tets, size_t count, uint32_t v) {
  for (size_t i = 0; i < 4 * count; i++)
    if (tets[i] == v) return 1;
  return 0;
}

/* Vertices no triangle uses (TetGen's .node semantics): the generic checks and comparisons of
 * run_case, then each node inside the cube must be a vertex of both meshes (dimension 3 in
 * ours) and each node outside of neither (dimension -1). */
static void isolated_nodes(void) {
  Surface s;
  size_t inside = 0;
  if (!surface_cube_with_nodes(&s, &inside)) {
    check_case(0, "generating the cube with nodes: out of memory");
    return;
  }
  Case c = case_of_surface(&s, 1);
  run_case(&c);
  for (int quality = 0; quality < 2; quality++) {
    Output ours, theirs;
    run_delmesh(&c, quality ? 1.414 : 0, &ours);
    run_tetgen(&c, quality ? "pq1.414YQ" : "pYQ", &theirs);
    size_t right_ours = 0, right_theirs = 0;
    const int8_t *dims = ours.ok ? delmesh_mesh_vertex_dimensions(ours.mesh) : NULL;
    for (uint32_t v = 8; v < s.n; v++) {
      int in = v < 8 + inside;
      if (ours.ok && referenced(ours.result.tets, ours.result.tet_count, v) == in && dims[v] == (in ? 3 : -1))
        right_ours++;
      if (theirs.ok && referenced(theirs.result.tets, theirs.result.tet_count, v) == in) right_theirs++;
    }
    check_case(ours.ok && right_ours == s.n - 8,
               "%s, %s: %zu of %zu nodes meshed exactly when inside (TetGen %s: %zu)", s.name,
               quality ? "q1.414" : "default", right_ours, s.n - 8, quality ? "-pq1.414Y" : "-pY", right_theirs);
    output_free(&ours);
    output_free(&theirs);
  }
  surface_free(&s);
}

/* Sum of the volumes of `count` tetrahedra, and the number of distinct labels. */
static double total_volume(const double *xyz, const uint32_t *tets, size_t count) {
  long double sum = 0;
  for (size_t t = 0; t < count; t++) {
    const double *p[4];
    for (int k = 0; k < 4; k++) p[k] = xyz + 3 * (size_t)tets[4 * t + k];
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) u[k] = p[1][k] - p[0][k], v[k] = p[2][k] - p[0][k], w[k] = p[3][k] - p[0][k];
    sum += (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
  }
  return (double)sum;
}

static size_t distinct_labels(const int32_t *labels, size_t count) {
  size_t distinct = 0;
  for (size_t t = 0; t < count; t++) {
    size_t u = 0;
    while (u < t && labels[u] != labels[t]) u++;
    distinct += u == t;
  }
  return distinct;
}

/* keep_convex_hull against TetGen -pcY on one triangle surface: both valid, the same total
 * volume (the hull's, 1e-12 relative), the input triangles our facets, one label more than
 * without the hull when the surface is not convex; tetrahedra and added points printed. */
static void convex_hull_case(const char *name, const double *xyz, size_t n, const uint32_t *tris, size_t m) {
  DelmeshSurfaceOptions options;
  memset(&options, 0, sizeof options);
  DelmeshMesh *plain = NULL, *mesh = NULL;
  DelmeshStatus s0 = delmesh_tetrahedralize_surface(xyz, n, tris, m, &options, &plain);
  options.keep_convex_hull = 1;
  double start = now();
  DelmeshStatus s1 = delmesh_tetrahedralize_surface(xyz, n, tris, m, &options, &mesh);
  double seconds = now() - start;
  RefSurfaceMesh ref;
  RefTiming timing = {0};
  char error[512] = "";
  memset(&ref, 0, sizeof ref);
  int theirs = tetgen_child_run(xyz, n, tris, NULL, m, NULL, 0, NULL, 0, "pcYQ", TETGEN_TIME_LIMIT, &ref, &timing, error,
                                sizeof error) == 0;
  if (s1 != DELMESH_OK || s0 != DELMESH_OK || !theirs) {
    check_case(s1 == DELMESH_OK,
               "%s, keep_convex_hull: delmesh status %d (%s), without the hull %d; TetGen -pcY %s", name, (int)s1,
               s1 == DELMESH_OK ? "ok" : delmesh_last_error_message(), (int)s0, theirs ? "ok" : error);
  } else {
    size_t nv = delmesh_mesh_vertex_count(mesh), nt = delmesh_mesh_tetrahedron_count(mesh);
    const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
    unsigned char *expect = malloc(nv);
    Validity v;
    int valid = 0;
    if (expect) {
      memset(expect, VERTEX_MAY_BE_UNUSED, nv);
      valid = metrics_validity(delmesh_mesh_vertices(mesh), nv, tets, nt, expect, NULL, 0, &v);
      free(expect);
    }
    double ours = total_volume(delmesh_mesh_vertices(mesh), tets, nt);
    double hull = total_volume(ref.xyz, ref.tets, ref.tet_count);
    int facets = delmesh_mesh_facet_count(mesh) == m && memcmp(delmesh_mesh_facets(mesh), tris, 3 * m * sizeof *tris) == 0;
    double without = total_volume(delmesh_mesh_vertices(plain), delmesh_mesh_tetrahedra(plain),
                                  delmesh_mesh_tetrahedron_count(plain));
    size_t labels = distinct_labels(delmesh_mesh_tetrahedron_labels(mesh), nt);
    size_t plain_labels = distinct_labels(delmesh_mesh_tetrahedron_labels(plain), delmesh_mesh_tetrahedron_count(plain));
    int convex = fabs(without - hull) <= 1e-12 * hull;
    check_case(valid && facets && fabs(ours - hull) <= 1e-12 * hull && labels == plain_labels + (convex ? 0 : 1),
               "%s, keep_convex_hull: valid, facets = input, volume %.15g vs TetGen -pcY %.15g, %zu labels (%zu without "
               "the hull); tetrahedra %zu vs %zu, points added %zu vs %zu, %.3f s vs %.3f s",
               name, ours, hull, labels, plain_labels, nt, ref.tet_count, nv - n, ref.vertex_count - n, seconds,
               timing.seconds);
  }
  delmesh_mesh_free(plain);
  delmesh_mesh_free(mesh);
  ref_surface_mesh_free(&ref);
}

static void convex_hull_cases(void) {
  Surface s;
  if (surface_terrain(&s, 20)) {
    convex_hull_case(s.name, s.xyz, s.n, s.tris, s.m);
    surface_free(&s);
  }
  if (surface_nested_cubes(&s, 0)) {
    convex_hull_case(s.name, s.xyz, s.n, s.tris, s.m);
    surface_free(&s);
  }
  const char *corpus = getenv("DELMESH_CORPUS");
  static const char *const files[] = {"surfaces/knot.off", "surfaces/eight.off", "surfaces/elephant.off",
                                      "surfaces/handle.off"};
  for (size_t i = 0; corpus && corpus[0] && i < sizeof files / sizeof files[0]; i++) {
    char path[4096], error[512];
    snprintf(path, sizeof path, "%s/%s", corpus, files[i]);
    SurfaceFile f;
    if (!surface_file_read(path, &f, error, sizeof error)) {
      check_note("%s: not read (%s), skipped", files[i], error);
      continue;
    }
    if (f.all_triangles) convex_hull_case(files[i], f.xyz, f.n, f.corners, f.polygon_count);
    surface_file_free(&f);
  }
}

int main(int argc, char **argv) {
  if (argc > 2 || (argc == 2 && strcmp(argv[1], "--small") != 0)) {
    fprintf(stderr, "usage: %s [--small]\n", argv[0]);
    return 2;
  }
  int small = argc == 2;
  self_test();

  Surface s;
  generated_case(surface_cube(&s), &s);
  generated_case(surface_octahedron(&s), &s);
  generated_case(surface_icosphere(&s, 2), &s);
  static const double twists[] = {10, 20, 30, 40, 50};
  for (size_t i = 0; i < sizeof twists / sizeof twists[0]; i++) generated_case(surface_twisted_prism(&s, twists[i]), &s);
  /* k = 2..8, 4 to 16 notches: TetGen -pY meshes k = 2, leaves points on its boundary at k = 3 and 4,
   * returns an invalid mesh at 5 (inverted tetrahedra) and fails from 6 on (assertion, endless
   * loop); delmesh meshes every k. Under --small
   * (the sanitized run) k stops at 3: larger ones pass the C API nothing new, and took 9 of its
   * 14 minutes (ASan's allocator slows recovery, which allocates much, more than twofold). */
  for (int k = 2; k <= (small ? 3 : 8); k++) generated_case(surface_chazelle(&s, k), &s);
  generated_case(surface_terrain(&s, 20), &s);
  generated_case(surface_slab(&s, 1), &s);
  generated_case(surface_slab(&s, 10), &s);
  for (int v = 0; v < 4; v++) generated_case(surface_nested_cubes(&s, v), &s);
  generated_case(surface_glued_boxes(&s), &s);
  generated_case(surface_edge_cubes(&s), &s);
  isolated_nodes();
  convex_hull_cases();

  invalid_case(surface_open_cube);
  invalid_case(surface_intersecting_spheres);
  invalid_case(surface_zero_area);

  if (surface_twisted_prism(&s, 30)) {
    determinism(&s, 0);
    surface_free(&s);
  }
  if (surface_terrain(&s, 20)) {
    determinism(&s, 0);
    surface_free(&s);
  }

  corpus_cases(small);
  print_table();
  return check_finish();
}
