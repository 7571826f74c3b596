/* Error paths of the triangulation calls through the C API (API.md "Conventions", "Status",
 * "Delaunay and regular triangulations"): each bad input returns its documented status, leaves
 * *out untouched, sets a non-empty message (naming the culprit where it is a point), and the
 * process keeps running. */
#include "check.h"
#include "prng.h"

#include <delmesh.h>

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_POINTS 64

/* A recognizable value for *out: it must still be there after a failed call. */
static double sentinel_storage;
#define SENTINEL ((DelmeshMesh *)(void *)&sentinel_storage)

static const char *status_name(DelmeshStatus s) {
  switch (s) {
    case DELMESH_OK: return "OK";
    case DELMESH_ERROR_NULL_ARGUMENT: return "NULL_ARGUMENT";
    case DELMESH_ERROR_INVALID_ARGUMENT: return "INVALID_ARGUMENT";
    case DELMESH_ERROR_INVALID_INPUT: return "INVALID_INPUT";
    case DELMESH_ERROR_CALLBACK: return "CALLBACK";
    case DELMESH_ERROR_CANCELLED: return "CANCELLED";
    case DELMESH_ERROR_LIMIT: return "LIMIT";
    case DELMESH_ERROR_OUT_OF_MEMORY: return "OUT_OF_MEMORY";
    case DELMESH_ERROR_IO: return "IO";
    case DELMESH_ERROR_INTERNAL: return "INTERNAL";
  }
  return "(not a status)";
}

/* 1 when `message` contains the decimal number `index` as a whole number (not inside a longer
 * run of digits). */
static int names_index(const char *message, size_t index) {
  for (const char *p = message; *p;) {
    if (isdigit((unsigned char)*p)) {
      char *end;
      unsigned long long v = strtoull(p, &end, 10);
      if (v == index) return 1;
      p = end;
    } else {
      p++;
    }
  }
  return 0;
}

typedef enum Which { DELAUNAY, REGULAR } Which;

typedef struct Call {
  const double *xyz;
  const double *weights; /* regular only */
  size_t n;
  int null_out;
} Call;

/* Runs one failing call and checks status, message and *out. `index` >= 0: the message must
 * name that point. */
static void expect_failure(Which which, const char *what, Call c, DelmeshStatus expected, long index) {
  DelmeshMesh *out = SENTINEL;
  DelmeshMesh **outp = c.null_out ? NULL : &out;
  DelmeshStatus s = which == DELAUNAY ? delmesh_delaunay_tetrahedralize(c.xyz, c.n, outp)
                                      : delmesh_regular_tetrahedralize(c.xyz, c.weights, c.n, outp);
  const char *m = delmesh_last_error_message();
  int ok = s == expected && m != NULL && m[0] != '\0' && out == SENTINEL;
  if (index >= 0) ok = ok && m != NULL && names_index(m, (size_t)index);
  check_case(ok, "%s %s: %s (expected %s)%s%s; message \"%s\"",
             which == DELAUNAY ? "delaunay" : "regular", what, status_name(s), status_name(expected),
             out == SENTINEL ? "" : ", *out was written",
             index >= 0 && !(m && names_index(m, (size_t)index)) ? ", message does not name the point" : "",
             m ? m : "(NULL)");
  if (s == DELMESH_OK && out != SENTINEL) delmesh_mesh_free(out);
}

/* Random points in the unit cube (affinely independent with probability 1). */
static void random_points(double *xyz, size_t n, uint64_t seed) {
  Prng g = prng_new(seed);
  for (size_t i = 0; i < 3 * n; i++) xyz[i] = prng_uniform(&g);
}

static void run_error_cases(Which which) {
  double xyz[3 * MAX_POINTS], w[MAX_POINTS];
  const size_t n = 12;
  random_points(xyz, MAX_POINTS, 0x5eed0001u);
  for (size_t i = 0; i < MAX_POINTS; i++) w[i] = 0.001 * (double)(i % 5);
  Call c = {xyz, w, n, 0};

  Call null_xyz = c;
  null_xyz.xyz = NULL;
  expect_failure(which, "NULL xyz", null_xyz, DELMESH_ERROR_NULL_ARGUMENT, -1);
  Call null_out = c;
  null_out.null_out = 1;
  expect_failure(which, "NULL out", null_out, DELMESH_ERROR_NULL_ARGUMENT, -1);
  if (which == REGULAR) {
    Call null_w = c;
    null_w.weights = NULL;
    expect_failure(which, "NULL weights", null_w, DELMESH_ERROR_NULL_ARGUMENT, -1);
  }

  for (size_t k = 0; k <= 3; k++) {
    char what[32];
    Call few = c;
    few.n = k;
    snprintf(what, sizeof what, "n = %zu", k);
    expect_failure(which, what, few, DELMESH_ERROR_INVALID_INPUT, -1);
  }

  /* n whose byte length overflows: refused before anything is read. */
  Call huge = c;
  huge.n = SIZE_MAX / 8;
  expect_failure(which, "n = SIZE_MAX/8", huge, DELMESH_ERROR_INVALID_ARGUMENT, -1);

  /* Non-finite coordinates, each in a different point and component. */
  static const struct {
    size_t point;
    int component;
    const char *text;
  } bad[] = {{5, 1, "nan"}, {9, 2, "inf"}, {0, 0, "-inf"}, {11, 2, "nan"}};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    double copy[3 * MAX_POINTS];
    char what[64];
    memcpy(copy, xyz, sizeof copy);
    copy[3 * bad[k].point + (size_t)bad[k].component] = strtod(bad[k].text, NULL);
    Call nonfinite = c;
    nonfinite.xyz = copy;
    snprintf(what, sizeof what, "%s in coordinate %d of point %zu", bad[k].text, bad[k].component,
             bad[k].point);
    expect_failure(which, what, nonfinite, DELMESH_ERROR_INVALID_INPUT, (long)bad[k].point);
  }
  if (which == REGULAR) {
    static const struct {
      size_t point;
      const char *text;
    } badw[] = {{7, "nan"}, {3, "inf"}, {10, "-inf"}};
    for (size_t k = 0; k < sizeof badw / sizeof badw[0]; k++) {
      double copy[MAX_POINTS];
      char what[64];
      memcpy(copy, w, sizeof copy);
      copy[badw[k].point] = strtod(badw[k].text, NULL);
      Call nonfinite = c;
      nonfinite.weights = copy;
      snprintf(what, sizeof what, "%s weight of point %zu", badw[k].text, badw[k].point);
      expect_failure(which, what, nonfinite, DELMESH_ERROR_INVALID_INPUT, (long)badw[k].point);
    }
  }

  /* Degenerate sets: fewer than 4 affinely independent points. */
  double flat[3 * MAX_POINTS];
  Prng g = prng_new(0x5eed0002u);
  for (size_t i = 0; i < 40; i++) { /* on the plane z = x + 2y, exactly (small integers) */
    double x = (double)prng_below(&g, 1000), y = (double)prng_below(&g, 1000);
    flat[3 * i] = x;
    flat[3 * i + 1] = y;
    flat[3 * i + 2] = x + 2.0 * y;
  }
  Call coplanar = {flat, w, 40, 0};
  expect_failure(which, "40 coplanar points", coplanar, DELMESH_ERROR_INVALID_INPUT, -1);
  for (size_t i = 0; i < 40; i++) { /* on the line t * (1, 2, 3) */
    double t = (double)prng_below(&g, 100000);
    flat[3 * i] = t;
    flat[3 * i + 1] = 2.0 * t;
    flat[3 * i + 2] = 3.0 * t;
  }
  expect_failure(which, "40 collinear points", coplanar, DELMESH_ERROR_INVALID_INPUT, -1);
  for (size_t i = 0; i < 40; i++) {
    flat[3 * i] = 0.25;
    flat[3 * i + 1] = -1.5;
    flat[3 * i + 2] = 3.0;
  }
  expect_failure(which, "40 identical points", coplanar, DELMESH_ERROR_INVALID_INPUT, -1);
  for (size_t i = 0; i < 40; i++) /* 3 distinct points, repeated */
    memcpy(flat + 3 * i, xyz + 3 * (i % 3), 3 * sizeof(double));
  expect_failure(which, "3 distinct points repeated to 40", coplanar, DELMESH_ERROR_INVALID_INPUT, -1);
}

/* After all the failures the library still works: the smallest valid input gives one
 * positively oriented tetrahedron. */
static void run_recovery(Which which) {
  const double xyz[12] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1};
  const double w[4] = {0, 0, 0, 0};
  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = which == DELAUNAY ? delmesh_delaunay_tetrahedralize(xyz, 4, &mesh)
                                      : delmesh_regular_tetrahedralize(xyz, w, 4, &mesh);
  size_t count = mesh ? delmesh_mesh_tetrahedron_count(mesh) : 0;
  const uint32_t *t = mesh ? delmesh_mesh_tetrahedra(mesh) : NULL;
  int oriented = 0;
  if (count == 1 && t) {
    /* Exact in doubles here: small integer coordinates. */
    const double *a = xyz + 3 * t[0], *b = xyz + 3 * t[1], *c = xyz + 3 * t[2], *d = xyz + 3 * t[3];
    double u[3], v[3], z[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k], z[k] = d[k] - a[k];
    double det = u[0] * (v[1] * z[2] - v[2] * z[1]) + u[1] * (v[2] * z[0] - v[0] * z[2]) +
                 u[2] * (v[0] * z[1] - v[1] * z[0]);
    oriented = det > 0;
  }
  check_case(s == DELMESH_OK && count == 1 && oriented,
             "%s after the failures: 4 points -> %s, %zu tetrahedron, %s",
             which == DELAUNAY ? "delaunay" : "regular", status_name(s), count,
             oriented ? "positively oriented" : "NOT positively oriented");
  delmesh_mesh_free(mesh);
}

int main(void) {
  run_error_cases(DELAUNAY);
  run_error_cases(REGULAR);
  run_recovery(DELAUNAY);
  run_recovery(REGULAR);

  delmesh_mesh_free(NULL);
  check_case(1, "delmesh_mesh_free(NULL) returned");
  check_case(delmesh_mesh_vertex_count(NULL) == 0 && delmesh_mesh_tetrahedron_count(NULL) == 0 &&
                 delmesh_mesh_tetrahedra(NULL) == NULL && delmesh_mesh_vertices(NULL) == NULL,
             "accessors on a NULL handle return 0 / NULL");
  return check_finish();
}
