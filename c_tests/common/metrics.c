#include "metrics.h"

#include "ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Validity --------------------------------------------------------------------------------- */

/* A facet of a tetrahedron: its vertices sorted ascending, and the parity of the permutation
 * that sorts the outward-oriented facet (0 even, 1 odd). Two tetrahedra on opposite sides of a
 * shared facet see it with opposite orientations, i.e. different parities. */
typedef struct Facet {
  uint32_t v[3];
  uint32_t parity;
} Facet;

static int compare_facets(const void *pa, const void *pb) {
  const Facet *a = pa, *b = pb;
  for (int k = 0; k < 3; k++)
    if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
  return (a->parity > b->parity) - (a->parity < b->parity);
}

/* Swaps v[i] and v[j] when out of order; each swap flips the parity. */
static void order_pair(Facet *f, int i, int j) {
  if (f->v[i] > f->v[j]) {
    uint32_t t = f->v[i];
    f->v[i] = f->v[j];
    f->v[j] = t;
    f->parity ^= 1;
  }
}

static Facet make_facet(uint32_t p, uint32_t q, uint32_t r) {
  Facet f = {{p, q, r}, 0};
  order_pair(&f, 0, 1);
  order_pair(&f, 1, 2);
  order_pair(&f, 0, 1);
  return f;
}

static const double *point(const double *xyz, uint32_t i) { return xyz + 3 * (size_t)i; }

typedef struct Keyed {
  double x, y, z;
  uint32_t index;
} Keyed;

static int compare_keyed(const void *pa, const void *pb) {
  const Keyed *a = pa, *b = pb;
  if (a->x != b->x) return a->x < b->x ? -1 : 1;
  if (a->y != b->y) return a->y < b->y ? -1 : 1;
  if (a->z != b->z) return a->z < b->z ? -1 : 1;
  return (a->index > b->index) - (a->index < b->index);
}

uint32_t *metrics_first_occurrence(const double *xyz, size_t n) {
  Keyed *keys = malloc((n ? n : 1) * sizeof *keys);
  uint32_t *first = malloc((n ? n : 1) * sizeof *first);
  if (!keys || !first) {
    free(keys);
    free(first);
    return NULL;
  }
  for (size_t i = 0; i < n; i++) {
    keys[i].x = xyz[3 * i];
    keys[i].y = xyz[3 * i + 1];
    keys[i].z = xyz[3 * i + 2];
    keys[i].index = (uint32_t)i;
  }
  qsort(keys, n, sizeof *keys, compare_keyed);
  for (size_t i = 0; i < n; i++) {
    int same = i > 0 && keys[i].x == keys[i - 1].x && keys[i].y == keys[i - 1].y &&
               keys[i].z == keys[i - 1].z;
    first[keys[i].index] = same ? first[keys[i - 1].index] : keys[i].index;
  }
  free(keys);
  return first;
}

int metrics_validity(const double *xyz, size_t n, const uint32_t *tets, size_t tet_count,
                     const unsigned char *expect, const uint32_t *hull_vertices, size_t hull_count,
                     Validity *v) {
  memset(v, 0, sizeof *v);
  v->tetrahedra = tet_count;
  v->first_bad_tetrahedron = -1;
  unsigned char *used = calloc(n ? n : 1, 1);
  Facet *facets = malloc((tet_count ? tet_count : 1) * 4 * sizeof *facets);
  uint32_t *first = metrics_first_occurrence(xyz, n);
  if (!used || !facets || !first) {
    free(used);
    free(facets);
    free(first);
    return 0;
  }
  size_t facet_count = 0;
  for (size_t t = 0; t < tet_count; t++) {
    const uint32_t *q = tets + 4 * t;
    int bad = 0;
    if (q[0] >= n || q[1] >= n || q[2] >= n || q[3] >= n) {
      v->index_out_of_range++;
      bad = 1;
    } else if (q[0] == q[1] || q[0] == q[2] || q[0] == q[3] || q[1] == q[2] || q[1] == q[3] ||
               q[2] == q[3]) {
      v->repeated_vertex++;
      bad = 1;
    } else {
      for (int k = 0; k < 4; k++) used[q[k]] = 1;
      if (ref_orient3d_exact(point(xyz, q[0]), point(xyz, q[1]), point(xyz, q[2]),
                             point(xyz, q[3])) <= 0) {
        v->not_positive++;
        bad = 1;
      }
      facets[facet_count++] = make_facet(q[1], q[2], q[3]);
      facets[facet_count++] = make_facet(q[0], q[3], q[2]);
      facets[facet_count++] = make_facet(q[0], q[1], q[3]);
      facets[facet_count++] = make_facet(q[0], q[2], q[1]);
    }
    if (bad && v->first_bad_tetrahedron < 0) v->first_bad_tetrahedron = (long)t;
  }

  qsort(facets, facet_count, sizeof *facets, compare_facets);
  for (size_t i = 0; i < facet_count;) {
    size_t j = i + 1;
    while (j < facet_count && memcmp(facets[j].v, facets[i].v, sizeof facets[i].v) == 0) j++;
    if (j - i == 1) {
      v->boundary_facets++;
      /* Outward orientation restored from the parity; no hull vertex may lie beyond it. */
      const Facet *f = &facets[i];
      uint32_t a = f->v[0], b = f->parity ? f->v[2] : f->v[1], c = f->parity ? f->v[1] : f->v[2];
      for (size_t h = 0; h < hull_count; h++) {
        if (hull_vertices[h] >= n) continue;
        if (ref_orient3d_exact(point(xyz, a), point(xyz, b), point(xyz, c),
                               point(xyz, hull_vertices[h])) > 0) {
          v->boundary_off_hull++;
          break;
        }
      }
    } else if (j - i == 2) {
      if (facets[i].parity == facets[i + 1].parity)
        v->facets_same_side++;
      else
        v->interior_facets++;
    } else {
      v->facets_overshared++;
    }
    i = j;
  }

  /* Vertex use, and no two used vertices at the same place. */
  unsigned char *group_used = calloc(n ? n : 1, 1);
  if (!group_used) {
    free(used);
    free(facets);
    free(first);
    return 0;
  }
  for (size_t i = 0; i < n; i++) {
    int e = expect ? expect[i] : VERTEX_MUST_BE_USED;
    if (e == VERTEX_MUST_BE_USED && !used[i]) v->unused_vertices++;
    if (e == VERTEX_MUST_BE_UNUSED && used[i]) v->used_but_unexpected++;
    if (used[i]) {
      if (group_used[first[i]]) v->coincident_used++;
      group_used[first[i]] = 1;
    }
  }
  free(group_used);
  free(used);
  free(facets);
  free(first);
  return v->index_out_of_range == 0 && v->repeated_vertex == 0 && v->not_positive == 0 &&
         v->facets_same_side == 0 && v->facets_overshared == 0 && v->boundary_off_hull == 0 &&
         v->unused_vertices == 0 && v->used_but_unexpected == 0 && v->coincident_used == 0 &&
         v->tetrahedra > 0;
}

void metrics_validity_describe(const Validity *v, char *buffer, size_t size) {
  struct {
    const char *name;
    size_t value;
  } defects[] = {
      {"indices out of range", v->index_out_of_range},
      {"repeated vertex", v->repeated_vertex},
      {"not positively oriented", v->not_positive},
      {"facets shared from the same side", v->facets_same_side},
      {"facets in 3+ tetrahedra", v->facets_overshared},
      {"boundary facets off the hull", v->boundary_off_hull},
      {"unused vertices", v->unused_vertices},
      {"vertices used but expected unused", v->used_but_unexpected},
      {"coincident used vertices", v->coincident_used},
  };
  size_t len = 0;
  buffer[0] = '\0';
  for (size_t k = 0; k < sizeof defects / sizeof defects[0]; k++) {
    if (!defects[k].value) continue;
    int w = snprintf(buffer + len, size > len ? size - len : 0, "%s%zu %s", len ? ", " : "",
                     defects[k].value, defects[k].name);
    if (w > 0) len += (size_t)w;
    if (len >= size) return;
  }
  if (v->tetrahedra == 0) {
    snprintf(buffer, size, "no tetrahedra");
  } else if (len == 0) {
    snprintf(buffer, size, "valid (%zu interior, %zu boundary facets)", v->interior_facets,
             v->boundary_facets);
  } else if (v->first_bad_tetrahedron >= 0 && len < size) {
    snprintf(buffer + len, size - len, " (first bad tetrahedron %ld)", v->first_bad_tetrahedron);
  }
}

static int compare_u32(const void *pa, const void *pb) {
  uint32_t a = *(const uint32_t *)pa, b = *(const uint32_t *)pb;
  return (a > b) - (a < b);
}

uint32_t *metrics_triangle_vertices(const uint32_t *triangles, size_t count, size_t *vertex_count) {
  uint32_t *all = malloc((count ? count : 1) * 3 * sizeof *all);
  if (!all) return NULL;
  memcpy(all, triangles, 3 * count * sizeof *all);
  qsort(all, 3 * count, sizeof *all, compare_u32);
  size_t m = 0;
  for (size_t i = 0; i < 3 * count; i++)
    if (m == 0 || all[m - 1] != all[i]) all[m++] = all[i];
  *vertex_count = m;
  return all;
}

/* ---- Volume ----------------------------------------------------------------------------------- */

/* Neumaier's compensated sum. */
typedef struct Sum {
  double sum, compensation;
} Sum;

static void sum_add(Sum *s, double x) {
  double t = s->sum + x;
  if (fabs(s->sum) >= fabs(x))
    s->compensation += (s->sum - t) + x;
  else
    s->compensation += (x - t) + s->sum;
  s->sum = t;
}

/* dot(b-a, cross(c-a, d-a)) / 6. */
static double tetrahedron_volume(const double *a, const double *b, const double *c, const double *d) {
  double u[3], w[3], z[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    w[k] = c[k] - a[k];
    z[k] = d[k] - a[k];
  }
  return (u[0] * (w[1] * z[2] - w[2] * z[1]) + u[1] * (w[2] * z[0] - w[0] * z[2]) +
          u[2] * (w[0] * z[1] - w[1] * z[0])) /
         6.0;
}

double metrics_tetrahedra_volume(const double *xyz, const uint32_t *tets, size_t count) {
  Sum s = {0.0, 0.0};
  for (size_t t = 0; t < count; t++) {
    const uint32_t *q = tets + 4 * t;
    sum_add(&s, tetrahedron_volume(point(xyz, q[0]), point(xyz, q[1]), point(xyz, q[2]),
                                   point(xyz, q[3])));
  }
  return s.sum + s.compensation;
}

double metrics_polyhedron_volume(const double *xyz, const uint32_t *triangles, size_t count) {
  if (count == 0) return 0.0;
  const double *o = point(xyz, triangles[0]);
  Sum s = {0.0, 0.0};
  for (size_t f = 0; f < count; f++) {
    const uint32_t *t = triangles + 3 * f;
    sum_add(&s, tetrahedron_volume(o, point(xyz, t[0]), point(xyz, t[1]), point(xyz, t[2])));
  }
  return s.sum + s.compensation;
}

double metrics_relative_error(double v, double reference) {
  return fabs(v - reference) / fabs(reference);
}

/* ---- Identity of two triangulations ------------------------------------------------------------ */

static int compare_quads(const void *pa, const void *pb) {
  const uint32_t *a = pa, *b = pb;
  for (int k = 0; k < 4; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

uint32_t *metrics_tetrahedron_set(const uint32_t *tets, size_t count, const uint32_t *rename) {
  uint32_t *set = malloc((count ? count : 1) * 4 * sizeof *set);
  if (!set) return NULL;
  for (size_t t = 0; t < count; t++) {
    uint32_t *q = set + 4 * t;
    for (int k = 0; k < 4; k++) q[k] = rename ? rename[tets[4 * t + k]] : tets[4 * t + k];
    for (int i = 1; i < 4; i++) /* insertion sort of 4 */
      for (int j = i; j > 0 && q[j - 1] > q[j]; j--) {
        uint32_t tmp = q[j];
        q[j] = q[j - 1];
        q[j - 1] = tmp;
      }
  }
  qsort(set, count, 4 * sizeof *set, compare_quads);
  return set;
}

SetComparison metrics_compare_tetrahedron_sets(const uint32_t *a, size_t a_count,
                                               const uint32_t *b, size_t b_count) {
  SetComparison r = {0, 0, 0};
  size_t i = 0, j = 0;
  while (i < a_count && j < b_count) {
    int c = compare_quads(a + 4 * i, b + 4 * j);
    if (c == 0) {
      r.common++;
      i++;
      j++;
    } else if (c < 0) {
      r.only_first++;
      i++;
    } else {
      r.only_second++;
      j++;
    }
  }
  r.only_first += a_count - i;
  r.only_second += b_count - j;
  return r;
}
