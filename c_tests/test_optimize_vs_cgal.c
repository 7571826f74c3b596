/* Mesh optimization after refinement: delmesh's defaults (its surface-sliver refinement
 * criterion, then sliver perturbation and exudation) against CGAL 5.5 Mesh_3 with its default optimizers,
 * perturb() then exude() (CGAL::perturb_mesh_3 and CGAL::exude_mesh_3 on the refined complex,
 * the calls make_mesh_3 makes; default sliver bounds, no time limit on either side, so that
 * neither result depends on the machine's speed). Same shapes and criteria as test_mesh_vs_cgal
 * (METRICS.md "Quality").
 *
 * Per case, delmesh runs three times on the same domain: with optimization 0 (refinement only),
 * and twice with the default optimization. Asserted, what the passes guarantee:
 * - the optimized mesh is valid (exact orientation, conformity, every vertex used) and its
 *   reported facets are its label-change faces;
 * - no point is added or removed, and no surface point moves: the same number of vertices, and
 *   the same coordinates, bit for bit, for every vertex of dimension 2 (perturbation moves
 *   vertices inside a subdomain only);
 * - the boundary is unchanged: the label-change faces (boundary and interfaces) before and after
 *   are the same set, compared by vertex coordinates bit for bit (vertex numbering may change),
 *   orientation and labels;
 * - every subdomain's volume is unchanged to 1e-12 relative;
 * - the radius-edge bound met by refinement still holds;
 * - the smallest dihedral angle strictly increases, overall and over the cells with at most one
 *   boundary face. A cell with two boundary (or interface) faces has its four vertices on the
 *   surface and two faces that must stay, which leaves flips few ways to remove it; the
 *   surface-sliver criterion of refinement keeps such cells above 15 degrees (without it, the
 *   ellipsoid's worst cell is one of them, at 0.013 degrees, and exudation cannot raise it);
 *   their figures are reported;
 * - the two optimized runs give bit-identical arrays (vertices, dimensions, tetrahedra and their
 *   labels, facets and their labels).
 * And the targets of the optimization issue, which hold on every case: our min dihedral angle >= CGAL's, >= 12 degrees on the
 * sphere, torus and ellipsoid, our count of cells below 10 degrees <= CGAL's. Reported beside
 * them: both sides' counts below 5, 10 and 15 degrees, before and after optimization, and the
 * optimization times (ours: the run with optimization minus the run without).
 *
 * Usage: test_optimize_vs_cgal [--small]
 * By default the seven shapes of test_mesh_vs_cgal, about 90 s, most of it CGAL's exudation
 * (~12 s on 1.5e5 cells without a time limit). `--small` (the
 * sanitizer run's flag) keeps the ellipsoid and the two spheres at the same criteria (cells with
 * two boundary faces, a boundary of two components; about 10 s plain, 20 s sanitized): delmesh
 * and the CGAL shim are not instrumented, but the sanitizers' allocator serves them too and this
 * program's own figures are instrumented: the five default cases take over two minutes there. */
#define _POSIX_C_SOURCE 200809L

#include "boundary.h"
#include "check.h"
#include "mesh_run.h"
#include "metrics.h"
#include "quality.h"
#include "ref_mesh3.h"
#include "shapes.h"

#include <delmesh.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define RELATIVE_ERROR 1e-6     /* of the domains' surface points, relative to the bbox diagonal */
#define VOLUME_TOLERANCE 1e-12  /* relative change of a subdomain's volume by optimization */
#define ROUNDING 1e-9           /* relative allowance of the double-precision radius-edge ratio */
#define TARGET_DIHEDRAL 12.0    /* the bound on the sphere, torus and ellipsoid (degrees) */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- A mesh as arrays ---------------------------------------------------------------------------- */

typedef struct Arrays {
  size_t n, tet_count, facet_count;
  const double *xyz;
  const int8_t *dimensions;
  const uint32_t *tets;
  const int32_t *labels;
  const uint32_t *facets;        /* delmesh only */
  const int32_t *facet_labels;   /* delmesh only */
} Arrays;

static Arrays delmesh_arrays(const DelmeshMesh *m) {
  Arrays a = {delmesh_mesh_vertex_count(m), delmesh_mesh_tetrahedron_count(m), delmesh_mesh_facet_count(m),
              delmesh_mesh_vertices(m), delmesh_mesh_vertex_dimensions(m), delmesh_mesh_tetrahedra(m),
              delmesh_mesh_tetrahedron_labels(m), delmesh_mesh_facets(m), delmesh_mesh_facet_labels(m)};
  return a;
}

static Arrays ref_arrays(const RefMesh *m) {
  Arrays a = {m->vertex_count, m->tet_count, 0, m->xyz, m->dimensions, m->tets, m->labels, NULL, NULL};
  return a;
}

/* Equal sizes and equal bytes (both NULL counts as equal only when the size is 0). */
static int same_bytes(const void *a, const void *b, size_t size) {
  if (size == 0) return 1;
  return a && b && memcmp(a, b, size) == 0;
}

/* The arrays of two runs, bit for bit. */
static int identical(const Arrays *a, const Arrays *b) {
  return a->n == b->n && a->tet_count == b->tet_count && a->facet_count == b->facet_count &&
         same_bytes(a->xyz, b->xyz, 3 * a->n * sizeof(double)) &&
         same_bytes(a->dimensions, b->dimensions, a->n * sizeof(int8_t)) &&
         same_bytes(a->tets, b->tets, 4 * a->tet_count * sizeof(uint32_t)) &&
         same_bytes(a->labels, b->labels, a->tet_count * sizeof(int32_t)) &&
         same_bytes(a->facets, b->facets, 3 * a->facet_count * sizeof(uint32_t)) &&
         same_bytes(a->facet_labels, b->facet_labels, 2 * a->facet_count * sizeof(int32_t));
}

/* ---- Sets compared by coordinates, bit for bit ------------------------------------------------- */

/* A label-change face by the coordinates of its vertices, rotated (orientation kept) so that the
 * vertex whose coordinate bytes compare smallest comes first. No padding: 9 doubles, 2 int32. */
typedef struct FaceKey {
  double c[9];
  int32_t from, to;
} FaceKey;

static int compare_bytes(const void *a, const void *b, size_t size) { return memcmp(a, b, size); }
static int compare_face_keys(const void *a, const void *b) { return compare_bytes(a, b, sizeof(FaceKey)); }
static int compare_points(const void *a, const void *b) { return compare_bytes(a, b, 3 * sizeof(double)); }

/* The faces as sorted keys (malloc'd, `count` entries). */
static FaceKey *face_keys(const double *xyz, const BoundaryFace *faces, size_t count) {
  FaceKey *keys = malloc((count ? count : 1) * sizeof *keys);
  if (!keys) return NULL;
  for (size_t i = 0; i < count; i++) {
    const uint32_t *v = faces[i].v;
    int first = 0;
    for (int k = 1; k < 3; k++)
      if (memcmp(xyz + 3 * v[k], xyz + 3 * v[first], 3 * sizeof(double)) < 0) first = k;
    memset(&keys[i], 0, sizeof keys[i]);
    for (int k = 0; k < 3; k++) memcpy(keys[i].c + 3 * k, xyz + 3 * v[(first + k) % 3], 3 * sizeof(double));
    keys[i].from = faces[i].from;
    keys[i].to = faces[i].to;
  }
  qsort(keys, count, sizeof *keys, compare_face_keys);
  return keys;
}

typedef struct Difference {
  size_t common, only_before, only_after;
} Difference;

/* Two sorted arrays of `size`-byte records compared as multisets. */
static Difference sorted_difference(const void *before, size_t nb, const void *after, size_t na, size_t size) {
  Difference d = {0, 0, 0};
  const unsigned char *p = before, *q = after;
  size_t i = 0, j = 0;
  while (i < nb && j < na) {
    int c = memcmp(p + i * size, q + j * size, size);
    if (c == 0) d.common++, i++, j++;
    else if (c < 0) d.only_before++, i++;
    else d.only_after++, j++;
  }
  d.only_before += nb - i;
  d.only_after += na - j;
  return d;
}

/* The coordinates of the vertices of dimension 2 (on the surface), sorted (malloc'd, 3 doubles
 * each, *count of them). */
static double *sorted_surface_points(const Arrays *a, size_t *count) {
  double *p = malloc((a->n ? a->n : 1) * 3 * sizeof *p);
  if (!p) return NULL;
  *count = 0;
  for (size_t i = 0; i < a->n; i++)
    if (a->dimensions[i] == 2) memcpy(p + 3 * (*count)++, a->xyz + 3 * i, 3 * sizeof *p);
  qsort(p, *count, 3 * sizeof *p, compare_points);
  return p;
}

/* ---- The runs ----------------------------------------------------------------------------------- */

typedef struct Case {
  ShapeId shape;
  RefMeshCriteria criteria;
  int small; /* run by --small too */
} Case;

enum { OPTIMIZE_NONE, OPTIMIZE_DEFAULT };

/* delmesh on the shape with the criteria, with no optimization or the default one. */
static DelmeshStatus run_delmesh(const Shape *s, const RefMeshCriteria *c, int optimize, DelmeshMesh **mesh,
                                 double *seconds) {
  double start = now();
  DelmeshStatus st = mesh_run(s, c, RELATIVE_ERROR, optimize == OPTIMIZE_NONE ? MESH_RUN_REFINE : MESH_RUN_DEFAULT, mesh);
  *seconds = now() - start;
  return st;
}

/* CGAL: refinement (exported), then perturb_mesh_3 and exude_mesh_3, no time limit. */
static int run_cgal(const Shape *s, const RefMeshCriteria *c, RefMesh *refined, RefMesh *optimized,
                    RefMeshTiming *timing) {
  RefMeshOptions options = {REF_OPTIMIZE_SEPARATE, 0.0, refined};
  return s->implicit
             ? ref_cgal_mesh_implicit_optimized(s->implicit, NULL, s->bbox, RELATIVE_ERROR, c, &options, optimized, timing)
             : ref_cgal_mesh_labeled_optimized(s->label, NULL, s->bbox, RELATIVE_ERROR, c, &options, optimized, timing);
}

static QualitySummary summary(const Arrays *a) { return quality_tetrahedra(a->xyz, a->tets, a->tet_count); }

static double ratio(double a, double b) { return b != 0 ? a / b : NAN; }

/* The shapes of the 12-degree target. */
static int dihedral_target_applies(ShapeId shape) {
  return shape == SHAPE_SPHERE || shape == SHAPE_TORUS || shape == SHAPE_ELLIPSOID;
}

/* A tetrahedron with two label-change faces has its four vertices on the boundary (or on
 * interfaces) and two faces that optimization must keep, which leaves flips few ways to remove it;
 * moving a vertex can. The quality of those ("locked") and of the other ("free") cells. */
typedef struct Split {
  QualitySummary free, locked;
  int ok;
} Split;

static int compare_triples(const void *a, const void *b) { return memcmp(a, b, 3 * sizeof(uint32_t)); }

static void sort3(uint32_t t[3]) {
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && t[j - 1] > t[j]; j--) {
      uint32_t x = t[j];
      t[j] = t[j - 1], t[j - 1] = x;
    }
}

static Split split_locked(const Arrays *a) {
  Split r;
  memset(&r, 0, sizeof r);
  size_t face_count = 0, m = a->tet_count;
  BoundaryFace *faces = boundary_faces(a->tets, a->labels, m, &face_count);
  uint32_t *triples = malloc((face_count ? face_count : 1) * 3 * sizeof *triples);
  uint32_t *free_tets = malloc((m ? m : 1) * 4 * sizeof *free_tets);
  uint32_t *locked_tets = malloc((m ? m : 1) * 4 * sizeof *locked_tets);
  if (faces && triples && free_tets && locked_tets) {
    for (size_t i = 0; i < face_count; i++) {
      memcpy(triples + 3 * i, faces[i].v, 3 * sizeof *triples);
      sort3(triples + 3 * i);
    }
    qsort(triples, face_count, 3 * sizeof *triples, compare_triples);
    size_t free_count = 0, locked_count = 0;
    for (size_t t = 0; t < m; t++) {
      const uint32_t *q = a->tets + 4 * t;
      int on_boundary = 0;
      for (int k = 0; k < 4; k++) {
        uint32_t f[3] = {q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]};
        sort3(f);
        on_boundary += bsearch(f, triples, face_count, 3 * sizeof *triples, compare_triples) != NULL;
      }
      if (on_boundary >= 2) memcpy(locked_tets + 4 * locked_count++, q, 4 * sizeof *q);
      else memcpy(free_tets + 4 * free_count++, q, 4 * sizeof *q);
    }
    r.free = quality_tetrahedra(a->xyz, free_tets, free_count);
    r.locked = quality_tetrahedra(a->xyz, locked_tets, locked_count);
    r.ok = 1;
  }
  free(faces);
  free(triples);
  free(free_tets);
  free(locked_tets);
  return r;
}

/* The passes' guarantees: `before` is the refinement-only mesh, `after` the optimized one. */
static void check_optimization(const char *name, const Shape *s, const RefMeshCriteria *c, const Arrays *before,
                            const Arrays *after, const QualitySummary *qb, const QualitySummary *qa) {
  Validity v;
  char text[256];
  int valid = metrics_validity(after->xyz, after->n, after->tets, after->tet_count, NULL, NULL, 0, &v);
  metrics_validity_describe(&v, text, sizeof text);
  check_case(valid, "%s: optimized mesh valid: %s", name, text);

  size_t nb = 0, na = 0;
  double *pb = sorted_surface_points(before, &nb), *pa = sorted_surface_points(after, &na);
  Difference dp = pb && pa ? sorted_difference(pb, nb, pa, na, 3 * sizeof(double)) : (Difference){0, nb, na};
  check_case(pb && pa && before->n == after->n && dp.only_before == 0 && dp.only_after == 0,
             "%s: %zu vertices before, %zu after; the %zu surface vertices kept bit for bit: %zu common, %zu gone, "
             "%zu new",
             name, before->n, after->n, nb, dp.common, dp.only_before, dp.only_after);
  free(pb);
  free(pa);

  size_t fb_count = 0, fa_count = 0;
  BoundaryFace *fb = boundary_faces(before->tets, before->labels, before->tet_count, &fb_count);
  BoundaryFace *fa = boundary_faces(after->tets, after->labels, after->tet_count, &fa_count);
  FaceKey *kb = fb ? face_keys(before->xyz, fb, fb_count) : NULL;
  FaceKey *ka = fa ? face_keys(after->xyz, fa, fa_count) : NULL;
  Difference df = kb && ka ? sorted_difference(kb, fb_count, ka, fa_count, sizeof(FaceKey))
                           : (Difference){0, fb_count, fa_count};
  check_case(kb && ka && fb_count > 0 && df.only_before == 0 && df.only_after == 0,
             "%s: boundary and interface faces unchanged (coordinates bit for bit, orientation, labels): %zu before, %zu after, %zu common, %zu gone, %zu new",
             name, fb_count, fa_count, df.common, df.only_before, df.only_after);
  free(kb);
  free(ka);

  BoundaryFace *reported = after->facets && after->facet_labels
                               ? boundary_faces_from_facets(after->facets, after->facet_labels, after->facet_count)
                               : NULL;
  FaceComparison fc = reported && fa ? boundary_compare_faces(fa, fa_count, reported, after->facet_count)
                                     : (FaceComparison){0, 0, 0, fa_count, after->facet_count};
  check_case(reported && fa && fc.common == fa_count && fc.common == after->facet_count,
             "%s: optimized mesh's reported facets are its %zu label-change faces: %zu equal, %zu misoriented, %zu wrong labels, %zu missing, %zu extra",
             name, fa_count, fc.common, fc.misoriented, fc.wrong_labels, fc.missing, fc.extra);
  free(reported);
  free(fb);
  free(fa);

  double vb[SHAPE_MAX_LABELS + 1], va[SHAPE_MAX_LABELS + 1];
  boundary_volumes(before->xyz, before->tets, before->labels, before->tet_count, s->labels, vb);
  boundary_volumes(after->xyz, after->tets, after->labels, after->tet_count, s->labels, va);
  for (int k = 1; k <= s->labels; k++) {
    double e = metrics_relative_error(va[k], vb[k]);
    check_case(e <= VOLUME_TOLERANCE, "%s: volume of subdomain %d unchanged: %.17g -> %.17g, relative change %.1e <= %g",
               name, k, vb[k], va[k], e, VOLUME_TOLERANCE);
  }

  if (c->cell_radius_edge_ratio > 0)
    check_case(qa->max_radius_edge <= c->cell_radius_edge_ratio * (1 + ROUNDING),
               "%s: max radius-edge ratio after optimization %.4f <= %g (before %.4f)", name, qa->max_radius_edge,
               c->cell_radius_edge_ratio, qb->max_radius_edge);
  check_case(qa->min_dihedral > qb->min_dihedral,
             "%s: optimization raises the min dihedral angle: %.3f -> %.3f degrees; below 5/10/15: %zu/%zu/%zu -> %zu/%zu/%zu",
             name, qb->min_dihedral, qa->min_dihedral, qb->dihedral_below[0], qb->dihedral_below[1],
             qb->dihedral_below[2], qa->dihedral_below[0], qa->dihedral_below[1], qa->dihedral_below[2]);
  Split sb = split_locked(before), sa = split_locked(after);
  check_case(sb.ok && sa.ok && sa.free.min_dihedral > sb.free.min_dihedral,
             "%s: optimization raises the min dihedral angle of the cells with at most one boundary face: %.3f -> %.3f degrees",
             name, sb.free.min_dihedral, sa.free.min_dihedral);
  check_note("%s: cells with two boundary faces (hardly removable by flips): %zu -> %zu, min dihedral %.3f -> %.3f, below 5/10/15 %zu/%zu/%zu -> %zu/%zu/%zu",
             name, sb.locked.tetrahedra, sa.locked.tetrahedra, sb.locked.min_dihedral, sa.locked.min_dihedral,
             sb.locked.dihedral_below[0], sb.locked.dihedral_below[1], sb.locked.dihedral_below[2],
             sa.locked.dihedral_below[0], sa.locked.dihedral_below[1], sa.locked.dihedral_below[2]);
}

static void run_case(const Case *k) {
  Shape s = shape_get(k->shape);
  const RefMeshCriteria *c = &k->criteria;
  char name[160];
  snprintf(name, sizeof name, "%s (facet size %g)", s.name, c->facet_size);

  RefMesh cgal_refined, cgal_optimized;
  RefMeshTiming timing;
  memset(&cgal_refined, 0, sizeof cgal_refined);
  memset(&cgal_optimized, 0, sizeof cgal_optimized);
  memset(&timing, 0, sizeof timing);
  int cgal_ran = run_cgal(&s, c, &cgal_refined, &cgal_optimized, &timing) == 0;
  DelmeshMesh *plain = NULL, *optimized = NULL, *again = NULL;
  double t_plain = 0, t_optimized = 0, t_again = 0;
  DelmeshStatus s1 = run_delmesh(&s, c, OPTIMIZE_NONE, &plain, &t_plain);
  DelmeshStatus s2 = run_delmesh(&s, c, OPTIMIZE_DEFAULT, &optimized, &t_optimized);
  DelmeshStatus s3 = run_delmesh(&s, c, OPTIMIZE_DEFAULT, &again, &t_again);
  int ok = check_case(cgal_ran, "%s: CGAL Mesh_3 ran, then perturb_mesh_3 (%s) and exude_mesh_3 (%s)%s%s", name,
                      ref_optimizer_code_name(timing.perturb_code), ref_optimizer_code_name(timing.exude_code),
                      cgal_ran ? "" : ": ", cgal_ran ? "" : ref_last_error());
  ok &= check_case(s1 == DELMESH_OK && s2 == DELMESH_OK && s3 == DELMESH_OK,
                   "%s: delmesh ran without and twice with the default optimization (statuses %d %d %d)%s%s", name,
                   (int)s1, (int)s2, (int)s3, s1 == DELMESH_OK && s2 == DELMESH_OK && s3 == DELMESH_OK ? "" : ": ",
                   s1 == DELMESH_OK && s2 == DELMESH_OK && s3 == DELMESH_OK ? "" : delmesh_last_error_message());
  if (ok) {
    Arrays ours0 = delmesh_arrays(plain), ours = delmesh_arrays(optimized), ours2 = delmesh_arrays(again);
    Arrays theirs0 = ref_arrays(&cgal_refined), theirs = ref_arrays(&cgal_optimized);
    QualitySummary q0 = summary(&ours0), q = summary(&ours), g0 = summary(&theirs0), g = summary(&theirs);
    double t_exude = t_optimized - t_plain;
    check_note("%s: %zu vertices, %zu tetrahedra (%zu before optimization); CGAL %zu vertices, %zu tetrahedra (%zu before perturbation)",
               name, ours.n, ours.tet_count, ours0.tet_count, theirs.n, theirs.tet_count, theirs0.tet_count);
    check_note("%s: min dihedral angle (degrees) ours %.3f, CGAL %.3f (refinement alone: ours %.3f, CGAL %.3f)", name,
               q.min_dihedral, g.min_dihedral, q0.min_dihedral, g0.min_dihedral);
    check_note("%s: tetrahedra below 5/10/15 degrees: ours %zu/%zu/%zu, CGAL %zu/%zu/%zu (refinement alone: ours %zu/%zu/%zu, CGAL %zu/%zu/%zu)",
               name, q.dihedral_below[0], q.dihedral_below[1], q.dihedral_below[2], g.dihedral_below[0],
               g.dihedral_below[1], g.dihedral_below[2], q0.dihedral_below[0], q0.dihedral_below[1],
               q0.dihedral_below[2], g0.dihedral_below[0], g0.dihedral_below[1], g0.dihedral_below[2]);
    check_note("%s: optimization time: ours ~%.3f s (run with optimization %.3f s - without %.3f s), CGAL %.3f s (perturb %.3f s + exude %.3f s; refinement %.3f s); ratio CGAL/ours %.2f",
               name, t_exude, t_optimized, t_plain, timing.perturb_seconds + timing.exude_seconds,
               timing.perturb_seconds, timing.exude_seconds, timing.refine_seconds,
               ratio(timing.perturb_seconds + timing.exude_seconds, t_exude));

    check_optimization(name, &s, c, &ours0, &ours, &q0, &q);
    check_case(identical(&ours, &ours2),
               "%s: two optimized runs give bit-identical arrays (%zu vertices, %zu tetrahedra, %zu facets)", name, ours.n,
               ours.tet_count, ours.facet_count);

    /* The targets. */
    check_case(q.min_dihedral >= g.min_dihedral, "%s: min dihedral angle %.3f >= CGAL's %.3f degrees (ratio %.2f)", name,
               q.min_dihedral, g.min_dihedral, ratio(q.min_dihedral, g.min_dihedral));
    check_case(q.dihedral_below[1] <= g.dihedral_below[1], "%s: tetrahedra below 10 degrees: %zu <= CGAL's %zu", name,
               q.dihedral_below[1], g.dihedral_below[1]);
    if (dihedral_target_applies(k->shape) && c->facet_size <= 0.05)
      check_case(q.min_dihedral >= TARGET_DIHEDRAL, "%s: min dihedral angle %.3f >= %g degrees (CGAL %.3f)", name,
                 q.min_dihedral, TARGET_DIHEDRAL, g.min_dihedral);
  }
  delmesh_mesh_free(plain);
  delmesh_mesh_free(optimized);
  delmesh_mesh_free(again);
  ref_mesh_free(&cgal_refined);
  ref_mesh_free(&cgal_optimized);
}

int main(int argc, char **argv) {
  int small = argc == 2 && strcmp(argv[1], "--small") == 0;
  if (argc > 2 || (argc == 2 && !small)) {
    fprintf(stderr, "usage: %s [--small]\n", argv[0]);
    return 2;
  }
  /* facet angle, facet size, facet distance, cell radius-edge ratio, cell size: test_mesh_vs_cgal's;
   * then whether --small runs it */
  static const Case cases[] = {
      {SHAPE_SPHERE, {30, 0.05, 0.01, 2, 0.05}, 0},          {SHAPE_TORUS, {30, 0.05, 0.005, 2, 0.05}, 0},
      {SHAPE_ELLIPSOID, {30, 0.05, 0.005, 2, 0.05}, 1},      {SHAPE_TWO_SPHERES, {30, 0.05, 0.01, 2, 0.05}, 1},
      {SHAPE_SECTORS, {30, 0.05, 0.01, 2, 0.05}, 0},         {SHAPE_TANGLECUBE, {30, 0.1, 0.01, 2, 0.1}, 0},
      {SHAPE_NESTED_SPHERES, {30, 0.05, 0.01, 2, 0.05}, 0},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    if (!small || cases[i].small) run_case(&cases[i]);
  return check_finish();
}
