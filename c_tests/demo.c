/* delmesh demo: a tetrahedral mesh of a shape given by an implicit function, through the C API.
 *
 *   demo [--shape tanglecube|torus] [--scale F] [--out FILE]
 *   demo --delaunay [--off FILE.off] [--out FILE]
 *
 * The default meshes the genus-5 "tanglecube" x⁴-5x²+y⁴-5y²+z⁴-5z²+11.8 < 0 (box [-3,3]³; or a
 * torus, R = 1, r = 0.4), given to delmesh_domain_new_implicit as a C callback, with CGAL Mesh_3
 * style criteria (facet angle 30°, facet size, facet distance, cell radius-edge ratio 2, cell
 * size; --scale F multiplies the three size bounds by F). It prints the vertex counts by
 * dimension (surface / volume), the tetrahedra, the boundary facets, the time of
 * delmesh_mesher_run, the volume against a reference, and the quality figures of METRICS.md
 * (quality.h); checks the mesh (validity, a closed boundary of the shape's Euler characteristic
 * enclosing the tetrahedra, labels, the criteria); and writes it with delmesh_mesh_write to FILE
 * (default c_tests/build/demo.vtu; .mesh, .msh or .vtu).
 *
 * --delaunay: the Delaunay tetrahedralization of a real point set instead: the vertices of
 * FILE.off, by default those of surfaces/elephant.off from the shared corpus ($DELMESH_CORPUS,
 * else ../shared/data seen from the repository root, where `make demo` runs), or 20000 generated
 * points near a sphere when that is absent (the demo says which). Prints the counts (points,
 * duplicates, tetrahedra), validity, volume against the convex hull, and the time of the call.
 *
 * Exits non-zero on any failure. */
#define _POSIX_C_SOURCE 200809L

#include "metrics.h"
#include "points.h"
#include "quality.h"
#include "ref.h"

#include <delmesh.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Writes the mesh (the extension of `path` chooses the format); 1 on success. */
static int write_mesh(const DelmeshMesh *mesh, const char *path) {
  DelmeshStatus status = delmesh_mesh_write(mesh, path);
  if (status != DELMESH_OK) {
    fprintf(stderr, "demo: delmesh_mesh_write(%s) failed (status %d): %s\n", path, (int)status,
            delmesh_last_error_message());
    return 0;
  }
  printf("written:     %s\n", path);
  return 1;
}

static double seconds_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int file_exists(const char *path) {
  FILE *f = fopen(path, "r");
  if (f) fclose(f);
  return f != NULL;
}

/* ---- Shapes --------------------------------------------------------------------------------- */

/* g(t) = t⁴ - 5t², the one-variable part of the tanglecube. */
static double tangle_g(double t) { return t * t * (t * t - 5.0); }

static double tanglecube(const double *p, void *user_data) {
  (void)user_data;
  return tangle_g(p[0]) + tangle_g(p[1]) + tangle_g(p[2]) + 11.8;
}

static void tanglecube_gradient(const double p[3], double g[3]) {
  for (int k = 0; k < 3; k++) g[k] = 4.0 * p[k] * p[k] * p[k] - 10.0 * p[k];
}

/* The tanglecube's volume, integrated in z exactly and in x, y by the midpoint rule on one
 * quadrant. Inside means s² - 5s + c < 0 for s = z² and c = g(x) + g(y) + 11.8: s between the
 * roots (5 ∓ √(25 - 4c)) / 2, so the chord in z has length 2(√s₂ - √max(s₁, 0)). The solid lies
 * within |x|, |y| < 2.27 (g >= -6.25). The integrand has a square-root edge at the silhouette:
 * with 4000² cells the error is well below 1e-5 relative. */
static double tanglecube_volume(void) {
  const int n = 4000;
  const double extent = 2.3, h = extent / n;
  double sum = 0.0;
  for (int i = 0; i < n; i++) {
    double gx = tangle_g((i + 0.5) * h);
    double row = 0.0;
    for (int j = 0; j < n; j++) {
      double c = gx + tangle_g((j + 0.5) * h) + 11.8;
      double disc = 25.0 - 4.0 * c;
      if (disc <= 0.0) continue;
      double root = sqrt(disc), s1 = 0.5 * (5.0 - root), s2 = 0.5 * (5.0 + root);
      row += 2.0 * (sqrt(s2) - (s1 > 0.0 ? sqrt(s1) : 0.0));
    }
    sum += row;
  }
  return 4.0 * sum * h * h;
}

#define TORUS_R 1.0
#define TORUS_r 0.4
#define PI 3.14159265358979323846

static double torus(const double *p, void *user_data) {
  (void)user_data;
  double rho = sqrt(p[0] * p[0] + p[1] * p[1]) - TORUS_R;
  return rho * rho + p[2] * p[2] - TORUS_r * TORUS_r;
}

static void torus_gradient(const double p[3], double g[3]) {
  double planar = sqrt(p[0] * p[0] + p[1] * p[1]);
  double scale = planar > 0.0 ? 2.0 * (planar - TORUS_R) / planar : 0.0;
  g[0] = scale * p[0];
  g[1] = scale * p[1];
  g[2] = 2.0 * p[2];
}

static double torus_volume(void) { return 2.0 * PI * PI * TORUS_R * TORUS_r * TORUS_r; }

typedef struct DemoShape {
  const char *name, *description;
  DelmeshImplicitFn f;
  void (*gradient)(const double p[3], double g[3]);
  double bbox[6];
  int genus; /* of its one boundary surface */
  double (*volume)(void);
  const char *volume_source;
  /* Criteria: facet angle (degrees), facet size, facet distance, cell radius-edge ratio, cell
   * size. */
  double facet_angle, facet_size, facet_distance, radius_edge, cell_size;
} DemoShape;

static const DemoShape SHAPES[] = {
    {"tanglecube", "x^4-5x^2+y^4-5y^2+z^4-5z^2+11.8 < 0, genus 5", tanglecube,
     tanglecube_gradient, {-3, -3, -3, 3, 3, 3}, 5, tanglecube_volume,
     "exact in z, midpoint rule on a 4000^2 grid in x, y", 30.0, 0.06, 0.006, 2.0, 0.075},
    {"torus", "(sqrt(x^2+y^2)-1)^2+z^2-0.4^2 < 0, genus 1", torus, torus_gradient,
     {-2, -2, -2, 2, 2, 2}, 1, torus_volume, "analytic 2 pi^2 R r^2", 30.0, 0.05, 0.005, 2.0,
     0.08},
};

/* ---- Checks of the oracle mesh ---------------------------------------------------------------- */

typedef struct EdgeKey {
  uint32_t lo, hi;
  int forward; /* the facet runs lo -> hi */
} EdgeKey;

static int compare_edges(const void *pa, const void *pb) {
  const EdgeKey *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->forward > b->forward) - (a->forward < b->forward);
}

typedef struct Surface {
  size_t vertices, edges, facets;
  size_t bad_edges;         /* in one facet, or in three or more */
  size_t misoriented_edges; /* in two facets that run it the same way */
  long euler;
} Surface;

/* The facets as a surface: closed and edge-manifold when every edge is in exactly two facets,
 * consistently oriented when those run it in opposite directions. Returns 0 when out of memory. */
static int surface_of(const uint32_t *facets, size_t count, Surface *s) {
  memset(s, 0, sizeof *s);
  s->facets = count;
  EdgeKey *edges = malloc((count ? 3 * count : 3) * sizeof *edges);
  uint32_t *vertices = metrics_triangle_vertices(facets, count, &s->vertices);
  if (!edges || !vertices) {
    free(edges);
    free(vertices);
    return 0;
  }
  for (size_t f = 0; f < count; f++)
    for (int k = 0; k < 3; k++) {
      uint32_t a = facets[3 * f + k], b = facets[3 * f + (k + 1) % 3];
      edges[3 * f + k] = (EdgeKey){a < b ? a : b, a < b ? b : a, a < b};
    }
  qsort(edges, 3 * count, sizeof *edges, compare_edges);
  for (size_t i = 0; i < 3 * count;) {
    size_t j = i;
    while (j < 3 * count && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) j++;
    s->edges++;
    if (j - i != 2)
      s->bad_edges++;
    else if (edges[i].forward == edges[i + 1].forward)
      s->misoriented_edges++;
    i = j;
  }
  s->euler = (long)s->vertices - (long)s->edges + (long)s->facets;
  free(edges);
  free(vertices);
  return 1;
}

static const char *yes_no(int ok) { return ok ? "yes" : "NO"; }

/* Rounding allowance of the double-precision quality figures against the criteria. */
#define ROUNDING 1e-9

static int run_oracle(const DemoShape *shape, const char *out_path) {
  printf("shape:       %s (%s), box [%g,%g]x[%g,%g]x[%g,%g]\n", shape->name, shape->description,
         shape->bbox[0], shape->bbox[3], shape->bbox[1], shape->bbox[4], shape->bbox[2],
         shape->bbox[5]);
  printf("criteria:    facet angle %g deg, facet size %g, facet distance %g, "
         "cell radius-edge %g, cell size %g\n",
         shape->facet_angle, shape->facet_size, shape->facet_distance, shape->radius_edge,
         shape->cell_size);

  DelmeshDomain *domain = NULL;
  DelmeshMesher *mesher = NULL;
  DelmeshMesh *mesh = NULL;
  /* Each step runs only while the previous ones succeeded; `call` names the last one run. */
  const char *call = "delmesh_domain_new_implicit";
  DelmeshStatus status = delmesh_domain_new_implicit(shape->f, NULL, shape->bbox, 1e-6, &domain);
#define STEP(function, ...)                                                                        \
  if (status == DELMESH_OK) {                                                                      \
    call = #function;                                                                              \
    status = function(__VA_ARGS__);                                                                \
  }
  STEP(delmesh_mesher_new, &mesher)
  STEP(delmesh_mesher_set_facet_angle, mesher, shape->facet_angle)
  STEP(delmesh_mesher_set_facet_size, mesher, shape->facet_size)
  STEP(delmesh_mesher_set_facet_distance, mesher, shape->facet_distance)
  STEP(delmesh_mesher_set_cell_radius_edge_ratio, mesher, shape->radius_edge)
  STEP(delmesh_mesher_set_cell_size, mesher, shape->cell_size)
  double t0 = seconds_now();
  STEP(delmesh_mesher_run, mesher, domain, &mesh)
  double elapsed = seconds_now() - t0;
#undef STEP
  delmesh_mesher_free(mesher);
  delmesh_domain_free(domain);
  if (status != DELMESH_OK) {
    fprintf(stderr, "demo: %s failed (status %d): %s\n", call, (int)status,
            delmesh_last_error_message());
    return 1;
  }

  size_t n = delmesh_mesh_vertex_count(mesh);
  size_t tet_count = delmesh_mesh_tetrahedron_count(mesh);
  size_t facet_count = delmesh_mesh_facet_count(mesh);
  const double *xyz = delmesh_mesh_vertices(mesh);
  const int8_t *dimensions = delmesh_mesh_vertex_dimensions(mesh);
  const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
  const int32_t *tet_labels = delmesh_mesh_tetrahedron_labels(mesh);
  const uint32_t *facets = delmesh_mesh_facets(mesh);
  const int32_t *facet_labels = delmesh_mesh_facet_labels(mesh);
  if (!xyz || !dimensions || !tets || !tet_labels || !facets || !facet_labels) {
    fprintf(stderr, "demo: the mesh lacks an array (%zu vertices, %zu tetrahedra, %zu facets)\n", n,
            tet_count, facet_count);
    delmesh_mesh_free(mesh);
    return 1;
  }
  int failed = 0;

  /* Vertices by dimension, and how far the surface ones are from f = 0 (|f| / |grad f|). */
  size_t by_dimension[4] = {0}, other_dimension = 0;
  double diagonal = sqrt((shape->bbox[3] - shape->bbox[0]) * (shape->bbox[3] - shape->bbox[0]) +
                         (shape->bbox[4] - shape->bbox[1]) * (shape->bbox[4] - shape->bbox[1]) +
                         (shape->bbox[5] - shape->bbox[2]) * (shape->bbox[5] - shape->bbox[2]));
  double surface_distance = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (dimensions[i] < 0 || dimensions[i] > 3) {
      other_dimension++;
      continue;
    }
    by_dimension[dimensions[i]]++;
    if (dimensions[i] == 2) {
      double g[3];
      shape->gradient(xyz + 3 * i, g);
      double d = fabs(shape->f(xyz + 3 * i, NULL)) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (d > surface_distance) surface_distance = d;
    }
  }
  printf("vertices:    %zu (surface %zu, volume %zu", n, by_dimension[2], by_dimension[3]);
  if (by_dimension[0] || by_dimension[1] || other_dimension)
    printf(", corner %zu, curve %zu, other %zu", by_dimension[0], by_dimension[1], other_dimension);
  printf(")\n");
  failed |= by_dimension[0] || by_dimension[1] || other_dimension;
  printf("tetrahedra:  %zu\n", tet_count);
  printf("facets:      %zu on the boundary\n", facet_count);
  printf("time:        %.3f s for delmesh_mesher_run (%.0f tetrahedra/s)\n", elapsed,
         elapsed > 0 ? (double)tet_count / elapsed : 0.0);

  /* Validity: exact orientation, conformity, every vertex used. */
  Validity v;
  char text[512];
  int valid = metrics_validity(xyz, n, tets, tet_count, NULL, NULL, 0, &v);
  metrics_validity_describe(&v, text, sizeof text);
  printf("validity:    %s\n", text);
  failed |= !valid;

  /* Labels: one subdomain (1); every facet between it and the outside (0). */
  size_t wrong_tet_labels = 0, wrong_facet_labels = 0;
  for (size_t t = 0; t < tet_count; t++) wrong_tet_labels += tet_labels[t] != 1;
  for (size_t f = 0; f < facet_count; f++) {
    int32_t from = facet_labels[2 * f], to = facet_labels[2 * f + 1];
    wrong_facet_labels += !((from == 1 && to == 0) || (from == 0 && to == 1));
  }
  printf("labels:      tetrahedra not labeled 1: %zu, facets not between 1 and 0: %zu\n",
         wrong_tet_labels, wrong_facet_labels);
  failed |= wrong_tet_labels || wrong_facet_labels;

  /* The boundary: the facets oriented out of subdomain 1 form a closed, consistently oriented,
   * edge-manifold surface of the shape's Euler characteristic; they are exactly as many as the
   * tetrahedron faces with no neighbour, their vertices are the surface vertices, and the
   * volume they enclose is that of the tetrahedra. */
  uint32_t *outward = malloc((facet_count ? 3 * facet_count : 3) * sizeof *outward);
  unsigned char *on_facet = calloc(n ? n : 1, 1);
  Surface s;
  if (!outward || !on_facet || !surface_of(facets, facet_count, &s)) {
    fprintf(stderr, "demo: out of memory\n");
    free(outward);
    free(on_facet);
    delmesh_mesh_free(mesh);
    return 1;
  }
  size_t off_surface = 0, surface_not_on_facet = 0;
  for (size_t f = 0; f < facet_count; f++) {
    const uint32_t *t = facets + 3 * f;
    int flip = facet_labels[2 * f] == 0; /* normal from 0 into 1: reverse it */
    outward[3 * f] = t[0];
    outward[3 * f + 1] = flip ? t[2] : t[1];
    outward[3 * f + 2] = flip ? t[1] : t[2];
    for (int k = 0; k < 3; k++) {
      off_surface += !on_facet[t[k]] && dimensions[t[k]] != 2;
      on_facet[t[k]] = 1;
    }
  }
  for (size_t i = 0; i < n; i++) surface_not_on_facet += dimensions[i] == 2 && !on_facet[i];
  free(on_facet);
  long expected_euler = 2 - 2 * (long)shape->genus;
  int closed = s.bad_edges == 0 && s.misoriented_edges == 0;
  printf("boundary:    %zu vertices, %zu edges, %zu facets: closed and oriented %s, "
         "Euler characteristic %ld (genus %d: %ld)\n",
         s.vertices, s.edges, s.facets, yes_no(closed), s.euler, shape->genus, expected_euler);
  if (!closed)
    printf("             %zu edges not in exactly two facets, %zu run the same way twice\n",
           s.bad_edges, s.misoriented_edges);
  printf("             tetrahedron faces without a neighbour: %zu; facet vertices not of "
         "dimension 2: %zu; vertices of dimension 2 on no facet: %zu\n",
         v.boundary_facets, off_surface, surface_not_on_facet);
  failed |= !closed || s.euler != expected_euler || v.boundary_facets != facet_count ||
            off_surface != 0;
  printf("             surface vertices: max |f|/|grad f| = %.2e (%.2e of the box diagonal)\n",
         surface_distance, surface_distance / diagonal);

  /* Volume. */
  double volume = metrics_tetrahedra_volume(xyz, tets, tet_count);
  double enclosed = metrics_polyhedron_volume(xyz, outward, facet_count);
  double reference = shape->volume();
  double error = metrics_relative_error(volume, reference);
  printf("volume:      %.9g (reference %.9g, %s: relative error %.2e)\n", volume, reference,
         shape->volume_source, error);
  printf("             enclosed by the boundary facets %.15g (relative difference %.1e)\n",
         enclosed, metrics_relative_error(enclosed, volume));
  failed |= !(error < 0.02) || !(metrics_relative_error(enclosed, volume) < 1e-9);

  /* Quality (METRICS.md), and the criteria that must hold at the end. */
  QualitySummary q = quality_tetrahedra(xyz, tets, tet_count);
  double facet_angle = quality_triangles_min_angle(xyz, facets, facet_count);
  printf("quality:     tetrahedra\n");
  quality_print(&q, "               ");
  printf("             boundary facets: min angle %.2f degrees\n", facet_angle);
  if (q.worst_dihedral >= 0) {
    const uint32_t *w = tets + 4 * q.worst_dihedral;
    TetQuality worst = quality_tetrahedron(xyz + 3 * (size_t)w[0], xyz + 3 * (size_t)w[1],
                                           xyz + 3 * (size_t)w[2], xyz + 3 * (size_t)w[3]);
    printf("             flattest tetrahedron: dihedral %.2f..%.2f, radius-edge %.3f, radius "
           "ratio %.4f, vertex dimensions %d %d %d %d\n",
           worst.min_dihedral, worst.max_dihedral, worst.radius_edge, worst.radius_ratio,
           dimensions[w[0]], dimensions[w[1]], dimensions[w[2]], dimensions[w[3]]);
  }
  /* The library's own report (delmesh_mesh_quality) must agree with this independent one. */
  DelmeshQuality lib;
  int lib_ok = delmesh_mesh_quality(mesh, &lib) == DELMESH_OK;
  int agree = lib_ok && lib.tetrahedra == tet_count &&
              fabs(lib.min_dihedral_angle - q.min_dihedral) <= 1e-9 * 180 &&
              fabs(lib.max_dihedral_angle - q.max_dihedral) <= 1e-9 * 180 &&
              lib.dihedral_below[0] == q.dihedral_below[0] && lib.dihedral_below[1] == q.dihedral_below[1] &&
              lib.dihedral_below[2] == q.dihedral_below[2] &&
              fabs(lib.min_facet_angle - facet_angle) <= 1e-9 * 180;
  if (lib_ok)
    printf("             delmesh_mesh_quality: dihedral %.2f..%.2f, radius-edge <= %.4f, radius ratio >= "
           "%.4f, below 5/10/15 deg: %zu/%zu/%zu, facet angle >= %.2f: %s\n",
           lib.min_dihedral_angle, lib.max_dihedral_angle, lib.max_radius_edge_ratio, lib.min_radius_ratio,
           lib.dihedral_below[0], lib.dihedral_below[1], lib.dihedral_below[2], lib.min_facet_angle,
           agree ? "agrees" : "DISAGREES with the figures above");
  failed |= !agree;
  int radius_edge_ok = q.max_radius_edge <= shape->radius_edge * (1 + ROUNDING);
  int angle_ok = facet_angle >= shape->facet_angle * (1 - ROUNDING);
  /* The cell size bound holds for the refined mesh; sliver perturbation and exudation (on by
   * default) move interior vertices a little and flip slivers away, which may enlarge a few
   * circumballs past it. */
  printf("criteria:    radius-edge %.4f <= %g: %s; facet angle %.2f >= %g: %s; largest "
         "circumradius %.4f (cell size %g before optimization)\n",
         q.max_radius_edge, shape->radius_edge, yes_no(radius_edge_ok), facet_angle,
         shape->facet_angle, yes_no(angle_ok), q.max_circumradius, shape->cell_size);
  failed |= !radius_edge_ok || !angle_ok;

  failed |= !write_mesh(mesh, out_path);
  free(outward);
  delmesh_mesh_free(mesh);
  return failed;
}

/* ---- Delaunay of a point set (--delaunay) ----------------------------------------------------- */

static int run_delaunay(const char *off, const char *out_path) {
  char corpus_path[4096];
  if (!off) {
    const char *corpus = getenv("DELMESH_CORPUS");
    snprintf(corpus_path, sizeof corpus_path, "%s/surfaces/elephant.off",
             corpus && corpus[0] ? corpus : "../shared/data");
    if (file_exists(corpus_path)) off = corpus_path;
  }

  double *xyz;
  size_t n = 0;
  if (off) {
    char error[512];
    xyz = points_read_off(off, &n, error, sizeof error);
    if (!xyz) {
      fprintf(stderr, "demo: %s\n", error);
      return 1;
    }
    printf("points:      %zu, the vertices of %s\n", n, off);
  } else {
    n = 20000;
    xyz = points_thin_shell(n, 0.05, 0xDE70u);
    if (!xyz) {
      fprintf(stderr, "demo: out of memory\n");
      return 1;
    }
    printf("points:      %zu generated near the unit sphere (no corpus: %s not found; set DELMESH_CORPUS)\n",
           n, corpus_path);
  }

  DelmeshMesh *mesh = NULL;
  double t0 = seconds_now();
  DelmeshStatus status = delmesh_delaunay_tetrahedralize(xyz, n, &mesh);
  double elapsed = seconds_now() - t0;
  if (status != DELMESH_OK) {
    fprintf(stderr, "demo: delmesh_delaunay_tetrahedralize failed (status %d): %s\n", (int)status,
            delmesh_last_error_message());
    free(xyz);
    return 1;
  }
  const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
  size_t count = delmesh_mesh_tetrahedron_count(mesh);
  size_t duplicates = delmesh_mesh_duplicate_count(mesh);
  int failed = 0;

  /* Duplicates: the library's report against our own count. */
  uint32_t *first = metrics_first_occurrence(xyz, n);
  unsigned char *expect = malloc(n ? n : 1);
  size_t expected_duplicates = 0;
  if (!first || !expect) {
    fprintf(stderr, "demo: out of memory\n");
    free(first);
    free(expect);
    free(xyz);
    delmesh_mesh_free(mesh);
    return 1;
  }
  for (size_t i = 0; i < n; i++) {
    expect[i] = first[i] == i ? VERTEX_MUST_BE_USED : VERTEX_MUST_BE_UNUSED;
    expected_duplicates += first[i] != i;
  }
  printf("duplicates:  %zu merged (independent count: %zu)\n", duplicates, expected_duplicates);
  failed |= duplicates != expected_duplicates;
  printf("tetrahedra:  %zu\n", count);
  printf("time:        %.3f s for delmesh_delaunay_tetrahedralize (%.0f points/s)\n", elapsed,
         elapsed > 0 ? (double)n / elapsed : 0.0);

  /* Validity and volume against the convex hull (CGAL convex_hull_3). */
  uint32_t *hull_triangles = NULL, *hull = NULL;
  size_t hull_triangle_count = 0, hull_count = 0;
  if (ref_cgal_convex_hull(xyz, n, &hull_triangles, &hull_triangle_count) != 0) {
    fprintf(stderr, "demo: convex hull failed: %s\n", ref_last_error());
    free(first);
    free(expect);
    free(xyz);
    delmesh_mesh_free(mesh);
    return 1;
  }
  hull = metrics_triangle_vertices(hull_triangles, hull_triangle_count, &hull_count);
  Validity v;
  char text[512];
  int valid = hull && metrics_validity(xyz, n, tets, count, expect, hull, hull_count, &v);
  if (hull) metrics_validity_describe(&v, text, sizeof text);
  printf("validity:    %s\n", hull ? text : "could not be checked");
  failed |= !valid;
  double volume = metrics_tetrahedra_volume(xyz, tets, count);
  double hull_volume = metrics_polyhedron_volume(xyz, hull_triangles, hull_triangle_count);
  double error = metrics_relative_error(volume, hull_volume);
  printf("volume:      %.15g (convex hull %.15g, relative error %.2g)\n", volume, hull_volume, error);
  failed |= !(error <= 1e-12);

  failed |= !write_mesh(mesh, out_path);

  delmesh_mesh_free(mesh);
  free(hull);
  free(hull_triangles);
  free(first);
  free(expect);
  free(xyz);
  return failed;
}

static int usage(const char *program) {
  fprintf(stderr,
          "usage: %s [--shape tanglecube|torus] [--scale F] [--out FILE]\n"
          "       %s --delaunay [--off FILE.off] [--out FILE]\n"
          "FILE ends in .mesh, .msh or .vtu (default c_tests/build/demo.vtu)\n",
          program, program);
  return 2;
}

int main(int argc, char **argv) {
  const char *off = NULL, *out_path = "c_tests/build/demo.vtu";
  const DemoShape *shape = &SHAPES[0];
  double scale = 1.0;
  int delaunay = 0, oracle_option = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--delaunay") == 0) {
      delaunay = 1;
    } else if (strcmp(argv[i], "--off") == 0 && i + 1 < argc) {
      off = argv[++i];
    } else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      out_path = argv[++i];
    } else if (strcmp(argv[i], "--shape") == 0 && i + 1 < argc) {
      const char *name = argv[++i];
      shape = NULL;
      for (size_t k = 0; k < sizeof SHAPES / sizeof SHAPES[0]; k++)
        if (strcmp(name, SHAPES[k].name) == 0) shape = &SHAPES[k];
      if (!shape) return usage(argv[0]);
      oracle_option = 1;
    } else if (strcmp(argv[i], "--scale") == 0 && i + 1 < argc) {
      char *end;
      scale = strtod(argv[++i], &end);
      if (*end || !(scale > 0.0 && scale < 1e3)) return usage(argv[0]);
      oracle_option = 1;
    } else {
      return usage(argv[0]);
    }
  }
  if ((off && !delaunay) || (oracle_option && delaunay)) return usage(argv[0]);

  if (delmesh_abi_version() != DELMESH_ABI_VERSION) {
    fprintf(stderr, "demo: library ABI version %u, header %d\n", (unsigned)delmesh_abi_version(),
            DELMESH_ABI_VERSION);
    return 1;
  }
  printf("delmesh %s\n", delmesh_version_string());
  DemoShape scaled = *shape;
  scaled.facet_size *= scale;
  scaled.facet_distance *= scale;
  scaled.cell_size *= scale;
  int failed = delaunay ? run_delaunay(off, out_path) : run_oracle(&scaled, out_path);
  printf("%s\n", failed ? "demo FAILED" : "demo OK");
  return failed ? 1 : 0;
}
