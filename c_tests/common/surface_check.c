#include "surface_check.h"

#include "boundary.h"
#include "metrics.h"
#include "quality.h"
#include "ref.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double *point(const double *xyz, uint32_t i) { return xyz + 3 * (size_t)i; }

/* ---- Faces keyed by their sorted vertices ----------------------------------------------------------
 * parity 1 when sorting the (oriented) triple took an odd permutation: two orientations of one
 * triangle have different parities. */

typedef struct Key {
  uint32_t v[3];
  uint32_t parity;
  size_t index; /* tetrahedron, or surface triangle */
} Key;

static Key make_key(uint32_t a, uint32_t b, uint32_t c, size_t index) {
  Key k = {{a, b, c}, 0, index};
  for (int pass = 0; pass < 3; pass++) {
    int i = pass == 1 ? 1 : 0;
    if (k.v[i] > k.v[i + 1]) {
      uint32_t t = k.v[i];
      k.v[i] = k.v[i + 1];
      k.v[i + 1] = t;
      k.parity ^= 1;
    }
  }
  return k;
}

static int compare_triples(const Key *a, const Key *b) {
  for (int k = 0; k < 3; k++)
    if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
  return 0;
}

static int compare_keys(const void *pa, const void *pb) {
  const Key *a = pa, *b = pb;
  int c = compare_triples(a, b);
  if (c) return c;
  return (a->index > b->index) - (a->index < b->index);
}

/* First key in sorted[0..count) with the triple of k (count if none). */
static size_t lower_bound(const Key *sorted, size_t count, const Key *k) {
  size_t lo = 0, hi = count;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (compare_triples(&sorted[mid], k) < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* The four outward faces of every (positively oriented) tetrahedron, sorted. */
static Key *tetrahedron_faces(const uint32_t *tets, size_t count) {
  Key *f = malloc((count ? count : 1) * 4 * sizeof *f);
  if (!f) return NULL;
  for (size_t t = 0; t < count; t++) {
    const uint32_t *q = tets + 4 * t;
    f[4 * t] = make_key(q[1], q[2], q[3], t);
    f[4 * t + 1] = make_key(q[0], q[3], q[2], t);
    f[4 * t + 2] = make_key(q[0], q[1], q[3], t);
    f[4 * t + 3] = make_key(q[0], q[2], q[1], t);
  }
  qsort(f, 4 * count, sizeof *f, compare_keys);
  return f;
}

/* ---- Exact point tests ------------------------------------------------------------------------------ */

static int orient(const double *a, const double *b, const double *c, const double *d) {
  return ref_orient3d_exact(a, b, c, d);
}

/* Whether p, known coplanar with the triangle abc (non-degenerate), lies in it (closed). */
static int coplanar_inside(const double *a, const double *b, const double *c, const double *p) {
  double u[3], v[3], n[3];
  for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
  n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
  int axis = fabs(n[0]) >= fabs(n[1]) && fabs(n[0]) >= fabs(n[2]) ? 0 : fabs(n[1]) >= fabs(n[2]) ? 1 : 2;
  /* q off the plane: a moved along the axis the normal leans on most (exactly off the plane
   * whenever that normal component is not zero; checked below). */
  double q[3] = {a[0], a[1], a[2]};
  q[axis] += fmax(1.0, fabs(a[axis]));
  int s = orient(a, b, c, q);
  if (s == 0) { /* the floating normal misled: try the other axes */
    for (int k = 0; k < 3 && s == 0; k++) {
      q[0] = a[0], q[1] = a[1], q[2] = a[2];
      q[k] += fmax(1.0, fabs(a[k]));
      s = orient(a, b, c, q);
    }
    if (s == 0) return 1; /* a degenerate triangle: count it as touched */
  }
  return orient(a, b, p, q) * s >= 0 && orient(b, c, p, q) * s >= 0 && orient(c, a, p, q) * s >= 0;
}

/* Whether p lies in the closed, positively oriented tetrahedron abcd. */
static int inside_tetrahedron(const double *a, const double *b, const double *c, const double *d, const double *p) {
  for (int k = 0; k < 3; k++) {
    double lo = fmin(fmin(a[k], b[k]), fmin(c[k], d[k])), hi = fmax(fmax(a[k], b[k]), fmax(c[k], d[k]));
    if (p[k] < lo || p[k] > hi) return 0;
  }
  return orient(p, b, c, d) >= 0 && orient(a, p, c, d) >= 0 && orient(a, b, p, d) >= 0 && orient(a, b, c, p) >= 0;
}

/* ---- Steiner points on the surface: a bucket grid of the triangles' bounding boxes ------------- */

typedef struct Grid {
  double lo[3], cell[3];
  size_t dim[3];
  size_t *start; /* CSR over cells */
  uint32_t *items;
} Grid;

static void cell_range(const Grid *g, const double lo[3], const double hi[3], size_t a[3], size_t b[3]) {
  for (int k = 0; k < 3; k++) {
    double x = floor((lo[k] - g->lo[k]) / g->cell[k]) - 1, y = floor((hi[k] - g->lo[k]) / g->cell[k]) + 1;
    a[k] = x < 0 ? 0 : x >= (double)g->dim[k] ? g->dim[k] - 1 : (size_t)x;
    b[k] = y < 0 ? 0 : y >= (double)g->dim[k] ? g->dim[k] - 1 : (size_t)y;
  }
}

static void triangle_box(const double *xyz, const uint32_t *t, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; k++) {
    double x = point(xyz, t[0])[k], y = point(xyz, t[1])[k], z = point(xyz, t[2])[k];
    lo[k] = fmin(fmin(x, y), z);
    hi[k] = fmax(fmax(x, y), z);
  }
}

static int grid_build(Grid *g, const double *xyz, const uint32_t *tris, size_t m) {
  memset(g, 0, sizeof *g);
  double hi[3];
  for (int k = 0; k < 3; k++) g->lo[k] = INFINITY, hi[k] = -INFINITY;
  for (size_t t = 0; t < m; t++) {
    double a[3], b[3];
    triangle_box(xyz, tris + 3 * t, a, b);
    for (int k = 0; k < 3; k++) g->lo[k] = fmin(g->lo[k], a[k]), hi[k] = fmax(hi[k], b[k]);
  }
  size_t side = 1;
  while (side * side * side < 2 * m && side < 128) side++;
  size_t cells = 1;
  for (int k = 0; k < 3; k++) {
    g->dim[k] = side;
    g->cell[k] = (hi[k] - g->lo[k]) / (double)side;
    if (!(g->cell[k] > 0)) g->cell[k] = 1; /* a flat extent */
    cells *= side;
  }
  g->start = calloc(cells + 1, sizeof *g->start);
  if (!g->start) return 0;
  for (int pass = 0; pass < 2; pass++) {
    for (size_t t = 0; t < m; t++) {
      double a[3], b[3];
      size_t i0[3], i1[3];
      triangle_box(xyz, tris + 3 * t, a, b);
      cell_range(g, a, b, i0, i1);
      for (size_t x = i0[0]; x <= i1[0]; x++)
        for (size_t y = i0[1]; y <= i1[1]; y++)
          for (size_t z = i0[2]; z <= i1[2]; z++) {
            size_t c = (x * side + y) * side + z;
            if (pass == 0)
              g->start[c + 1]++;
            else
              g->items[g->start[c]++] = (uint32_t)t;
          }
    }
    if (pass == 0) {
      for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
      g->items = malloc((g->start[cells] ? g->start[cells] : 1) * sizeof *g->items);
      if (!g->items) return 0;
    } else {
      for (size_t c = cells; c > 0; c--) g->start[c] = g->start[c - 1]; /* undo the fill shift */
      g->start[0] = 0;
    }
  }
  return 1;
}

static void grid_free(Grid *g) {
  free(g->start);
  free(g->items);
}

/* Whether p is on one of the triangles (exact). */
static int on_surface(const Grid *g, const double *xyz, const uint32_t *tris, const double *p) {
  size_t a[3];
  for (int k = 0; k < 3; k++) { /* the cell of p (each triangle is in its box's cells and one more around) */
    double x = floor((p[k] - g->lo[k]) / g->cell[k]);
    if (x < 0 || x > (double)g->dim[k]) return 0; /* outside every triangle's box */
    a[k] = x >= (double)g->dim[k] ? g->dim[k] - 1 : (size_t)x;
  }
  size_t c = (a[0] * g->dim[1] + a[1]) * g->dim[2] + a[2];
  for (size_t i = g->start[c]; i < g->start[c + 1]; i++) {
    const uint32_t *t = tris + 3 * (size_t)g->items[i];
    double lo[3], hi[3];
    triangle_box(xyz, t, lo, hi);
    if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
    const double *u = point(xyz, t[0]), *v = point(xyz, t[1]), *w = point(xyz, t[2]);
    if (orient(u, v, w, p) == 0 && coplanar_inside(u, v, w, p)) return 1;
  }
  return 0;
}

/* ---- Volumes in long double --------------------------------------------------------------------------
 * Rounding: with eps = LDBL_EPSILON / 2 (2^-64 for x87 extended precision), the volume
 * det(b-a, c-a, d-a) / 6 of one tetrahedron (or cone) is computed with an error below
 * 10 eps P / 6, P the sum of the six products |u_i v_j w_k| of the determinant's expansion (the
 * three differences carry eps each, the 2x2 minors, products and sums up to six more). The
 * compensated (Neumaier) sum adds about eps |sum|. So the relative difference of the two volume
 * figures of a label is below (sum of 10 eps P / 6 over its tetrahedra and its triangles'
 * cones + 2 eps |V|) / |V|: surface_check reports it as volume_error_bound, and the check's
 * tolerance SURFACE_VOLUME_TOLERANCE (1e-12) holds only when that bound is far below it. */

typedef struct LSum {
  long double sum, compensation, bound;
} LSum;

static void lsum_add(LSum *s, long double x) {
  long double t = s->sum + x;
  if (fabsl(s->sum) >= fabsl(x))
    s->compensation += (s->sum - t) + x;
  else
    s->compensation += (x - t) + s->sum;
  s->sum = t;
}

/* det(b-a, c-a, d-a) / 6, its rounding bound added to *bound. */
static long double volume6(const double *a, const double *b, const double *c, const double *d, long double *bound) {
  long double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) {
    u[k] = (long double)b[k] - a[k];
    v[k] = (long double)c[k] - a[k];
    w[k] = (long double)d[k] - a[k];
  }
  long double m0 = v[1] * w[2] - v[2] * w[1], m1 = v[2] * w[0] - v[0] * w[2], m2 = v[0] * w[1] - v[1] * w[0];
  long double p = fabsl(u[0]) * (fabsl(v[1] * w[2]) + fabsl(v[2] * w[1])) +
                  fabsl(u[1]) * (fabsl(v[2] * w[0]) + fabsl(v[0] * w[2])) +
                  fabsl(u[2]) * (fabsl(v[0] * w[1]) + fabsl(v[1] * w[0]));
  *bound += 10 * (LDBL_EPSILON / 2) * p / 6;
  return (u[0] * m0 + u[1] * m1 + u[2] * m2) / 6;
}

/* ---- The check ------------------------------------------------------------------------------------ */

static int compare_i32(const void *pa, const void *pb) {
  int32_t a = *(const int32_t *)pa, b = *(const int32_t *)pb;
  return (a > b) - (a < b);
}

static size_t label_index(const int32_t *sorted, size_t count, int32_t label) {
  size_t lo = 0, hi = count;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (sorted[mid] < label)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < count && sorted[lo] == label ? lo : count;
}

/* The circumcenter of tetrahedron abcd (long double arithmetic); 0 when it is flat. */
static int circumcenter(const double *a, const double *b, const double *c, const double *d, double out[3]) {
  long double u[3], v[3], w[3], vw[3], wu[3], uv[3];
  for (int k = 0; k < 3; k++) u[k] = (long double)b[k] - a[k], v[k] = (long double)c[k] - a[k], w[k] = (long double)d[k] - a[k];
  for (int k = 0; k < 3; k++) {
    int i = (k + 1) % 3, j = (k + 2) % 3;
    vw[k] = v[i] * w[j] - v[j] * w[i];
    wu[k] = w[i] * u[j] - w[j] * u[i];
    uv[k] = u[i] * v[j] - u[j] * v[i];
  }
  long double det = 2 * (u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2]);
  if (det == 0) return 0;
  long double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2],
              ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  for (int k = 0; k < 3; k++) out[k] = (double)(a[k] + (uu * vw[k] + vv * wu[k] + ww * uv[k]) / det);
  return 1;
}

static long double distance2(const double *p, const double *q) {
  long double s = 0;
  for (int k = 0; k < 3; k++) s += ((long double)p[k] - q[k]) * ((long double)p[k] - q[k]);
  return s;
}

/* Whether p lies in the diametral ball of segment ab or of triangle abc (the ball whose
 * equator is its circumcircle), with the relative allowance. */
static int in_diametral_ball(const double *a, const double *b, const double *c, const double *p) {
  const double *e[3][2] = {{a, b}, {b, c}, {c, a}};
  for (int i = 0; i < 3; i++) {
    long double m[3];
    for (int k = 0; k < 3; k++) m[k] = ((long double)e[i][0][k] + e[i][1][k]) / 2;
    long double d = 0;
    for (int k = 0; k < 3; k++) d += (p[k] - m[k]) * (p[k] - m[k]);
    if (d <= distance2(e[i][0], e[i][1]) / 4 * (1 + SURFACE_QUALITY_ROUNDING)) return 1;
  }
  /* Circumcenter of the triangle: a + (|v|^2 (u x v) x u + |u|^2 v x (u x v)) / (2 |u x v|^2). */
  long double u[3], v[3], n[3], x[3], y[3];
  for (int k = 0; k < 3; k++) u[k] = (long double)b[k] - a[k], v[k] = (long double)c[k] - a[k];
  for (int k = 0; k < 3; k++) n[k] = u[(k + 1) % 3] * v[(k + 2) % 3] - u[(k + 2) % 3] * v[(k + 1) % 3];
  for (int k = 0; k < 3; k++) {
    x[k] = n[(k + 1) % 3] * u[(k + 2) % 3] - n[(k + 2) % 3] * u[(k + 1) % 3];
    y[k] = v[(k + 1) % 3] * n[(k + 2) % 3] - v[(k + 2) % 3] * n[(k + 1) % 3];
  }
  long double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  long double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  if (nn == 0) return 0;
  long double center[3], r2 = 0, d2 = 0;
  for (int k = 0; k < 3; k++) center[k] = a[k] + (vv * x[k] + uu * y[k]) / (2 * nn);
  for (int k = 0; k < 3; k++) r2 += (a[k] - center[k]) * (a[k] - center[k]), d2 += (p[k] - center[k]) * (p[k] - center[k]);
  return d2 <= r2 * (1 + SURFACE_QUALITY_ROUNDING);
}

/* Whether refinement that keeps the surface whole must decline point p for a tetrahedron of
 * label `label` (surface_check.h): diametral balls, protecting balls (`shortest`: per vertex
 * its shortest surface edge, 0 off the surface), beyond the surface. */
static int forced_by_surface(const SurfaceInput *in, const SurfaceResult *r, const double *shortest, int32_t label,
                             const double *p) {
  for (size_t t = 0; t < in->m; t++) {
    const uint32_t *f = in->tris + 3 * t;
    if (in_diametral_ball(point(r->xyz, f[0]), point(r->xyz, f[1]), point(r->xyz, f[2]), p)) return 1;
  }
  for (size_t v = 0; v < in->n; v++)
    if (shortest[v] > 0 && distance2(p, point(r->xyz, (uint32_t)v)) <=
                               (long double)shortest[v] * shortest[v] * (1 + SURFACE_QUALITY_ROUNDING))
      return 1;
  for (size_t t = 0; t < r->tet_count; t++) {
    const uint32_t *q = r->tets + 4 * t;
    if (r->labels[t] == label &&
        inside_tetrahedron(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]), p))
      return 0;
  }
  return 1;
}

/* Whether a vertex lies closer to p than `length` (with the relative allowance): the
 * circumsphere of a tetrahedron whose center is p holds a vertex near its center, which only a
 * mesh kept from being Delaunay (by the surface) allows. */
static int vertex_closer_than(const SurfaceResult *r, const double *p, double length) {
  long double l2 = (long double)length * length * (1 + SURFACE_QUALITY_ROUNDING);
  for (size_t v = 0; v < r->vertex_count; v++)
    if (distance2(p, point(r->xyz, (uint32_t)v)) < l2) return 1;
  return 0;
}

/* Per input vertex, its shortest surface edge (0 for a vertex no triangle uses). */
static double *shortest_surface_edges(const SurfaceInput *in) {
  double *shortest = calloc(in->n ? in->n : 1, sizeof *shortest);
  if (!shortest) return NULL;
  for (size_t t = 0; t < 3 * in->m; t++) {
    uint32_t a = in->tris[t], b = in->tris[t - t % 3 + (t + 1) % 3];
    if (a >= in->n || b >= in->n) continue;
    double l = sqrt((double)distance2(point(in->xyz, a), point(in->xyz, b)));
    if (shortest[a] == 0 || l < shortest[a]) shortest[a] = l;
    if (shortest[b] == 0 || l < shortest[b]) shortest[b] = l;
  }
  return shortest;
}

int surface_check(const SurfaceInput *in, const SurfaceResult *r, double radius_edge_bound, SurfaceReport *out) {
  memset(out, 0, sizeof *out);
  out->first_surface_steiner = -1;
  size_t nv = r->vertex_count, nt = r->tet_count;
  out->steiner = nv > in->n ? nv - in->n : 0;

  /* Surface vertices, and what the validity check expects of each vertex. */
  unsigned char *expect = malloc(nv ? nv : 1), *on_surface_vertex = calloc(nv ? nv : 1, 1);
  Key *faces = tetrahedron_faces(r->tets, nt);
  Key *surface = malloc((in->m ? in->m : 1) * sizeof *surface);
  int32_t *side = malloc((in->m ? in->m : 1) * 2 * sizeof *side); /* (from, to) per surface triangle */
  int32_t *labels = malloc((nt ? nt : 1) * sizeof *labels);
  Grid grid;
  memset(&grid, 0, sizeof grid);
  int ok = expect && on_surface_vertex && faces && surface && side && labels;
  if (ok) {
    for (size_t i = 0; i < nv; i++) expect[i] = i < in->n ? VERTEX_MAY_BE_UNUSED : VERTEX_MUST_BE_USED;
    for (size_t t = 0; t < 3 * in->m; t++)
      if (in->tris[t] < nv) expect[in->tris[t]] = VERTEX_MUST_BE_USED, on_surface_vertex[in->tris[t]] = 1;
    Validity v;
    out->valid = metrics_validity(r->xyz, nv, r->tets, nt, expect, NULL, 0, &v);
    metrics_validity_describe(&v, out->validity, sizeof out->validity);
  }

  /* Labels present. */
  size_t label_count = 0;
  if (ok) {
    memcpy(labels, r->labels, nt * sizeof *labels);
    qsort(labels, nt, sizeof *labels, compare_i32);
    for (size_t t = 0; t < nt; t++)
      if (label_count == 0 || labels[label_count - 1] != labels[t]) labels[label_count++] = labels[t];
    out->regions = (int)label_count;
  }

  /* Each surface triangle among the faces, and the labels on its two sides. */
  for (size_t t = 0; ok && t < in->m; t++) {
    const uint32_t *v = in->tris + 3 * t;
    surface[t] = make_key(v[0], v[1], v[2], t);
    side[2 * t] = side[2 * t + 1] = 0;
    size_t i = lower_bound(faces, 4 * nt, &surface[t]);
    if (i == 4 * nt || compare_triples(&faces[i], &surface[t]) != 0) {
      out->missing++;
      continue;
    }
    for (; i < 4 * nt && compare_triples(&faces[i], &surface[t]) == 0; i++) {
      /* The tetrahedron's outward face has the triangle's orientation: the normal leaves it. */
      int leaves = faces[i].parity == surface[t].parity;
      side[2 * t + (leaves ? 0 : 1)] = r->labels[faces[i].index];
    }
    if (side[2 * t] == side[2 * t + 1]) out->same_label++;
  }
  if (ok) qsort(surface, in->m, sizeof *surface, compare_keys);

  /* Label-change faces that are not surface triangles. */
  for (size_t i = 0; ok && i < 4 * nt;) {
    size_t j = i + 1;
    while (j < 4 * nt && compare_triples(&faces[j], &faces[i]) == 0) j++;
    int change = j - i == 1 ? r->labels[faces[i].index] != 0
                            : j - i == 2 && r->labels[faces[i].index] != r->labels[faces[i + 1].index];
    if (change) {
      size_t k = lower_bound(surface, in->m, &faces[i]);
      if (k == in->m || compare_triples(&surface[k], &faces[i]) != 0) out->extra++;
    }
    i = j;
  }

  /* Reported facets. */
  if (ok && r->facets) {
    out->facets_checked = 1;
    if (r->facet_count != in->m) {
      out->facets_misplaced = r->facet_count > in->m ? r->facet_count - in->m : in->m - r->facet_count;
    }
    size_t common = r->facet_count < in->m ? r->facet_count : in->m;
    for (size_t t = 0; t < common; t++) {
      const uint32_t *f = r->facets + 3 * t, *v = in->tris + 3 * t;
      if (f[0] != v[0] || f[1] != v[1] || f[2] != v[2]) out->facets_misplaced++;
      if (!r->facet_labels || r->facet_labels[2 * t] != side[2 * t] || r->facet_labels[2 * t + 1] != side[2 * t + 1])
        out->facets_mislabeled++;
    }
  }

  /* Volumes per label. */
  if (ok) {
    LSum *tet_sum = calloc(label_count ? label_count : 1, sizeof *tet_sum);
    LSum *surface_sum = calloc(label_count ? label_count : 1, sizeof *surface_sum);
    LSum all = {0, 0, 0};
    if (!tet_sum || !surface_sum) {
      ok = 0;
    } else {
      for (size_t t = 0; t < nt; t++) {
        const uint32_t *q = r->tets + 4 * t;
        size_t l = label_index(labels, label_count, r->labels[t]);
        long double x = volume6(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]),
                                &tet_sum[l].bound);
        lsum_add(&tet_sum[l], x);
        lsum_add(&all, x);
      }
      /* Cones from the middle of the input's bounding box. */
      double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, o[3];
      for (size_t i = 0; i < in->n; i++)
        for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], in->xyz[3 * i + k]), hi[k] = fmax(hi[k], in->xyz[3 * i + k]);
      for (int k = 0; k < 3; k++) o[k] = in->n ? 0.5 * (lo[k] + hi[k]) : 0;
      for (size_t t = 0; t < in->m; t++) {
        const uint32_t *v = in->tris + 3 * t;
        long double bound = 0;
        long double x = volume6(o, point(in->xyz, v[0]), point(in->xyz, v[1]), point(in->xyz, v[2]), &bound);
        for (int s = 0; s < 2; s++) {
          size_t l = label_index(labels, label_count, side[2 * t + s]);
          if (side[2 * t + s] == 0 || l == label_count) continue;
          lsum_add(&surface_sum[l], s == 0 ? x : -x); /* + for the label the normal leaves */
          surface_sum[l].bound += bound;
        }
      }
      for (size_t l = 0; l < label_count; l++) {
        long double a = tet_sum[l].sum + tet_sum[l].compensation;
        long double b = surface_sum[l].sum + surface_sum[l].compensation;
        double error = (double)(fabsl(a - b) / fabsl(b));
        double bound = (double)((tet_sum[l].bound + surface_sum[l].bound + 2 * (LDBL_EPSILON / 2) * fabsl(b)) / fabsl(b));
        if (!(error <= out->volume_error)) out->volume_error = error; /* NaN propagates */
        if (bound > out->volume_error_bound) out->volume_error_bound = bound;
      }
      out->volume = (double)(all.sum + all.compensation);
    }
    free(tet_sum);
    free(surface_sum);
  }

  /* Region seeds, hole seeds, volume bounds. */
  for (size_t s = 0; ok && s < in->n_regions; s++) {
    const double *seed = in->regions + 5 * s;
    int32_t label = (int32_t)lround(seed[3]);
    size_t containing = 0, wrong = 0;
    for (size_t t = 0; t < nt; t++) {
      const uint32_t *q = r->tets + 4 * t;
      if (inside_tetrahedron(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]), seed)) {
        containing++;
        wrong += r->labels[t] != label;
      }
      if (seed[4] > 0 && r->labels[t] == label) {
        long double unused = 0;
        double volume = (double)volume6(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]), &unused);
        if (volume > seed[4] * (1 + SURFACE_QUALITY_ROUNDING)) out->above_max_volume++;
      }
    }
    if (containing == 0 || wrong) out->seeds_wrong++;
  }
  for (size_t h = 0; ok && h < in->n_holes; h++)
    for (size_t t = 0; t < nt; t++) {
      const uint32_t *q = r->tets + 4 * t;
      if (inside_tetrahedron(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]), in->holes + 3 * h)) {
        out->holes_covered++;
        break;
      }
    }

  /* Steiner points on the surface. */
  if (ok && nv > in->n && in->m) {
    if (!grid_build(&grid, in->xyz, in->tris, in->m)) {
      ok = 0;
    } else {
      for (size_t i = in->n; i < nv; i++)
        if (on_surface(&grid, in->xyz, in->tris, point(r->xyz, (uint32_t)i))) {
          if (out->first_surface_steiner < 0) out->first_surface_steiner = (long)i;
          out->surface_steiner++;
        }
    }
  }

  /* Quality. */
  out->shapes_measured = ok && out->valid;
  if (out->shapes_measured) out->shapes = quality_tetrahedra(r->xyz, r->tets, nt);
  double *shortest = NULL;
  if (ok && radius_edge_bound > 0) {
    shortest = shortest_surface_edges(in);
    ok = shortest != NULL;
  }
  if (ok && radius_edge_bound > 0) {
    out->max_radius_edge = 0;
    for (size_t t = 0; t < nt; t++) {
      const uint32_t *q = r->tets + 4 * t;
      if (q[0] >= nv || q[1] >= nv || q[2] >= nv || q[3] >= nv) continue;
      TetQuality tq = quality_tetrahedron(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]));
      double ratio = tq.radius_edge;
      if (ratio > out->max_radius_edge) out->max_radius_edge = ratio;
      if (ratio > radius_edge_bound * (1 + SURFACE_QUALITY_ROUNDING)) {
        int on = 0;
        for (int k = 0; k < 4; k++) on += on_surface_vertex[q[k]];
        out->above_radius_edge++;
        out->above_with_3_surface += on >= 3;
        out->above_with_4_surface += on == 4;
        double c[3];
        if (on < 3 && circumcenter(point(r->xyz, q[0]), point(r->xyz, q[1]), point(r->xyz, q[2]), point(r->xyz, q[3]), c)) {
          if (forced_by_surface(in, r, shortest, r->labels[t], c)) {
            out->above_forced++;
          } else {
            out->above_near_vertex += vertex_closer_than(r, c, tq.shortest_edge);
          }
        }
      }
    }
  }
  grid_free(&grid);
  free(shortest);
  free(expect);
  free(on_surface_vertex);
  free(faces);
  free(surface);
  free(side);
  free(labels);
  return ok;
}

int surface_report_ok(const SurfaceReport *r, int expected_regions, int quality, int volume_bounds) {
  return r->valid && r->missing == 0 && r->same_label == 0 && r->extra == 0 &&
         (!r->facets_checked || (r->facets_misplaced == 0 && r->facets_mislabeled == 0)) &&
         r->volume_error <= SURFACE_VOLUME_TOLERANCE && (expected_regions <= 0 || r->regions == expected_regions) &&
         r->seeds_wrong == 0 && r->holes_covered == 0 && (!volume_bounds || r->above_max_volume == 0) &&
         r->surface_steiner == 0 &&
         (!quality || r->above_radius_edge == r->above_with_3_surface + r->above_forced + r->above_near_vertex);
}

void surface_report_describe(const SurfaceReport *r, int expected_regions, int quality, char *buffer, size_t size) {
  size_t len = 0;
#define ADD(...)                                                                    \
  do {                                                                              \
    int w_ = snprintf(buffer + len, len < size ? size - len : 0, __VA_ARGS__);      \
    if (w_ > 0) len += (size_t)w_;                                                  \
  } while (0)
  buffer[0] = '\0';
  /* Failures first. */
  if (!r->valid) ADD("INVALID: %s; ", r->validity);
  if (r->missing) ADD("%zu surface triangles not faces; ", r->missing);
  if (r->same_label) ADD("%zu surface triangles inside one label; ", r->same_label);
  if (r->extra) ADD("%zu label-change faces not on the surface; ", r->extra);
  if (r->facets_checked && r->facets_misplaced) ADD("%zu facets not the input triangle of their index; ", r->facets_misplaced);
  if (r->facets_checked && r->facets_mislabeled) ADD("%zu facets with labels other than their tetrahedra's; ", r->facets_mislabeled);
  if (!(r->volume_error <= SURFACE_VOLUME_TOLERANCE)) ADD("volume error %.2e > %g; ", r->volume_error, SURFACE_VOLUME_TOLERANCE);
  if (expected_regions > 0 && r->regions != expected_regions) ADD("%d regions, expected %d; ", r->regions, expected_regions);
  if (r->seeds_wrong) ADD("%zu region seeds not in a tetrahedron of their label; ", r->seeds_wrong);
  if (r->holes_covered) ADD("%zu hole seeds inside a tetrahedron; ", r->holes_covered);
  if (r->above_max_volume) ADD("%zu tetrahedra above their region's max volume; ", r->above_max_volume);
  if (r->surface_steiner) ADD("%zu Steiner points on the surface (first: vertex %ld); ", r->surface_steiner, r->first_surface_steiner);
  if (quality && r->above_radius_edge != r->above_with_3_surface + r->above_forced + r->above_near_vertex)
    ADD("%zu tetrahedra above the radius-edge bound with < 3 surface vertices that the surface does not force; ",
        r->above_radius_edge - r->above_with_3_surface - r->above_forced - r->above_near_vertex);
  if (len == 0) ADD("ok: ");
  /* Figures. */
  ADD("%s, %zu Steiner, %d region%s, volume error %.1e (bound %.1e)", r->valid ? "valid" : "invalid", r->steiner,
      r->regions, r->regions == 1 ? "" : "s", r->volume_error, r->volume_error_bound);
  if (r->facets_checked) ADD(", facets = input");
  if (r->shapes_measured)
    ADD(", min dihedral %.3f, max radius-edge %.3g, dihedral < 5/10/15: %zu/%zu/%zu", r->shapes.min_dihedral,
        r->shapes.max_radius_edge, r->shapes.dihedral_below[0], r->shapes.dihedral_below[1], r->shapes.dihedral_below[2]);
  if (quality)
    ADD(", max radius-edge %.3f, %zu above the bound (%zu with >= 3, %zu with 4 surface vertices, %zu with < 3 forced "
        "by the surface, %zu with a vertex nearer their circumcenter than their shortest edge)",
        r->max_radius_edge, r->above_radius_edge, r->above_with_3_surface, r->above_with_4_surface, r->above_forced,
        r->above_near_vertex);
#undef ADD
}

/* ---- Polygonal inputs ---------------------------------------------------------------------------------- */

/* Newell's normal of a polygon (twice its vector area), in long double. */
static void polygon_normal(const double *xyz, const uint32_t *c, size_t k, long double n[3]) {
  n[0] = n[1] = n[2] = 0;
  for (size_t i = 0; i < k; i++) {
    const double *p = point(xyz, c[i]), *q = point(xyz, c[(i + 1) % k]);
    n[0] += ((long double)p[1] - q[1]) * ((long double)p[2] + q[2]);
    n[1] += ((long double)p[2] - q[2]) * ((long double)p[0] + q[0]);
    n[2] += ((long double)p[0] - q[0]) * ((long double)p[1] + q[1]);
  }
}

static long double norm3l(const long double n[3]) { return sqrtl(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]); }

/* Whether the point p (in the polygon's plane) is inside the polygon: crossing number in the
 * projection that drops the normal's largest axis. */
static int inside_polygon(const double *xyz, const uint32_t *c, size_t k, const long double n[3], const double p[3]) {
  int drop = fabsl(n[0]) >= fabsl(n[1]) && fabsl(n[0]) >= fabsl(n[2]) ? 0 : fabsl(n[1]) >= fabsl(n[2]) ? 1 : 2;
  int a = drop == 0 ? 1 : 0, b = drop == 2 ? 1 : 2;
  int inside = 0;
  for (size_t i = 0, j = k - 1; i < k; j = i++) {
    const double *pi = point(xyz, c[i]), *pj = point(xyz, c[j]);
    if ((pi[b] > p[b]) != (pj[b] > p[b]) && p[a] < (pj[a] - pi[a]) * (p[b] - pi[b]) / (pj[b] - pi[b]) + pi[a])
      inside = !inside;
  }
  return inside;
}

int surface_check_polygons(const double *xyz, const uint32_t *corners, const size_t *offsets, size_t polygon_count,
                           const uint32_t *tris, size_t count, PolygonCover *out) {
  memset(out, 0, sizeof *out);
  out->triangles = count;
  size_t n = 0; /* vertices named by the polygons */
  for (size_t i = 0; i < offsets[polygon_count]; i++)
    if (corners[i] + (size_t)1 > n) n = corners[i] + (size_t)1;
  for (size_t i = 0; i < 3 * count; i++)
    if (tris[i] + (size_t)1 > n) n = tris[i] + (size_t)1;
  size_t *start = calloc(n + 1, sizeof *start);
  uint32_t *incident = malloc((offsets[polygon_count] ? offsets[polygon_count] : 1) * sizeof *incident);
  long double *area = calloc(polygon_count ? polygon_count : 1, sizeof *area);
  if (!start || !incident || !area) {
    free(start);
    free(incident);
    free(area);
    return 0;
  }
  for (size_t i = 0; i < offsets[polygon_count]; i++) start[corners[i] + 1]++;
  for (size_t v = 0; v < n; v++) start[v + 1] += start[v];
  for (size_t f = 0; f < polygon_count; f++)
    for (size_t i = offsets[f]; i < offsets[f + 1]; i++) incident[start[corners[i]]++] = (uint32_t)f;
  for (size_t v = n; v > 0; v--) start[v] = start[v - 1];
  start[0] = 0;
  for (size_t t = 0; t < count; t++) {
    const uint32_t *v = tris + 3 * t;
    double centroid[3];
    for (int k = 0; k < 3; k++) centroid[k] = (point(xyz, v[0])[k] + point(xyz, v[1])[k] + point(xyz, v[2])[k]) / 3;
    int placed = 0;
    for (size_t i = start[v[0]]; i < start[v[0] + 1] && !placed; i++) {
      size_t f = incident[i], k = offsets[f + 1] - offsets[f];
      const uint32_t *c = corners + offsets[f];
      int found1 = 0, found2 = 0;
      for (size_t j = 0; j < k; j++) found1 |= c[j] == v[1], found2 |= c[j] == v[2];
      long double normal[3];
      polygon_normal(xyz, c, k, normal);
      if (!found1 || !found2 || !inside_polygon(xyz, c, k, normal, centroid)) continue;
      long double u[3], w[3], x[3];
      for (int a = 0; a < 3; a++) {
        u[a] = (long double)point(xyz, v[1])[a] - point(xyz, v[0])[a];
        w[a] = (long double)point(xyz, v[2])[a] - point(xyz, v[0])[a];
      }
      x[0] = u[1] * w[2] - u[2] * w[1], x[1] = u[2] * w[0] - u[0] * w[2], x[2] = u[0] * w[1] - u[1] * w[0];
      area[f] += norm3l(x) / 2;
      placed = 1;
    }
    if (!placed) out->outside++;
  }
  for (size_t f = 0; f < polygon_count; f++) {
    long double normal[3];
    polygon_normal(xyz, corners + offsets[f], offsets[f + 1] - offsets[f], normal);
    long double expected = norm3l(normal) / 2;
    double error = (double)(fabsl(area[f] - expected) / expected);
    if (!(error <= out->max_area_error)) out->max_area_error = error;
    if (!(error <= 1e-12)) out->polygons_off++;
  }
  free(start);
  free(incident);
  free(area);
  return out->outside == 0 && out->polygons_off == 0;
}

typedef struct PolygonEdge {
  uint32_t lo, hi;
  size_t polygon;
  int forward; /* the polygon runs lo -> hi */
} PolygonEdge;

static int compare_polygon_edges(const void *pa, const void *pb) {
  const PolygonEdge *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->polygon > b->polygon) - (a->polygon < b->polygon);
}

double surface_polygons_volume(const double *xyz, const uint32_t *corners, const size_t *offsets, size_t polygon_count) {
  /* Files need not orient their polygons consistently (TetGen does not ask it): orient them by
   * walking across edges, each in exactly two polygons that must run it in opposite directions. */
  size_t edge_count = offsets[polygon_count];
  PolygonEdge *e = malloc((edge_count ? edge_count : 1) * sizeof *e);
  size_t *mate = malloc((edge_count ? edge_count : 1) * sizeof *mate); /* the other use of edge use i */
  signed char *sign = calloc(polygon_count ? polygon_count : 1, 1);
  size_t *queue = malloc((polygon_count ? polygon_count : 1) * sizeof *queue);
  double result = NAN;
  if (!e || !mate || !sign || !queue) goto done;
  for (size_t f = 0; f < polygon_count; f++)
    for (size_t i = offsets[f]; i < offsets[f + 1]; i++) {
      uint32_t a = corners[i], b = corners[i + 1 < offsets[f + 1] ? i + 1 : offsets[f]];
      e[i] = (PolygonEdge){a < b ? a : b, a < b ? b : a, f, a < b};
    }
  qsort(e, edge_count, sizeof *e, compare_polygon_edges);
  for (size_t i = 0; i < edge_count; i += 2) {
    if (i + 1 >= edge_count || e[i + 1].lo != e[i].lo || e[i + 1].hi != e[i].hi ||
        (i + 2 < edge_count && e[i + 2].lo == e[i].lo && e[i + 2].hi == e[i].hi))
      goto done; /* not a closed 2-manifold */
    mate[i] = i + 1, mate[i + 1] = i;
  }
  /* Edge uses of each polygon, for the walk. */
  size_t *first = calloc(polygon_count + 1, sizeof *first), *uses = malloc((edge_count ? edge_count : 1) * sizeof *uses);
  if (!first || !uses) {
    free(first);
    free(uses);
    goto done;
  }
  for (size_t i = 0; i < edge_count; i++) first[e[i].polygon + 1]++;
  for (size_t f = 0; f < polygon_count; f++) first[f + 1] += first[f];
  for (size_t i = 0; i < edge_count; i++) uses[first[e[i].polygon]++] = i;
  for (size_t f = polygon_count; f > 0; f--) first[f] = first[f - 1];
  first[0] = 0;
  int orientable = 1;
  for (size_t seed = 0; seed < polygon_count && orientable; seed++) {
    if (sign[seed]) continue;
    sign[seed] = 1;
    size_t head = 0, tail = 0;
    queue[tail++] = seed;
    while (head < tail && orientable) {
      size_t f = queue[head++];
      for (size_t k = first[f]; k < first[f + 1]; k++) {
        const PolygonEdge *x = &e[uses[k]], *y = &e[mate[uses[k]]];
        /* As oriented, f runs the edge forward iff x->forward == (sign > 0); y must not. */
        int f_forward = x->forward == (sign[f] > 0);
        signed char wanted = (signed char)(y->forward == !f_forward ? 1 : -1);
        if (!sign[y->polygon]) {
          sign[y->polygon] = wanted;
          queue[tail++] = y->polygon;
        } else if (sign[y->polygon] != wanted) {
          orientable = 0;
        }
      }
    }
  }
  free(first);
  free(uses);
  if (!orientable) goto done;
  LSum s = {0, 0, 0};
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, c[3];
  for (size_t i = 0; i < edge_count; i++)
    for (int k = 0; k < 3; k++) lo[k] = fmin(lo[k], point(xyz, corners[i])[k]), hi[k] = fmax(hi[k], point(xyz, corners[i])[k]);
  for (int k = 0; k < 3; k++) c[k] = edge_count ? 0.5 * (lo[k] + hi[k]) : 0;
  for (size_t f = 0; f < polygon_count; f++) {
    const uint32_t *p = corners + offsets[f];
    size_t k = offsets[f + 1] - offsets[f];
    for (size_t i = 1; i + 1 < k; i++) { /* a fan: exact for any planar polygon (signed cones) */
      long double unused = 0, x = volume6(c, point(xyz, p[0]), point(xyz, p[i]), point(xyz, p[i + 1]), &unused);
      lsum_add(&s, sign[f] > 0 ? x : -x);
    }
  }
  result = fabs((double)(s.sum + s.compensation));
done:
  free(e);
  free(mate);
  free(sign);
  free(queue);
  return result;
}

size_t surface_polygons_nonplanar(const double *xyz, const uint32_t *corners, const size_t *offsets, size_t polygon_count) {
  size_t count = 0;
  for (size_t f = 0; f < polygon_count; f++) {
    const uint32_t *c = corners + offsets[f];
    size_t k = offsets[f + 1] - offsets[f];
    if (k == 3) continue;
    /* The plane through the corner triple of largest (floating) cross product: exactly a plane. */
    size_t best = 0;
    double best_norm = -1;
    for (size_t i = 0; i < k; i++) {
      const double *a = point(xyz, c[i]), *b = point(xyz, c[(i + 1) % k]), *d = point(xyz, c[(i + 2) % k]);
      double u[3], v[3];
      for (int j = 0; j < 3; j++) u[j] = b[j] - a[j], v[j] = d[j] - a[j];
      double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
      double norm = x * x + y * y + z * z;
      if (norm > best_norm) best_norm = norm, best = i;
    }
    const double *a = point(xyz, c[best]), *b = point(xyz, c[(best + 1) % k]), *d = point(xyz, c[(best + 2) % k]);
    for (size_t i = 0; i < k; i++)
      if (orient(a, b, d, point(xyz, c[i])) != 0) {
        count++;
        break;
      }
  }
  return count;
}

uint32_t *surface_label_change_faces(const uint32_t *tets, const int32_t *labels, size_t tet_count, size_t *count) {
  size_t n = 0;
  BoundaryFace *faces = boundary_faces(tets, labels, tet_count, &n);
  uint32_t *tris = malloc((n ? n : 1) * 3 * sizeof *tris);
  if (!faces || !tris) {
    free(faces);
    free(tris);
    return NULL;
  }
  for (size_t i = 0; i < n; i++) memcpy(tris + 3 * i, faces[i].v, sizeof faces[i].v);
  free(faces);
  *count = n;
  return tris;
}
