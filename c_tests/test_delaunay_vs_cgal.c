/* delmesh_delaunay_tetrahedralize against CGAL's Delaunay_triangulation_3 and TetGen, through
 * the C API (METRICS.md "Validity", "Volume"):
 * - random points (10^3, 10^4, 10^5): the same set of finite tetrahedra as CGAL and as TetGen;
 * - degenerate inputs (integer grids, cospherical integer points, coplanar layers, duplicates):
 *   the same number of tetrahedra as CGAL, the same set (both perturb symbolically in
 *   lexicographic order), and the volume of the convex hull;
 * - every result valid: exact orientation, conformity, boundary on the hull, every distinct
 *   point used, duplicates unused and reported.
 * - the vertices of real surfaces (fandisk, anchor, elephant from $DELMESH_CORPUS/surfaces; the
 *   cases say so and are skipped when it is not set or the files are missing).
 * Usage: test_delaunay_vs_cgal [--small]   (--small: the sanitizer sizes) */
#include "check.h"
#include "compare.h"
#include "metrics.h"
#include "points.h"
#include "prng.h"
#include "ref.h"

#include <delmesh.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VOLUME_TOLERANCE 1e-12

/* ---- The checker checks itself first: a test of an invalid mesh must fail. ------------------ */

/* Exact sign of the orientation determinant in 64-bit integers. Valid when the differences
 * b-a, c-a stay below 2^19 and d-a below 2^21 in magnitude: each of the six products is then
 * below 2^59 and their sum below 2^63. */
static int orient_int64(const int64_t a[3], const int64_t b[3], const int64_t c[3], const int64_t d[3]) {
  int64_t u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
  int64_t det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                u[2] * (v[0] * w[1] - v[1] * w[0]);
  return (det > 0) - (det < 0);
}

static void self_test_orientation(void) {
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
  const double p[3] = {0.25, 0.5, 0}; /* in the plane z = 0 */
  check_case(ref_orient3d_exact(o, x, y, z) == 1 && ref_orient3d_exact(o, y, x, z) == -1 &&
                 ref_orient3d_exact(o, x, y, p) == 0,
             "exact orient3d: unit tetrahedron +1, swapped -1, coplanar 0 (API.md convention)");

  /* Coplanar and nearly coplanar integer quadruples: d = a + s(b-a) + t(c-a) + e with e = 0 or a
   * unit offset, so the determinant is 0 or small against products near 2^59, where plain double
   * evaluation rounds (its errors are counted for information). */
  Prng g = prng_new(0x0123456789abcdefu);
  const int64_t range = (int64_t)1 << 19; /* coordinates in [-2^18, 2^18): products near 2^59 */
  size_t cases = 2000, wrong = 0, double_wrong = 0;
  for (size_t i = 0; i < cases; i++) {
    int64_t a[3], b[3], c[3], d[3];
    int64_t s = (int64_t)prng_below(&g, 3) - 1, t = (int64_t)prng_below(&g, 3) - 1;
    int64_t offset = (int64_t)(i % 2); /* every other quadruple exactly coplanar */
    for (int k = 0; k < 3; k++) {
      a[k] = (int64_t)prng_below(&g, (uint64_t)range) - range / 2;
      b[k] = (int64_t)prng_below(&g, (uint64_t)range) - range / 2;
      c[k] = (int64_t)prng_below(&g, (uint64_t)range) - range / 2;
      d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]) + offset * ((int64_t)prng_below(&g, 3) - 1);
    }
    double ad[3], bd[3], cd[3], dd[3];
    for (int k = 0; k < 3; k++) ad[k] = (double)a[k], bd[k] = (double)b[k], cd[k] = (double)c[k], dd[k] = (double)d[k];
    int exact = orient_int64(a, b, c, d);
    if (ref_orient3d_exact(ad, bd, cd, dd) != exact) wrong++;
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) u[k] = bd[k] - ad[k], v[k] = cd[k] - ad[k], w[k] = dd[k] - ad[k];
    double det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0]);
    if (((det > 0) - (det < 0)) != exact) double_wrong++;
  }
  check_case(wrong == 0,
             "exact orient3d agrees with 64-bit integer arithmetic on %zu coplanar or nearly coplanar quadruples (%zu wrong; naive double: %zu wrong)",
             cases, wrong, double_wrong);
}

/* The validity check accepts CGAL's triangulation and rejects damaged copies of it. */
static void self_test_validity(void) {
  const size_t n = 1000;
  double *xyz = points_uniform_cube(n, 0x5e1f7e57u);
  uint32_t *tets = NULL, *hull = NULL;
  size_t count = 0, hull_count = 0;
  double hull_volume = 0;
  if (!xyz || ref_cgal_delaunay(xyz, n, &tets, &count, NULL) != 0 ||
      !compare_convex_hull("self-test", xyz, n, &hull, &hull_count, &hull_volume)) {
    check_case(0, "self-test: reference triangulation failed: %s", ref_last_error());
    free(xyz);
    free(tets);
    return;
  }
  Validity v;
  char text[256];
  int ok = metrics_validity(xyz, n, tets, count, NULL, hull, hull_count, &v);
  metrics_validity_describe(&v, text, sizeof text);
  check_case(ok, "self-test: CGAL's triangulation of %zu points passes the validity check: %s", n, text);
  check_case(metrics_relative_error(metrics_tetrahedra_volume(xyz, tets, count), hull_volume) <= VOLUME_TOLERANCE,
             "self-test: CGAL's tetrahedra fill the hull of convex_hull_3 (volume)");

  uint32_t *damaged = malloc((count + 1) * 4 * sizeof *damaged);
  if (!damaged) {
    check_case(0, "self-test: out of memory");
  } else {
    /* 1. one tetrahedron reversed */
    memcpy(damaged, tets, count * 4 * sizeof *damaged);
    uint32_t tmp = damaged[4 * 7];
    damaged[4 * 7] = damaged[4 * 7 + 1];
    damaged[4 * 7 + 1] = tmp;
    ok = metrics_validity(xyz, n, damaged, count, NULL, hull, hull_count, &v);
    check_case(!ok && v.not_positive == 1, "self-test: a reversed tetrahedron is caught (%zu not positive)", v.not_positive);
    /* 2. one tetrahedron missing: a hole whose facets are not on the hull */
    memcpy(damaged, tets, count * 4 * sizeof *damaged);
    size_t t = count / 2;
    memmove(damaged + 4 * t, damaged + 4 * (t + 1), (count - t - 1) * 4 * sizeof *damaged);
    ok = metrics_validity(xyz, n, damaged, count - 1, NULL, hull, hull_count, &v);
    check_case(!ok && v.boundary_off_hull > 0, "self-test: a missing tetrahedron is caught (%zu boundary facets off the hull)", v.boundary_off_hull);
    /* 3. one tetrahedron twice: overlap */
    memcpy(damaged, tets, count * 4 * sizeof *damaged);
    memcpy(damaged + 4 * count, tets + 4 * 3, 4 * sizeof *damaged);
    ok = metrics_validity(xyz, n, damaged, count + 1, NULL, hull, hull_count, &v);
    check_case(!ok && v.facets_overshared > 0, "self-test: a repeated tetrahedron is caught (%zu facets in 3+ tetrahedra)", v.facets_overshared);
    /* 4. an index out of range, and an unused point */
    memcpy(damaged, tets, count * 4 * sizeof *damaged);
    damaged[4 * 5 + 2] = (uint32_t)n;
    ok = metrics_validity(xyz, n, damaged, count, NULL, hull, hull_count, &v);
    check_case(!ok && v.index_out_of_range == 1, "self-test: an index out of range is caught");
    /* 5. the set comparison sees one changed tetrahedron */
    memcpy(damaged, tets, count * 4 * sizeof *damaged);
    damaged[4 * 9] = damaged[4 * 10 + 3] == damaged[4 * 9] ? damaged[4 * 10 + 2] : damaged[4 * 10 + 3];
    uint32_t *a = metrics_tetrahedron_set(tets, count, NULL), *b = metrics_tetrahedron_set(damaged, count, NULL);
    SetComparison c = a && b ? metrics_compare_tetrahedron_sets(a, count, b, count) : (SetComparison){0, 0, 0};
    check_case(a && b && c.only_first == 1 && c.only_second == 1 && c.common == count - 1,
               "self-test: the set comparison sees exactly one changed tetrahedron");
    free(a);
    free(b);
    free(damaged);
  }
  free(hull);
  free(tets);
  free(xyz);
}

/* ---- One input -------------------------------------------------------------------------------- */

typedef struct Case {
  const char *name;
  double *xyz; /* owned */
  size_t n;
  double analytic_volume; /* of the convex hull, or NAN */
  int random;             /* general position: TetGen's set must be equal too */
} Case;

static void run_case(Case k) {
  char name[128];
  snprintf(name, sizeof name, "%s (n=%zu)", k.name, k.n);
  if (!k.xyz) {
    check_case(0, "%s: could not generate the points", name);
    return;
  }

  uint32_t *first = metrics_first_occurrence(k.xyz, k.n);
  unsigned char *expect = malloc(k.n ? k.n : 1);
  if (!first || !expect) {
    check_case(0, "%s: out of memory", name);
    free(first);
    free(expect);
    free(k.xyz);
    return;
  }
  size_t duplicates = 0;
  for (size_t i = 0; i < k.n; i++) {
    expect[i] = first[i] == i ? VERTEX_MUST_BE_USED : VERTEX_MUST_BE_UNUSED;
    duplicates += first[i] != i;
  }

  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = delmesh_delaunay_tetrahedralize(k.xyz, k.n, &mesh);
  if (!check_case(s == DELMESH_OK && mesh, "%s: delmesh_delaunay_tetrahedralize -> %d %s", name,
                  (int)s, s == DELMESH_OK ? "" : delmesh_last_error_message())) {
    free(first);
    free(expect);
    free(k.xyz);
    return;
  }
  compare_mesh_arrays(name, mesh, k.xyz, k.n);
  const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
  size_t count = delmesh_mesh_tetrahedron_count(mesh);

  /* Duplicates reported as API.md says: merged onto their first occurrence. */
  const uint32_t *dup = delmesh_mesh_duplicate_of(mesh);
  size_t dup_count = delmesh_mesh_duplicate_count(mesh);
  size_t dup_wrong = 0;
  for (size_t i = 0; dup && i < k.n; i++) dup_wrong += dup[i] != first[i];
  check_case(dup && dup_wrong == 0 && dup_count == duplicates,
             "%s: duplicates reported: count %zu (expected %zu), duplicate_of %s (%zu wrong entries)",
             name, dup_count, duplicates, dup ? "present" : "NULL", dup_wrong);

  /* Validity against the hull of convex_hull_3. */
  uint32_t *hull = NULL;
  size_t hull_count = 0;
  double hull_volume = NAN;
  if (compare_convex_hull(name, k.xyz, k.n, &hull, &hull_count, &hull_volume)) {
    Validity v;
    char text[512];
    int ok = metrics_validity(k.xyz, k.n, tets, count, expect, hull, hull_count, &v);
    metrics_validity_describe(&v, text, sizeof text);
    check_case(ok, "%s: valid: %s", name, text);
    double volume = metrics_tetrahedra_volume(k.xyz, tets, count);
    compare_volume(name, "convex hull (CGAL convex_hull_3)", volume, hull_volume, VOLUME_TOLERANCE);
    if (!isnan(k.analytic_volume))
      compare_volume(name, "analytic", volume, k.analytic_volume, VOLUME_TOLERANCE);
  }
  free(hull);

  /* CGAL: same count always; same set (both use lexicographic symbolic perturbation). CGAL keeps
   * some copy of a duplicated point: its indices are renamed onto the first occurrence. */
  uint32_t *ref = NULL;
  size_t ref_count = 0;
  int rc = ref_cgal_delaunay(k.xyz, k.n, &ref, &ref_count, NULL);
  if (check_case(rc == 0, "%s: CGAL Delaunay_triangulation_3 ran%s%s", name, rc ? ": " : "",
                 rc ? ref_last_error() : "")) {
    check_case(count == ref_count, "%s: %zu tetrahedra, CGAL %zu", name, count, ref_count);
    compare_tetrahedron_sets(name, "CGAL", tets, count, NULL, ref, ref_count, first, 1);
    free(ref);
  }

  /* TetGen: the same set in general position; on degenerate inputs its perturbation differs, so
   * its count and set are only reported. */
  rc = ref_tetgen_delaunay(k.xyz, k.n, &ref, &ref_count, NULL);
  if (check_case(rc == 0, "%s: TetGen ran%s%s", name, rc ? ": " : "", rc ? ref_last_error() : "")) {
    if (k.random)
      compare_tetrahedron_sets(name, "TetGen", tets, count, NULL, ref, ref_count, first, 1);
    else
      compare_tetrahedron_sets(name, "TetGen", tets, count, NULL, ref, ref_count, first, 0);
    free(ref);
  }

  delmesh_mesh_free(mesh);
  free(first);
  free(expect);
  free(k.xyz);
}

int main(int argc, char **argv) {
  int small = argc > 1 && strcmp(argv[1], "--small") == 0;

  self_test_orientation();
  self_test_validity();

  /* Random points in general position. */
  size_t sizes[] = {1000, 10000, 100000};
  size_t n_sizes = small ? 2 : 3;
  for (size_t i = 0; i < n_sizes; i++)
    run_case((Case){"uniform cube", points_uniform_cube(sizes[i], 0xC0BE0000u + i), sizes[i], NAN, 1});

  /* Degenerate inputs. */
  unsigned grids[] = {10, small ? 20u : 30u};
  for (size_t i = 0; i < 2; i++) {
    double side = (double)(grids[i] - 1);
    run_case((Case){grids[i] == 10 ? "integer grid 10^3" : small ? "integer grid 20^3" : "integer grid 30^3",
                    points_grid(grids[i], 0x61D00000u + i), (size_t)grids[i] * grids[i] * grids[i],
                    side * side * side, 0});
  }
  size_t sphere_n = 0;
  long r2 = small ? 4225 : 11025; /* 65^2: 390 points; 105^2: 1350 points */
  double *sphere = points_integer_sphere(r2, 0x5F4E0000u, &sphere_n);
  run_case((Case){small ? "integer points on the sphere x^2+y^2+z^2 = 65^2" : "integer points on the sphere x^2+y^2+z^2 = 105^2",
                  sphere, sphere_n, NAN, 0});
  size_t per_layer = small ? 400 : 2000;
  run_case((Case){"5 coplanar layers z = 0..4", points_layers(5, per_layer, 0x1A7E0000u), 5 * per_layer, NAN, 0});

  /* Duplicates mixed in (some copies come before their original). */
  size_t base = small ? 2000 : 10000;
  double *cube = points_uniform_cube(base, 0xD0B10000u);
  run_case((Case){"uniform cube + 20% duplicates", cube ? points_with_duplicates(cube, base, base / 5, 0xD0B10001u) : NULL,
                  base + base / 5, NAN, 1});
  free(cube);
  double *grid = points_grid(10, 0xD0B10002u);
  run_case((Case){"integer grid 10^3 + 300 duplicates", grid ? points_with_duplicates(grid, 1000, 300, 0xD0B10003u) : NULL,
                  1300, 729.0, 0});
  free(grid);

  /* Real point sets: the vertices of surfaces from the shared corpus (CAD models with many
   * coplanar and cocircular points), when $DELMESH_CORPUS names it. */
  const char *corpus = getenv("DELMESH_CORPUS");
  static const char *const surfaces[] = {"fandisk.off", "anchor.off", "elephant.off"};
  for (size_t i = 0; i < sizeof surfaces / sizeof surfaces[0]; i++) {
    char path[4096], error[512], label[128];
    size_t n = 0;
    snprintf(path, sizeof path, "%s/surfaces/%s", corpus && corpus[0] ? corpus : ".", surfaces[i]);
    double *xyz = corpus && corpus[0] ? points_read_off(path, &n, error, sizeof error) : NULL;
    if (!xyz) {
      check_note("corpus case %s skipped: %s", surfaces[i],
                 corpus && corpus[0] ? error : "DELMESH_CORPUS is not set");
      continue;
    }
    snprintf(label, sizeof label, "vertices of %s", surfaces[i]);
    run_case((Case){label, xyz, n, NAN, 0});
  }

  return check_finish();
}
