/* Error paths and stops of oracle meshing through the C API (API.md "Domains", "Mesher"): every
 * bad argument or failing callback returns its documented status with a message, leaves *out
 * untouched and leaks nothing (the sanitizer run checks leaks); a cancelled or over-budget run
 * stops cleanly; a successful run afterwards is unaffected, and two runs give bit-identical
 * arrays. */
#include "check.h"

#include <delmesh.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static double sentinel_storage;
#define SENTINEL_MESH ((DelmeshMesh *)(void *)&sentinel_storage)
#define SENTINEL_DOMAIN ((DelmeshDomain *)(void *)&sentinel_storage)

static const double BOX[6] = {-2, -2, -2, 2, 2, 2};

static double sphere(const double p[3], void *user_data) {
  (void)user_data;
  return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0;
}

/* NaN in the upper half space. */
static double sphere_nan_above(const double p[3], void *user_data) {
  return p[2] > 0.5 ? NAN : sphere(p, user_data);
}

/* Inside everywhere within radius 3: inside on the box's boundary. */
static double too_big(const double p[3], void *user_data) {
  (void)user_data;
  return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 9.0;
}

static double nowhere(const double p[3], void *user_data) {
  (void)p, (void)user_data;
  return 1.0;
}

/* Label 1 in the unit ball, -7 (a failure) for x > 0.9. */
static int32_t bad_label(const double p[3], void *user_data) {
  (void)user_data;
  if (p[0] > 0.9) return -7;
  return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] < 1.0;
}

static double negative_size(const double p[3], int32_t dimension, int32_t index, void *user_data) {
  (void)p, (void)dimension, (void)index, (void)user_data;
  return -1.0;
}

/* The constant size 0.3 through a field, counting calls in *user_data. */
static double size_field(const double p[3], int32_t dimension, int32_t index, void *user_data) {
  (void)p, (void)index;
  ++*(long *)user_data;
  return dimension == 2 || dimension == 3 ? 0.3 : NAN;
}

/* Cancels at the first report; counts reports in *user_data. */
static int32_t cancel_at_first(const DelmeshProgress *p, void *user_data) {
  (void)p;
  ++*(int *)user_data;
  return 1;
}

static void expect(DelmeshStatus got, DelmeshStatus want, const char *what, const char *must_contain) {
  const char *m = delmesh_last_error_message();
  int ok = got == want && m && m[0] && (!must_contain || strstr(m, must_contain));
  check_case(ok, "%s: status %d (expected %d); message \"%s\"", what, (int)got, (int)want, m ? m : "(NULL)");
}

static void domain_errors(void) {
  DelmeshDomain *d = SENTINEL_DOMAIN;
  const double empty[6] = {0, 0, 0, 1, -1, 1}, infinite[6] = {0, 0, 0, 1, INFINITY, 1};
  expect(delmesh_domain_new_implicit(NULL, NULL, BOX, 1e-6, &d), DELMESH_ERROR_NULL_ARGUMENT, "implicit, NULL f", "`f`");
  expect(delmesh_domain_new_implicit(sphere, NULL, NULL, 1e-6, &d), DELMESH_ERROR_NULL_ARGUMENT, "implicit, NULL bbox", "bbox");
  expect(delmesh_domain_new_implicit(sphere, NULL, BOX, 1e-6, NULL), DELMESH_ERROR_NULL_ARGUMENT, "implicit, NULL out", "out");
  expect(delmesh_domain_new_implicit(sphere, NULL, empty, 1e-6, &d), DELMESH_ERROR_INVALID_ARGUMENT, "implicit, empty bbox", "along y");
  expect(delmesh_domain_new_implicit(sphere, NULL, infinite, 1e-6, &d), DELMESH_ERROR_INVALID_ARGUMENT, "implicit, infinite bbox", "non-finite");
  const double errors[] = {0.0, -1e-6, NAN, 0.5};
  for (size_t i = 0; i < sizeof errors / sizeof errors[0]; i++) {
    char what[64];
    snprintf(what, sizeof what, "implicit, relative_error %g", errors[i]);
    expect(delmesh_domain_new_implicit(sphere, NULL, BOX, errors[i], &d), DELMESH_ERROR_INVALID_ARGUMENT, what, "relative_error");
  }
  expect(delmesh_domain_new_labeled(NULL, NULL, BOX, 1e-6, &d), DELMESH_ERROR_NULL_ARGUMENT, "labeled, NULL f", "`f`");
  check_case(d == SENTINEL_DOMAIN, "*out untouched by every failed domain constructor");

  DelmeshDomain *ok = NULL;
  DelmeshStatus s = delmesh_domain_new_implicit(sphere, NULL, BOX, 1e-6, &ok);
  check_case(s == DELMESH_OK && ok, "implicit domain of the unit sphere created");
  const double seeds[6] = {1, 0, 0, 0, 3, 0}; /* the second is outside the box */
  expect(delmesh_domain_add_surface_points(ok, seeds, 2), DELMESH_ERROR_INVALID_INPUT, "seed point outside the box", "surface point 1");
  expect(delmesh_domain_add_surface_points(NULL, seeds, 1), DELMESH_ERROR_NULL_ARGUMENT, "seeds, NULL domain", "`d`");
  expect(delmesh_domain_add_surface_points(ok, NULL, 1), DELMESH_ERROR_NULL_ARGUMENT, "seeds, NULL xyz", "xyz");
  delmesh_domain_free(ok);
  delmesh_domain_free(NULL);
}

static void mesher_errors(void) {
  DelmeshMesher *m = NULL;
  check_case(delmesh_mesher_new(&m) == DELMESH_OK && m, "mesher created");
  expect(delmesh_mesher_new(NULL), DELMESH_ERROR_NULL_ARGUMENT, "mesher_new, NULL out", "out");
  expect(delmesh_mesher_set_facet_angle(NULL, 20), DELMESH_ERROR_NULL_ARGUMENT, "facet angle, NULL mesher", "`m`");
  const double angles[] = {0, -5, 31, NAN};
  for (size_t i = 0; i < 4; i++) {
    char what[48];
    snprintf(what, sizeof what, "facet angle %g", angles[i]);
    expect(delmesh_mesher_set_facet_angle(m, angles[i]), DELMESH_ERROR_INVALID_ARGUMENT, what, "facet angle");
  }
  const double sizes[] = {0, -1, INFINITY, NAN};
  for (size_t i = 0; i < 4; i++) {
    char what[48];
    snprintf(what, sizeof what, "sizes %g", sizes[i]);
    expect(delmesh_mesher_set_facet_size(m, sizes[i]), DELMESH_ERROR_INVALID_ARGUMENT, what, "facet size");
    expect(delmesh_mesher_set_facet_distance(m, sizes[i]), DELMESH_ERROR_INVALID_ARGUMENT, what, "facet distance");
    expect(delmesh_mesher_set_cell_size(m, sizes[i]), DELMESH_ERROR_INVALID_ARGUMENT, what, "cell size");
  }
  expect(delmesh_mesher_set_cell_radius_edge_ratio(m, 1.5), DELMESH_ERROR_INVALID_ARGUMENT, "radius-edge ratio 1.5", "terminate");
  expect(delmesh_mesher_set_surface_sliver_angle(m, 25), DELMESH_ERROR_INVALID_ARGUMENT, "surface sliver angle 25", "terminate");
  expect(delmesh_mesher_set_surface_sliver_angle(m, NAN), DELMESH_ERROR_INVALID_ARGUMENT, "surface sliver angle NaN", "surface sliver");
  expect(delmesh_mesher_set_sizing_field(m, 7, size_field, NULL), DELMESH_ERROR_INVALID_ARGUMENT, "sizing field for criterion 7", "7");
  expect(delmesh_mesher_set_sizing_field(m, DELMESH_SIZING_CELL_SIZE, NULL, NULL), DELMESH_ERROR_NULL_ARGUMENT, "NULL sizing field", "`f`");
  expect(delmesh_mesher_set_optimization(m, 64, 0), DELMESH_ERROR_INVALID_ARGUMENT, "unknown optimization flag", "unknown");
  check_case(delmesh_mesher_set_optimization(m, DELMESH_OPTIMIZE_ODT | DELMESH_OPTIMIZE_PERTURB | DELMESH_OPTIMIZE_EXUDE, 10) ==
                 DELMESH_OK,
             "all optimization passes with a time limit accepted");
  expect(delmesh_mesher_set_optimization(m, DELMESH_OPTIMIZE_EXUDE, -1), DELMESH_ERROR_INVALID_ARGUMENT, "negative time limit", "time limit");
  expect(delmesh_mesher_set_optimization(m, DELMESH_OPTIMIZE_EXUDE, NAN), DELMESH_ERROR_INVALID_ARGUMENT, "NaN time limit", "time limit");
  expect(delmesh_mesher_set_optimization(NULL, 0, 0), DELMESH_ERROR_NULL_ARGUMENT, "optimization, NULL mesher", "`m`");
  expect(delmesh_mesher_set_sliver_bound(m, 0), DELMESH_ERROR_INVALID_ARGUMENT, "sliver bound 0", "sliver bound");
  expect(delmesh_mesher_set_sliver_bound(m, 50), DELMESH_ERROR_INVALID_ARGUMENT, "sliver bound 50", "sliver bound");
  check_case(delmesh_mesher_set_sliver_bound(m, 20) == DELMESH_OK, "sliver bound 20 accepted");

  DelmeshDomain *d = NULL;
  DelmeshMesh *out = SENTINEL_MESH;
  delmesh_domain_new_implicit(sphere, NULL, BOX, 1e-6, &d);
  expect(delmesh_mesher_run(NULL, d, &out), DELMESH_ERROR_NULL_ARGUMENT, "run, NULL mesher", "`m`");
  expect(delmesh_mesher_run(m, NULL, &out), DELMESH_ERROR_NULL_ARGUMENT, "run, NULL domain", "`d`");
  expect(delmesh_mesher_run(m, d, NULL), DELMESH_ERROR_NULL_ARGUMENT, "run, NULL out", "out");
  check_case(out == SENTINEL_MESH, "*out untouched by the failed runs");
  delmesh_domain_free(d);
  delmesh_mesher_free(m);
  delmesh_mesher_free(NULL);
}

static DelmeshMesher *coarse_mesher(void) {
  DelmeshMesher *m = NULL;
  delmesh_mesher_new(&m);
  delmesh_mesher_set_facet_angle(m, 25);
  delmesh_mesher_set_facet_size(m, 0.3);
  delmesh_mesher_set_facet_distance(m, 0.06);
  delmesh_mesher_set_cell_radius_edge_ratio(m, 3);
  delmesh_mesher_set_cell_size(m, 0.3);
  return m;
}

/* Runs `m` on the implicit `f` (or the labeling `label` when f is NULL) expecting `want`. */
static void expect_run(DelmeshMesher *m, DelmeshImplicitFn f, DelmeshLabelFn label, DelmeshStatus want,
                       const char *what, const char *must_contain) {
  DelmeshDomain *d = NULL;
  DelmeshStatus s = f ? delmesh_domain_new_implicit(f, NULL, BOX, 1e-6, &d)
                      : delmesh_domain_new_labeled(label, NULL, BOX, 1e-6, &d);
  DelmeshMesh *out = SENTINEL_MESH;
  if (s == DELMESH_OK) s = delmesh_mesher_run(m, d, &out);
  expect(s, want, what, must_contain);
  check_case(out == SENTINEL_MESH, "%s: *out untouched", what);
  delmesh_domain_free(d);
}

static void run_failures(void) {
  DelmeshMesher *m = coarse_mesher();
  expect_run(m, sphere_nan_above, NULL, DELMESH_ERROR_CALLBACK, "implicit function returning NaN", "NaN");
  expect_run(m, NULL, bad_label, DELMESH_ERROR_CALLBACK, "labeling function returning -7", "-7");
  expect_run(m, too_big, NULL, DELMESH_ERROR_INVALID_INPUT, "domain inside on its bbox", "boundary of its bbox");
  expect_run(m, nowhere, NULL, DELMESH_ERROR_INVALID_INPUT, "empty domain", "surface points");

  DelmeshMesher *sized = coarse_mesher();
  delmesh_mesher_set_sizing_field(sized, DELMESH_SIZING_FACET_SIZE, negative_size, NULL);
  expect_run(sized, sphere, NULL, DELMESH_ERROR_CALLBACK, "sizing field returning -1", "sizing field returned -1");
  delmesh_mesher_free(sized);

  DelmeshMesher *budget = coarse_mesher();
  delmesh_mesher_set_facet_size(budget, 0.05);
  delmesh_mesher_set_cell_size(budget, 0.05);
  delmesh_mesher_set_max_vertices(budget, 300);
  expect_run(budget, sphere, NULL, DELMESH_ERROR_LIMIT, "vertex budget of 300", "300");
  delmesh_mesher_set_max_vertices(budget, 0);
  int reports = 0;
  delmesh_mesher_set_progress(budget, cancel_at_first, &reports);
  expect_run(budget, sphere, NULL, DELMESH_ERROR_CANCELLED, "progress callback cancelling", "cancelled");
  check_case(reports == 1, "the progress callback ran once before the cancellation (%d)", reports);
  delmesh_mesher_free(budget);
  delmesh_mesher_free(m);
}

/* After all failures: a run succeeds, a sizing field gives the same mesh as the equal constant,
 * and two runs give bit-identical arrays. */
static void run_successes(void) {
  DelmeshMesher *m = coarse_mesher(), *field = coarse_mesher();
  long calls = 0;
  delmesh_mesher_set_sizing_field(field, DELMESH_SIZING_FACET_SIZE, size_field, &calls);
  delmesh_mesher_set_sizing_field(field, DELMESH_SIZING_CELL_SIZE, size_field, &calls);
  DelmeshDomain *d = NULL;
  delmesh_domain_new_implicit(sphere, NULL, BOX, 1e-6, &d);
  DelmeshMesh *a = NULL, *b = NULL, *c = NULL;
  DelmeshStatus sa = delmesh_mesher_run(m, d, &a), sb = delmesh_mesher_run(m, d, &b);
  DelmeshStatus sc = delmesh_mesher_run(field, d, &c);
  check_case(sa == DELMESH_OK && sb == DELMESH_OK && sc == DELMESH_OK, "runs after the failures succeed");
  if (sa == DELMESH_OK && sb == DELMESH_OK && sc == DELMESH_OK) {
    size_t nv = delmesh_mesh_vertex_count(a), nt = delmesh_mesh_tetrahedron_count(a);
    int same = nv == delmesh_mesh_vertex_count(b) && nt == delmesh_mesh_tetrahedron_count(b) &&
               memcmp(delmesh_mesh_vertices(a), delmesh_mesh_vertices(b), 3 * nv * sizeof(double)) == 0 &&
               memcmp(delmesh_mesh_tetrahedra(a), delmesh_mesh_tetrahedra(b), 4 * nt * sizeof(uint32_t)) == 0;
    check_case(same && nt > 0, "two runs: bit-identical arrays (%zu vertices, %zu tetrahedra)", nv, nt);
    int same_field = nv == delmesh_mesh_vertex_count(c) && nt == delmesh_mesh_tetrahedron_count(c) &&
                     memcmp(delmesh_mesh_vertices(a), delmesh_mesh_vertices(c), 3 * nv * sizeof(double)) == 0;
    check_case(same_field && calls > 0, "a constant sizing field (%ld calls) gives the constant's mesh", calls);
    DelmeshQuality q;
    int quality_ok = delmesh_mesh_quality(a, &q) == DELMESH_OK && q.tetrahedra == nt && q.min_dihedral_angle > 0 &&
                     q.max_dihedral_angle < 180 && q.min_facet_angle >= 25 * (1 - 1e-9);
    check_case(quality_ok, "delmesh_mesh_quality: %zu tetrahedra, dihedral %.2f..%.2f, facet angle >= %.2f", q.tetrahedra,
               q.min_dihedral_angle, q.max_dihedral_angle, q.min_facet_angle);
    expect(delmesh_mesh_quality(NULL, &q), DELMESH_ERROR_NULL_ARGUMENT, "quality of a NULL mesh", "`m`");
    expect(delmesh_mesh_quality(a, NULL), DELMESH_ERROR_NULL_ARGUMENT, "quality into NULL", "out");
  }
  delmesh_mesh_free(a);
  delmesh_mesh_free(b);
  delmesh_mesh_free(c);
  delmesh_domain_free(d);
  delmesh_mesher_free(m);
  delmesh_mesher_free(field);
}

int main(void) {
  domain_errors();
  mesher_errors();
  run_failures();
  run_successes();
  return check_finish();
}
