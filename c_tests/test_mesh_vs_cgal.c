/* delmesh's oracle-driven volume mesher (delmesh_domain_new_implicit / _labeled,
 * delmesh_mesher_run) against CGAL 5.5 Mesh_3 (make_mesh_3's refinement, no perturbation, no
 * exudation; CGAL's initial points replaced by crossings of random segments so that it finds
 * every component: ref_mesh3.cpp) on the same domains with the same criteria (METRICS.md).
 * delmesh gets no seed points. For each shape of shapes.h, on both meshes:
 * - validity: exact orientation, conformity, every vertex used (metrics_validity);
 * - quality: max radius-edge ratio <= the bound, min boundary-facet angle >= the facet-angle bound
 *   (computed in double, with a 1e-9 relative allowance for that rounding);
 * - boundary conformity: per subdomain, the faces between different labels (0 outside) form a
 *   closed, consistently oriented, edge-manifold surface whose components have the analytic Euler
 *   characteristics; every surface vertex (dimension 2, or on a boundary face) lies within
 *   1e-3 * bbox diagonal of the true surface; delmesh's reported facets (delmesh_mesh_facets with
 *   their (from, to) labels) are exactly those faces, normal from `from` to `to`;
 * - volume per subdomain against the analytic one (the tanglecube's by numerical integration):
 *   our relative error <= CGAL's + 0.001, and < 0.005 on the unit sphere at facet size 0.05;
 * - two-sided Hausdorff distance between the boundary faces and the true surface (boundary.h):
 *   our max <= 1.1 * CGAL's;
 * - vertex count within 15% of CGAL's.
 * Delmesh's figures are asserted; CGAL's are printed beside them (a self-test first checks that
 * CGAL's sphere passes the same checks and that the checks catch damaged copies).
 * Usage: test_mesh_vs_cgal [--small]
 * `--small` (the sanitizer run's flag) changes nothing here: delmesh and the CGAL shim are not
 * instrumented, so the full cases take about 25 s under the sanitizers too, and coarser criteria
 * would make the max and ratio figures compare single facets rather than the meshers. */
#define _POSIX_C_SOURCE 200809L

#include "boundary.h"
#include "check.h"
#include "mesh_run.h"
#include "quality.h"
#include "metrics.h"
#include "ref_mesh3.h"
#include "shapes.h"

#include <delmesh.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RELATIVE_ERROR 1e-6      /* of the domains' surface points, relative to the bbox diagonal */
#define SURFACE_TOLERANCE 1e-3   /* surface vertices: distance to the surface / bbox diagonal */
#define ROUNDING 1e-9            /* relative allowance of the double-precision quality figures */
#define VOLUME_MARGIN 0.001      /* our relative volume error <= CGAL's + this */
#define SPHERE_VOLUME_ERROR 0.005 /* unit sphere at facet size 0.05 */
#define HAUSDORFF_FACTOR 1.1     /* our max <= this * CGAL's */
#define VERTEX_COUNT_SPREAD 0.15 /* |ours / CGAL's - 1| <= this */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- One mesh and its figures ----------------------------------------------------------------- */

typedef struct Result {
  double seconds;
  size_t n, tet_count;
  const double *xyz;
  const int8_t *dimensions;
  const uint32_t *tets;
  const int32_t *labels;
  int valid;
  char validity[256];
  BoundaryFace *faces;
  size_t face_count;
  int closed[SHAPE_MAX_LABELS + 1];
  SubdomainSurface surface[SHAPE_MAX_LABELS + 1];
  SurfaceVertices on_surface;
  double volume_error[SHAPE_MAX_LABELS + 1];
  Hausdorff hausdorff;
  double radius_edge, face_angle;
} Result;

/* Every figure of a mesh of shape `s` (the surface samples are shared by both meshes). */
static int analyze(Result *r, const Shape *s, const double *samples, size_t sample_count) {
  Validity v;
  r->valid = metrics_validity(r->xyz, r->n, r->tets, r->tet_count, NULL, NULL, 0, &v);
  metrics_validity_describe(&v, r->validity, sizeof r->validity);
  r->faces = boundary_faces(r->tets, r->labels, r->tet_count, &r->face_count);
  if (!r->faces) return 0;
  for (int k = 1; k <= s->labels; k++)
    r->closed[k] = boundary_subdomain_surface(r->faces, r->face_count, k, &r->surface[k]);
  double diagonal = shape_bbox_diagonal(s);
  r->on_surface = boundary_surface_vertices(r->xyz, r->n, r->dimensions, r->faces, r->face_count,
                                            s->distance, SURFACE_TOLERANCE * diagonal);
  double volumes[SHAPE_MAX_LABELS + 1];
  boundary_volumes(r->xyz, r->tets, r->labels, r->tet_count, s->labels, volumes);
  for (int k = 1; k <= s->labels; k++) r->volume_error[k] = metrics_relative_error(volumes[k], s->volume[k]);
  if (!boundary_hausdorff(r->xyz, r->faces, r->face_count, s->distance, samples, sample_count, &r->hausdorff))
    return 0;
  r->radius_edge = quality_tetrahedra(r->xyz, r->tets, r->tet_count).max_radius_edge;
  r->face_angle = 180.0;
  for (size_t i = 0; i < r->face_count; i++) {
    const uint32_t *v = r->faces[i].v;
    double angle = quality_triangle_min_angle(r->xyz + 3 * v[0], r->xyz + 3 * v[1], r->xyz + 3 * v[2]);
    r->face_angle = fmin(r->face_angle, angle);
  }
  return 1;
}

/* "closed, oriented, edge-manifold, χ = {2, 2}" or the defects. */
static void describe_surface(const Result *r, int label, char *buffer, size_t size) {
  const SubdomainSurface *f = &r->surface[label];
  int len = snprintf(buffer, size, "%zu faces, ", f->faces);
  if (r->closed[label])
    len += snprintf(buffer + len, size - (size_t)len, "closed, oriented, edge-manifold");
  else
    len += snprintf(buffer + len, size - (size_t)len, "%zu open, %zu non-manifold, %zu misoriented edges",
                    f->open_edges, f->nonmanifold_edges, f->misoriented_edges);
  len += snprintf(buffer + len, size - (size_t)len, ", %zu component%s, chi = {", f->components,
                  f->components == 1 ? "" : "s");
  for (size_t c = 0; c < f->components && c < BOUNDARY_MAX_COMPONENTS && len < (int)size; c++)
    len += snprintf(buffer + len, size - (size_t)len, "%s%d", c ? ", " : "", f->euler[c]);
  if (len < (int)size) snprintf(buffer + len, size - (size_t)len, "}");
}

static int topology_matches(const Result *r, const Shape *s, int label) {
  const SubdomainSurface *f = &r->surface[label];
  if (!r->closed[label] || f->components != (size_t)s->components[label]) return 0;
  for (int c = 0; c < s->components[label]; c++)
    if (f->euler[c] != s->euler[label][c]) return 0;
  return 1;
}

static double ratio(double ours, double theirs) { return theirs != 0 ? ours / theirs : NAN; }

/* ---- The cases ---------------------------------------------------------------------------------- */

typedef struct Case {
  ShapeId shape;
  RefMeshCriteria criteria;
} Case;

/* The reference side: CGAL Mesh_3 on the same domain. */
static int run_cgal(const Shape *s, const RefMeshCriteria *c, RefMesh *mesh, Result *r) {
  RefTiming timing = {0};
  int rc = s->implicit ? ref_cgal_mesh_implicit(s->implicit, NULL, s->bbox, RELATIVE_ERROR, c, mesh, &timing)
                       : ref_cgal_mesh_labeled(s->label, NULL, s->bbox, RELATIVE_ERROR, c, mesh, &timing);
  if (rc != 0) return 0;
  *r = (Result){.seconds = timing.seconds, .n = mesh->vertex_count, .tet_count = mesh->tet_count,
                .xyz = mesh->xyz, .dimensions = mesh->dimensions, .tets = mesh->tets, .labels = mesh->labels};
  return 1;
}

/* Our side, through the C API. Returns the status; *mesh is set on success. */
static DelmeshStatus run_delmesh(const Shape *s, const RefMeshCriteria *c, DelmeshMesh **mesh, Result *r) {
  double start = now();
  /* Refinement alone with CGAL's criteria only, as CGAL's side runs with no_perturb() and
   * no_exude(): no optimization, no surface sliver bound. */
  DelmeshStatus st = mesh_run(s, c, RELATIVE_ERROR, MESH_RUN_AS_CGAL, mesh);
  double seconds = now() - start;
  if (st != DELMESH_OK) return st;
  *r = (Result){.seconds = seconds, .n = delmesh_mesh_vertex_count(*mesh),
                .tet_count = delmesh_mesh_tetrahedron_count(*mesh), .xyz = delmesh_mesh_vertices(*mesh),
                .dimensions = delmesh_mesh_vertex_dimensions(*mesh), .tets = delmesh_mesh_tetrahedra(*mesh),
                .labels = delmesh_mesh_tetrahedron_labels(*mesh)};
  return st;
}

/* The checks hold on CGAL's sphere and catch damaged copies of its faces and tetrahedra. */
static void self_test(const Shape *s, const Result *cgal) {
  check_case(cgal->valid && topology_matches(cgal, s, 1) && cgal->on_surface.far == 0,
             "self-test: CGAL's %s is valid, its boundary closed with chi = 2, its surface vertices on the surface",
             s->name);
  size_t m = cgal->face_count;
  BoundaryFace *copy = malloc((m ? m : 1) * sizeof *copy);
  uint32_t *tets = malloc((cgal->tet_count ? cgal->tet_count : 1) * 4 * sizeof *tets);
  if (!copy || !tets || m < 10) {
    check_case(0, "self-test: out of memory or no faces");
    free(copy);
    free(tets);
    return;
  }
  memcpy(copy, cgal->faces, m * sizeof *copy);
  FaceComparison c = boundary_compare_faces(cgal->faces, m, copy, m);
  check_case(c.common == m && c.missing + c.extra + c.misoriented + c.wrong_labels == 0,
             "self-test: the faces compare equal to themselves");
  uint32_t t = copy[3].v[1];
  copy[3].v[1] = copy[3].v[2], copy[3].v[2] = t; /* one face flipped */
  copy[5].to = 7;                               /* one face mislabeled */
  copy[7] = copy[8];                            /* one face lost, one twice */
  c = boundary_compare_faces(cgal->faces, m, copy, m);
  check_case(c.misoriented == 1 && c.wrong_labels == 1 && c.missing == 1 && c.extra == 1 && c.common == m - 3,
             "self-test: a flipped, a mislabeled, a missing and a repeated face are caught");
  SubdomainSurface surface;
  int closed = boundary_subdomain_surface(copy, m, 1, &surface);
  check_case(!closed && surface.misoriented_edges > 0 && surface.open_edges > 0,
             "self-test: the surface check sees the flipped face (%zu misoriented edges) and the hole (%zu open edges)",
             surface.misoriented_edges, surface.open_edges);
  /* An interior tetrahedron (no boundary face) removed: a second boundary component, chi 2. */
  unsigned char *on_boundary = calloc(cgal->n ? cgal->n : 1, 1);
  size_t interior = cgal->tet_count;
  for (size_t i = 0; on_boundary && i < m; i++)
    for (int k = 0; k < 3; k++) on_boundary[cgal->faces[i].v[k]] = 1;
  for (size_t i = 0; on_boundary && i < cgal->tet_count && interior == cgal->tet_count; i++) {
    const uint32_t *q = cgal->tets + 4 * i;
    if (!on_boundary[q[0]] && !on_boundary[q[1]] && !on_boundary[q[2]] && !on_boundary[q[3]]) interior = i;
  }
  free(on_boundary);
  size_t kept = 0;
  for (size_t i = 0; i < cgal->tet_count; i++)
    if (i != interior) memcpy(tets + 4 * kept++, cgal->tets + 4 * i, 4 * sizeof *tets);
  size_t holed_count = 0;
  BoundaryFace *holed = boundary_faces(tets, cgal->labels, kept, &holed_count);
  closed = holed && boundary_subdomain_surface(holed, holed_count, 1, &surface);
  check_case(interior < cgal->tet_count && closed && surface.components == 2 && surface.euler[0] == 2 &&
                 surface.euler[1] == 2,
             "self-test: a cavity left by a removed tetrahedron is a second boundary component (%zu components)",
             surface.components);
  free(holed);
  free(tets);
  free(copy);
}

/* Our figures asserted against the bounds and CGAL's. */
static void compare(const char *name, const Shape *s, ShapeId shape, const RefMeshCriteria *c,
                    const DelmeshMesh *mesh, const Result *ours, const Result *theirs) {
  double diagonal = shape_bbox_diagonal(s);
  check_note("%s: %zu vertices, %zu tetrahedra, %.2f s; CGAL %zu vertices, %zu tetrahedra, %.2f s (time ratio CGAL/delmesh %.2f)",
             name, ours->n, ours->tet_count, ours->seconds, theirs->n, theirs->tet_count, theirs->seconds,
             ratio(theirs->seconds, ours->seconds));
  check_case(ours->valid, "%s: valid: %s (CGAL: %s)", name, ours->validity, theirs->validity);

  /* Quality */
  double bound = c->cell_radius_edge_ratio;
  if (bound > 0)
    check_case(ours->radius_edge <= bound * (1 + ROUNDING), "%s: max radius-edge ratio %.4f <= %g (CGAL %.4f)", name,
               ours->radius_edge, bound, theirs->radius_edge);
  if (c->facet_angle > 0)
    check_case(ours->face_angle >= c->facet_angle * (1 - ROUNDING), "%s: min boundary facet angle %.3f >= %g degrees (CGAL %.3f)",
               name, ours->face_angle, c->facet_angle, theirs->face_angle);

  /* Boundary conformity */
  for (int label = 1; label <= s->labels; label++) {
    char a[256], b[256], expected[64];
    int len = snprintf(expected, sizeof expected, "{");
    for (int j = 0; j < s->components[label]; j++)
      len += snprintf(expected + len, sizeof expected - (size_t)len, "%s%d", j ? ", " : "", s->euler[label][j]);
    snprintf(expected + len, sizeof expected - (size_t)len, "}");
    describe_surface(ours, label, a, sizeof a);
    describe_surface(theirs, label, b, sizeof b);
    check_case(topology_matches(ours, s, label), "%s: boundary of subdomain %d: %s, expected chi = %s (CGAL: %s)", name,
               label, a, expected, b);
  }
  check_case(ours->on_surface.far == 0,
             "%s: %zu surface vertices within %.0e * diagonal of the surface: %zu farther, max %.2e * diagonal (CGAL: %zu farther, max %.2e)",
             name, ours->on_surface.checked, SURFACE_TOLERANCE, ours->on_surface.far, ours->on_surface.max_distance / diagonal,
             theirs->on_surface.far, theirs->on_surface.max_distance / diagonal);
  if (ours->on_surface.volume_on_boundary || theirs->on_surface.volume_on_boundary)
    check_note("%s: boundary-face vertices reported of dimension 3: %zu (CGAL %zu)", name,
               ours->on_surface.volume_on_boundary, theirs->on_surface.volume_on_boundary);
  size_t reported_count = delmesh_mesh_facet_count(mesh);
  const uint32_t *facets = delmesh_mesh_facets(mesh);
  const int32_t *facet_labels = delmesh_mesh_facet_labels(mesh);
  BoundaryFace *reported = facets && facet_labels ? boundary_faces_from_facets(facets, facet_labels, reported_count) : NULL;
  FaceComparison fc = reported ? boundary_compare_faces(ours->faces, ours->face_count, reported, reported_count)
                               : (FaceComparison){0, 0, 0, ours->face_count, reported_count};
  check_case(reported && fc.common == ours->face_count && fc.common == reported_count,
             "%s: reported facets are the %zu label-change faces, normal from `from` to `to`: %zu reported, %zu equal, %zu misoriented, %zu wrong labels, %zu missing, %zu extra",
             name, ours->face_count, reported_count, fc.common, fc.misoriented, fc.wrong_labels, fc.missing, fc.extra);
  free(reported);

  /* Volume */
  for (int label = 1; label <= s->labels; label++) {
    double e = ours->volume_error[label], t = theirs->volume_error[label];
    check_case(e <= t + VOLUME_MARGIN, "%s: volume of subdomain %d, relative error to the %s %.6f: %.2e <= CGAL's %.2e + %g (ratio %.2f)",
               name, label, s->volume_source, s->volume[label], e, t, VOLUME_MARGIN, ratio(e, t));
  }
  if (shape == SHAPE_SPHERE && c->facet_size <= 0.05)
    check_case(ours->volume_error[1] < SPHERE_VOLUME_ERROR, "%s: volume relative error %.2e < %g", name,
               ours->volume_error[1], SPHERE_VOLUME_ERROR);

  /* Hausdorff distance */
  const Hausdorff *h = &ours->hausdorff, *g = &theirs->hausdorff;
  check_case(h->max <= HAUSDORFF_FACTOR * g->max,
             "%s: Hausdorff / diagonal: max %.2e (mesh->surface %.2e, surface->mesh %.2e), RMS %.2e / %.2e; CGAL max %.2e (%.2e, %.2e), RMS %.2e / %.2e; ratio %.2f <= %g (%zu + %zu samples)",
             name, h->max / diagonal, h->mesh_to_surface_max / diagonal, h->surface_to_mesh_max / diagonal,
             h->mesh_to_surface_rms / diagonal, h->surface_to_mesh_rms / diagonal, g->max / diagonal,
             g->mesh_to_surface_max / diagonal, g->surface_to_mesh_max / diagonal, g->mesh_to_surface_rms / diagonal,
             g->surface_to_mesh_rms / diagonal, ratio(h->max, g->max), HAUSDORFF_FACTOR, h->mesh_samples,
             h->surface_samples);

  /* Size */
  double r = ratio((double)ours->n, (double)theirs->n);
  check_case(fabs(r - 1) <= VERTEX_COUNT_SPREAD, "%s: %zu vertices, CGAL %zu: ratio %.3f within 1 +- %g", name, ours->n,
             theirs->n, r, VERTEX_COUNT_SPREAD);
}

static void run_case(const Case *k, int first) {
  Shape s = shape_get(k->shape);
  const RefMeshCriteria *c = &k->criteria;
  char name[160];
  snprintf(name, sizeof name, "%s (facet size %g)", s.name, c->facet_size);

  size_t sample_count = 0;
  double *samples = shape_surface_samples(&s, 60000, 1000, 0x5A3F1E00u + (uint64_t)k->shape, &sample_count);
  RefMesh ref_mesh = {0};
  Result theirs, ours;
  memset(&theirs, 0, sizeof theirs);
  memset(&ours, 0, sizeof ours);
  int cgal_ran = samples && run_cgal(&s, c, &ref_mesh, &theirs);
  if (check_case(cgal_ran, "%s: CGAL Mesh_3 ran%s%s", name, cgal_ran ? "" : ": ",
                 cgal_ran ? "" : samples ? ref_last_error() : "out of memory")) {
    if (!analyze(&theirs, &s, samples, sample_count)) check_case(0, "%s: CGAL's figures: out of memory", name);
    if (first) self_test(&s, &theirs);
    DelmeshMesh *mesh = NULL;
    DelmeshStatus st = run_delmesh(&s, c, &mesh, &ours);
    if (check_case(st == DELMESH_OK, "%s: delmesh ran (status %d)%s%s", name, (int)st,
                   st == DELMESH_OK ? "" : ": ", st == DELMESH_OK ? "" : delmesh_last_error_message()) &&
        check_case(analyze(&ours, &s, samples, sample_count), "%s: figures computed", name))
      compare(name, &s, k->shape, c, mesh, &ours, &theirs);
    delmesh_mesh_free(mesh);
  }
  free(ours.faces);
  free(theirs.faces);
  ref_mesh_free(&ref_mesh);
  free(samples);
}

int main(int argc, char **argv) {
  if (argc > 2 || (argc == 2 && strcmp(argv[1], "--small") != 0)) {
    fprintf(stderr, "usage: %s [--small]\n", argv[0]);
    return 2;
  }
  /* facet angle, facet size, facet distance, cell radius-edge ratio, cell size */
  static const Case cases[] = {
      {SHAPE_SPHERE, {30, 0.05, 0.01, 2, 0.05}},       {SHAPE_TORUS, {30, 0.05, 0.005, 2, 0.05}},
      {SHAPE_TANGLECUBE, {30, 0.1, 0.01, 2, 0.1}},     {SHAPE_TWO_SPHERES, {30, 0.05, 0.01, 2, 0.05}},
      {SHAPE_ELLIPSOID, {30, 0.05, 0.005, 2, 0.05}},   {SHAPE_NESTED_SPHERES, {30, 0.05, 0.01, 2, 0.05}},
      {SHAPE_SECTORS, {30, 0.05, 0.01, 2, 0.05}},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) run_case(&cases[i], i == 0);
  return check_finish();
}
