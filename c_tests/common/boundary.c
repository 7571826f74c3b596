#include "boundary.h"

#include "metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double *point(const double *xyz, uint32_t i) { return xyz + 3 * (size_t)i; }

static void sub3(const double a[3], const double b[3], double out[3]) {
  for (int k = 0; k < 3; k++) out[k] = a[k] - b[k];
}
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* ---- Faces --------------------------------------------------------------------------------------- */

/* A face keyed by its sorted vertices; parity 1 when sorting took an odd permutation. */
typedef struct Keyed {
  uint32_t v[3];
  uint32_t parity;
  int32_t from, to; /* boundary_compare_faces */
  size_t tet;       /* boundary_faces */
} Keyed;

static Keyed keyed(uint32_t a, uint32_t b, uint32_t c) {
  Keyed k;
  memset(&k, 0, sizeof k);
  k.v[0] = a, k.v[1] = b, k.v[2] = c;
  for (int pass = 0; pass < 3; pass++) {
    int i = pass == 1 ? 1 : 0; /* compare-swap (0,1), (1,2), (0,1) */
    if (k.v[i] > k.v[i + 1]) {
      uint32_t t = k.v[i];
      k.v[i] = k.v[i + 1];
      k.v[i + 1] = t;
      k.parity ^= 1;
    }
  }
  return k;
}

static int compare_vertices(const Keyed *a, const Keyed *b) {
  for (int k = 0; k < 3; k++)
    if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
  return 0;
}

static int compare_keyed(const void *pa, const void *pb) {
  const Keyed *a = pa, *b = pb;
  int c = compare_vertices(a, b);
  if (c) return c;
  if (a->parity != b->parity) return a->parity < b->parity ? -1 : 1;
  if (a->from != b->from) return a->from < b->from ? -1 : 1;
  return (a->to > b->to) - (a->to < b->to);
}

/* The face of a key, in its original orientation. */
static BoundaryFace unkey(const Keyed *k, int32_t from, int32_t to) {
  BoundaryFace f = {{k->v[0], k->parity ? k->v[2] : k->v[1], k->parity ? k->v[1] : k->v[2]}, from, to};
  return f;
}

BoundaryFace *boundary_faces(const uint32_t *tets, const int32_t *labels, size_t tet_count,
                             size_t *face_count) {
  Keyed *all = malloc((tet_count ? tet_count : 1) * 4 * sizeof *all);
  BoundaryFace *faces = malloc((tet_count ? tet_count : 1) * 4 * sizeof *faces);
  if (!all || !faces) {
    free(all);
    free(faces);
    return NULL;
  }
  for (size_t t = 0; t < tet_count; t++) {
    const uint32_t *q = tets + 4 * t;
    all[4 * t] = keyed(q[1], q[2], q[3]); /* outward faces of a positive tetrahedron */
    all[4 * t + 1] = keyed(q[0], q[3], q[2]);
    all[4 * t + 2] = keyed(q[0], q[1], q[3]);
    all[4 * t + 3] = keyed(q[0], q[2], q[1]);
    for (int i = 0; i < 4; i++) all[4 * t + i].tet = t;
  }
  qsort(all, 4 * tet_count, sizeof *all, compare_keyed);
  size_t n = 0;
  for (size_t i = 0; i < 4 * tet_count;) {
    size_t j = i + 1;
    while (j < 4 * tet_count && compare_vertices(&all[i], &all[j]) == 0) j++;
    if (j - i == 1) {
      faces[n++] = unkey(&all[i], labels[all[i].tet], 0);
    } else if (j - i == 2) {
      int32_t a = labels[all[i].tet], b = labels[all[i + 1].tet];
      if (a != b) faces[n++] = a > b ? unkey(&all[i], a, b) : unkey(&all[i + 1], b, a);
    } /* a face in three or more tetrahedra: invalid mesh, reported by metrics_validity */
    i = j;
  }
  free(all);
  *face_count = n;
  return faces;
}

BoundaryFace *boundary_faces_from_facets(const uint32_t *facets, const int32_t *facet_labels,
                                         size_t count) {
  BoundaryFace *faces = malloc((count ? count : 1) * sizeof *faces);
  if (!faces) return NULL;
  for (size_t i = 0; i < count; i++) {
    const uint32_t *f = facets + 3 * i;
    int32_t from = facet_labels[2 * i], to = facet_labels[2 * i + 1];
    faces[i] = from >= to ? (BoundaryFace){{f[0], f[1], f[2]}, from, to}
                          : (BoundaryFace){{f[0], f[2], f[1]}, to, from};
  }
  return faces;
}

static Keyed *key_faces(const BoundaryFace *faces, size_t count) {
  Keyed *keys = malloc((count ? count : 1) * sizeof *keys);
  if (!keys) return NULL;
  for (size_t i = 0; i < count; i++) {
    keys[i] = keyed(faces[i].v[0], faces[i].v[1], faces[i].v[2]);
    keys[i].from = faces[i].from;
    keys[i].to = faces[i].to;
  }
  qsort(keys, count, sizeof *keys, compare_keyed);
  return keys;
}

FaceComparison boundary_compare_faces(const BoundaryFace *expected, size_t expected_count,
                                      const BoundaryFace *reported, size_t reported_count) {
  FaceComparison c = {0, 0, 0, 0, 0};
  Keyed *a = key_faces(expected, expected_count), *b = key_faces(reported, reported_count);
  if (!a || !b) {
    c.missing = expected_count;
    c.extra = reported_count;
  } else {
    size_t i = 0, j = 0;
    while (i < expected_count || j < reported_count) {
      int order = i == expected_count ? 1 : j == reported_count ? -1 : compare_vertices(&a[i], &b[j]);
      if (order < 0) {
        c.missing++, i++;
      } else if (order > 0) {
        c.extra++, j++;
      } else {
        if (a[i].from != b[j].from || a[i].to != b[j].to)
          c.wrong_labels++;
        else if (a[i].parity != b[j].parity)
          c.misoriented++;
        else
          c.common++;
        i++, j++;
      }
    }
  }
  free(a);
  free(b);
  return c;
}

/* ---- Surfaces of the subdomains --------------------------------------------------------------------- */

typedef struct Edge {
  uint32_t lo, hi;
  uint32_t forward; /* 1 when the face runs it lo -> hi */
  uint32_t face;
} Edge;

static int compare_edges(const void *pa, const void *pb) {
  const Edge *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  return (a->hi > b->hi) - (a->hi < b->hi);
}

static uint32_t find_root(uint32_t *parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

static int compare_u64(const void *pa, const void *pb) {
  uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
  return (a > b) - (a < b);
}

static int compare_int(const void *pa, const void *pb) {
  int a = *(const int *)pa, b = *(const int *)pb;
  return (a > b) - (a < b);
}

int boundary_subdomain_surface(const BoundaryFace *faces, size_t count, int32_t label,
                               SubdomainSurface *out) {
  memset(out, 0, sizeof *out);
  out->label = label;
  size_t m = 0;
  for (size_t i = 0; i < count; i++) m += faces[i].from == label || faces[i].to == label;
  uint32_t (*tri)[3] = malloc((m ? m : 1) * sizeof *tri);
  Edge *edges = malloc((m ? m : 1) * 3 * sizeof *edges);
  uint32_t *parent = malloc((m ? m : 1) * sizeof *parent);
  long *face_count = calloc(m ? m : 1, sizeof *face_count), *edge_count = calloc(m ? m : 1, sizeof *edge_count),
       *vertex_count = calloc(m ? m : 1, sizeof *vertex_count);
  uint64_t *corner = malloc((m ? m : 1) * 3 * sizeof *corner);
  int ok = tri && edges && parent && face_count && edge_count && vertex_count && corner;
  if (ok) {
    m = 0;
    for (size_t i = 0; i < count; i++) { /* outward from `label` */
      const BoundaryFace *f = &faces[i];
      if (f->from == label) tri[m][0] = f->v[0], tri[m][1] = f->v[1], tri[m][2] = f->v[2], m++;
      else if (f->to == label) tri[m][0] = f->v[0], tri[m][1] = f->v[2], tri[m][2] = f->v[1], m++;
    }
    out->faces = m;
    for (uint32_t f = 0; f < m; f++) {
      parent[f] = f;
      for (int k = 0; k < 3; k++) {
        uint32_t a = tri[f][k], b = tri[f][(k + 1) % 3];
        edges[3 * f + k] = (Edge){a < b ? a : b, a < b ? b : a, a < b, f};
      }
    }
    qsort(edges, 3 * m, sizeof *edges, compare_edges);
    for (size_t i = 0; i < 3 * m;) {
      size_t j = i + 1;
      while (j < 3 * m && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) j++;
      if (j - i == 1) out->open_edges++;
      else if (j - i > 2) out->nonmanifold_edges++;
      else if (edges[i].forward == edges[i + 1].forward) out->misoriented_edges++;
      for (size_t k = i + 1; k < j; k++) /* faces sharing an edge: one component */
        parent[find_root(parent, edges[k].face)] = find_root(parent, edges[i].face);
      i = j;
    }
    /* Components: V - E + F each (an edge counts in the component of its faces). */
    for (size_t i = 0; i < 3 * m;) {
      size_t j = i + 1;
      while (j < 3 * m && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) j++;
      edge_count[find_root(parent, edges[i].face)]++;
      i = j;
    }
    for (uint32_t f = 0; f < m; f++) {
      uint32_t r = find_root(parent, f);
      face_count[r]++;
      for (int k = 0; k < 3; k++) corner[3 * f + k] = ((uint64_t)tri[f][k] << 32) | r;
    }
    qsort(corner, 3 * m, sizeof *corner, compare_u64);
    for (size_t i = 0; i < 3 * m; i++)
      if (i == 0 || corner[i] != corner[i - 1]) vertex_count[corner[i] & 0xffffffffu]++;
    int euler[BOUNDARY_MAX_COMPONENTS];
    for (uint32_t f = 0; f < m; f++) {
      if (find_root(parent, f) != f) continue;
      if (out->components < BOUNDARY_MAX_COMPONENTS)
        euler[out->components] = (int)(vertex_count[f] - edge_count[f] + face_count[f]);
      out->components++;
    }
    size_t stored = out->components < BOUNDARY_MAX_COMPONENTS ? out->components : BOUNDARY_MAX_COMPONENTS;
    qsort(euler, stored, sizeof euler[0], compare_int);
    memcpy(out->euler, euler, stored * sizeof euler[0]);
  }
  free(tri);
  free(edges);
  free(parent);
  free(face_count);
  free(edge_count);
  free(vertex_count);
  free(corner);
  return ok && m > 0 && out->open_edges == 0 && out->nonmanifold_edges == 0 &&
         out->misoriented_edges == 0;
}

/* ---- Vertices on the surface, volumes ----------------------------------------------------------- */

SurfaceVertices boundary_surface_vertices(const double *xyz, size_t n, const int8_t *dimensions,
                                          const BoundaryFace *faces, size_t count,
                                          double (*distance)(const double p[3]), double tolerance) {
  SurfaceVertices r = {0, 0, 0, 0.0};
  unsigned char *on_face = calloc(n ? n : 1, 1);
  if (!on_face) {
    r.far = n;
    return r;
  }
  for (size_t i = 0; i < count; i++)
    for (int k = 0; k < 3; k++)
      if (faces[i].v[k] < n) on_face[faces[i].v[k]] = 1;
  for (size_t i = 0; i < n; i++) {
    int dim2 = dimensions && dimensions[i] == 2;
    if (!dim2 && !on_face[i]) continue;
    if (on_face[i] && dimensions && dimensions[i] == 3) r.volume_on_boundary++;
    double d = distance(point(xyz, (uint32_t)i));
    r.checked++;
    if (!(d <= tolerance)) r.far++;
    if (d > r.max_distance) r.max_distance = d;
  }
  free(on_face);
  return r;
}

void boundary_volumes(const double *xyz, const uint32_t *tets, const int32_t *labels,
                      size_t tet_count, int32_t max_label, double *volumes) {
  uint32_t *subset = malloc((tet_count ? tet_count : 1) * 4 * sizeof *subset);
  for (int32_t label = 0; label <= max_label; label++) {
    size_t m = 0;
    for (size_t t = 0; subset && t < tet_count; t++)
      if (labels[t] == label) memcpy(subset + 4 * m++, tets + 4 * t, 4 * sizeof *subset);
    volumes[label] = subset ? metrics_tetrahedra_volume(xyz, subset, m) : NAN;
  }
  free(subset);
}

/* ---- Hausdorff distance ------------------------------------------------------------------------ */

/* Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5); returns
 * the squared distance. */
static double triangle_distance2(const double p[3], const double a[3], const double b[3], const double c[3]) {
  double ab[3], ac[3], ap[3], bp[3], cp[3], q[3], d[3];
  sub3(b, a, ab), sub3(c, a, ac), sub3(p, a, ap);
  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return sub3(p, a, d), dot3(d, d);
  sub3(p, b, bp);
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return sub3(p, b, d), dot3(d, d);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double v = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k];
    return sub3(p, q, d), dot3(d, d);
  }
  sub3(p, c, cp);
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return sub3(p, c, d), dot3(d, d);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double w = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) q[k] = a[k] + w * ac[k];
    return sub3(p, q, d), dot3(d, d);
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) q[k] = b[k] + w * (c[k] - b[k]);
    return sub3(p, q, d), dot3(d, d);
  }
  double denom = 1.0 / (va + vb + vc), v = vb * denom, w = vc * denom;
  for (int k = 0; k < 3; k++) q[k] = a[k] + ab[k] * v + ac[k] * w;
  return sub3(p, q, d), dot3(d, d);
}

/* Uniform grid of cells of side h; cell c lists the triangles whose bounding box meets it. */
typedef struct Grid {
  double lo[3], h;
  long dim[3];
  size_t *start; /* dim0*dim1*dim2 + 1 */
  uint32_t *items;
} Grid;

static long cell_of(const Grid *g, int k, double x) {
  double c = floor((x - g->lo[k]) / g->h);
  return c < 0 ? 0 : c >= (double)g->dim[k] ? g->dim[k] - 1 : (long)c;
}

static int grid_build(Grid *g, const double *xyz, const BoundaryFace *faces, size_t count) {
  double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k < 3; k++) g->lo[k] = INFINITY;
  for (size_t i = 0; i < count; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++) {
        double x = point(xyz, faces[i].v[j])[k];
        g->lo[k] = fmin(g->lo[k], x);
        hi[k] = fmax(hi[k], x);
      }
  double extent[3], volume = 1.0;
  for (int k = 0; k < 3; k++) extent[k] = fmax(hi[k] - g->lo[k], 1e-12), volume *= extent[k];
  g->h = cbrt(volume / (double)(count ? count : 1));
  for (int k = 0; k < 3; k++) {
    g->h = fmax(g->h, extent[k] / 512.0);
  }
  size_t cells = 1;
  for (int k = 0; k < 3; k++) g->dim[k] = (long)(extent[k] / g->h) + 1, cells *= (size_t)g->dim[k];
  g->start = calloc(cells + 1, sizeof *g->start);
  if (!g->start) return 0;
  for (int pass = 0; pass < 2; pass++) { /* count, then fill */
    for (size_t i = 0; i < count; i++) {
      long a[3], b[3];
      for (int k = 0; k < 3; k++) {
        double x0 = point(xyz, faces[i].v[0])[k], x1 = point(xyz, faces[i].v[1])[k], x2 = point(xyz, faces[i].v[2])[k];
        a[k] = cell_of(g, k, fmin(x0, fmin(x1, x2)));
        b[k] = cell_of(g, k, fmax(x0, fmax(x1, x2)));
      }
      for (long x = a[0]; x <= b[0]; x++)
        for (long y = a[1]; y <= b[1]; y++)
          for (long z = a[2]; z <= b[2]; z++) {
            size_t c = ((size_t)x * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[2] + (size_t)z;
            if (pass == 0) g->start[c + 1]++;
            else g->items[g->start[c]++] = (uint32_t)i;
          }
    }
    if (pass == 0) {
      for (size_t c = 0; c < cells; c++) g->start[c + 1] += g->start[c];
      g->items = malloc((g->start[cells] ? g->start[cells] : 1) * sizeof *g->items);
      if (!g->items) return 0;
    } else { /* start[c] advanced to the end of cell c: shift back */
      memmove(g->start + 1, g->start, cells * sizeof *g->start);
      g->start[0] = 0;
    }
  }
  return 1;
}

static double grid_distance(const Grid *g, const double *xyz, const BoundaryFace *faces, const double p[3]) {
  long c[3];
  for (int k = 0; k < 3; k++) c[k] = cell_of(g, k, p[k]);
  double best2 = INFINITY;
  for (long r = 0;; r++) {
    long a[3], b[3];
    for (int k = 0; k < 3; k++) a[k] = c[k] - r < 0 ? 0 : c[k] - r, b[k] = c[k] + r >= g->dim[k] ? g->dim[k] - 1 : c[k] + r;
    for (long x = a[0]; x <= b[0]; x++)
      for (long y = a[1]; y <= b[1]; y++)
        for (long z = a[2]; z <= b[2]; z++) {
          long ring = labs(x - c[0]);
          if (labs(y - c[1]) > ring) ring = labs(y - c[1]);
          if (labs(z - c[2]) > ring) ring = labs(z - c[2]);
          if (ring != r) continue; /* visited in an earlier shell */
          size_t cell = ((size_t)x * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[2] + (size_t)z;
          for (size_t i = g->start[cell]; i < g->start[cell + 1]; i++) {
            const BoundaryFace *f = &faces[g->items[i]];
            double d2 = triangle_distance2(p, point(xyz, f->v[0]), point(xyz, f->v[1]), point(xyz, f->v[2]));
            if (d2 < best2) best2 = d2;
          }
        }
    /* Any triangle not seen lies wholly outside the searched box [a, b]. */
    double bound = INFINITY;
    for (int k = 0; k < 3; k++) {
      if (a[k] > 0) bound = fmin(bound, p[k] - (g->lo[k] + (double)a[k] * g->h));
      if (b[k] < g->dim[k] - 1) bound = fmin(bound, g->lo[k] + (double)(b[k] + 1) * g->h - p[k]);
    }
    if (bound == INFINITY || (bound > 0 && best2 <= bound * bound)) return sqrt(best2);
  }
}

int boundary_hausdorff(const double *xyz, const BoundaryFace *faces, size_t count,
                       double (*distance)(const double p[3]), const double *samples,
                       size_t sample_count, Hausdorff *out) {
  memset(out, 0, sizeof *out);
  if (count == 0) return 0;
  /* mesh -> surface */
  double sum2 = 0.0;
  for (size_t i = 0; i < count; i++) {
    const double *v[3] = {point(xyz, faces[i].v[0]), point(xyz, faces[i].v[1]), point(xyz, faces[i].v[2])};
    double s[7][3];
    for (int k = 0; k < 3; k++) {
      s[0][k] = v[0][k], s[1][k] = v[1][k], s[2][k] = v[2][k];
      s[3][k] = (v[0][k] + v[1][k] + v[2][k]) / 3.0;
      s[4][k] = 0.5 * (v[0][k] + v[1][k]), s[5][k] = 0.5 * (v[1][k] + v[2][k]), s[6][k] = 0.5 * (v[2][k] + v[0][k]);
    }
    for (int j = 0; j < 7; j++) {
      double d = distance(s[j]);
      sum2 += d * d;
      if (d > out->mesh_to_surface_max) out->mesh_to_surface_max = d;
    }
  }
  out->mesh_samples = 7 * count;
  out->mesh_to_surface_rms = sqrt(sum2 / (double)out->mesh_samples);

  /* surface -> mesh */
  Grid g;
  memset(&g, 0, sizeof g);
  int ok = grid_build(&g, xyz, faces, count);
  sum2 = 0.0;
  for (size_t i = 0; ok && i < sample_count; i++) {
    double d = grid_distance(&g, xyz, faces, samples + 3 * i);
    sum2 += d * d;
    if (d > out->surface_to_mesh_max) out->surface_to_mesh_max = d;
  }
  free(g.start);
  free(g.items);
  out->surface_samples = sample_count;
  out->surface_to_mesh_rms = sample_count ? sqrt(sum2 / (double)sample_count) : 0.0;
  out->max = fmax(out->mesh_to_surface_max, out->surface_to_mesh_max);
  return ok;
}
