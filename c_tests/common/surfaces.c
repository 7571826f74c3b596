#include "surfaces.h"

#include "prng.h"
#include "ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- A surface under construction ---------------------------------------------------------------
 * Vertices are merged by exact coordinates and triangles by vertex set (a face shared by two
 * boxes is added by both and kept once), both through open-addressing hash tables. */

typedef struct Builder {
  double *xyz;
  size_t n, vertex_capacity;
  uint32_t *tris;
  size_t m, tri_capacity;
  uint32_t *vertex_slots; /* index + 1, 0 = empty */
  size_t vertex_slot_count;
  uint32_t *tri_slots;
  size_t tri_slot_count;
  int failed;
} Builder;

static uint64_t mix(uint64_t h) {
  h ^= h >> 33;
  h *= UINT64_C(0xff51afd7ed558ccd);
  h ^= h >> 33;
  return h;
}

static uint64_t hash_point(const double p[3]) {
  uint64_t h = 0;
  for (int k = 0; k < 3; k++) {
    double x = p[k] == 0 ? 0.0 : p[k]; /* -0 and +0 are one coordinate */
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    h = mix(h ^ bits) + (uint64_t)k;
  }
  return h;
}

static void sort3(const uint32_t t[3], uint32_t s[3]) {
  s[0] = t[0], s[1] = t[1], s[2] = t[2];
  for (int i = 1; i < 3; i++)
    for (int j = i; j > 0 && s[j - 1] > s[j]; j--) {
      uint32_t x = s[j];
      s[j] = s[j - 1];
      s[j - 1] = x;
    }
}

static uint64_t hash_triangle(const uint32_t t[3]) {
  uint32_t s[3];
  sort3(t, s);
  return mix(mix(mix(s[0]) ^ s[1]) ^ s[2]);
}

static int same_point(const double *a, const double *b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static int same_triangle(const uint32_t *a, const uint32_t *b) {
  uint32_t s[3], t[3];
  sort3(a, s);
  sort3(b, t);
  return s[0] == t[0] && s[1] == t[1] && s[2] == t[2];
}

/* Rebuilds a table of `count` slots (a power of two) over the first `entries` items. */
static uint32_t *rehash(size_t count, size_t entries, const Builder *b, int triangles) {
  uint32_t *slots = calloc(count, sizeof *slots);
  if (!slots) return NULL;
  for (size_t i = 0; i < entries; i++) {
    uint64_t h = triangles ? hash_triangle(b->tris + 3 * i) : hash_point(b->xyz + 3 * i);
    size_t k = (size_t)h & (count - 1);
    while (slots[k]) k = (k + 1) & (count - 1);
    slots[k] = (uint32_t)(i + 1);
  }
  return slots;
}

static uint32_t add_vertex(Builder *b, double x, double y, double z) {
  if (b->failed) return 0;
  double p[3] = {x, y, z};
  if (2 * (b->n + 1) > b->vertex_slot_count) {
    size_t count = b->vertex_slot_count ? 2 * b->vertex_slot_count : 64;
    uint32_t *slots = rehash(count, b->n, b, 0);
    if (!slots) return b->failed = 1, 0;
    free(b->vertex_slots);
    b->vertex_slots = slots;
    b->vertex_slot_count = count;
  }
  size_t k = (size_t)hash_point(p) & (b->vertex_slot_count - 1);
  for (; b->vertex_slots[k]; k = (k + 1) & (b->vertex_slot_count - 1))
    if (same_point(b->xyz + 3 * (size_t)(b->vertex_slots[k] - 1), p)) return b->vertex_slots[k] - 1;
  if (b->n == b->vertex_capacity) {
    size_t capacity = b->vertex_capacity ? 2 * b->vertex_capacity : 64;
    double *xyz = realloc(b->xyz, 3 * capacity * sizeof *xyz);
    if (!xyz) return b->failed = 1, 0;
    b->xyz = xyz;
    b->vertex_capacity = capacity;
  }
  memcpy(b->xyz + 3 * b->n, p, sizeof p);
  b->vertex_slots[k] = (uint32_t)(b->n + 1);
  return (uint32_t)b->n++;
}

/* Adds the triangle (a, b, c) unless a triangle on the same vertices is there already. */
static void add_triangle(Builder *b, uint32_t v0, uint32_t v1, uint32_t v2) {
  if (b->failed) return;
  uint32_t t[3] = {v0, v1, v2};
  if (2 * (b->m + 1) > b->tri_slot_count) {
    size_t count = b->tri_slot_count ? 2 * b->tri_slot_count : 64;
    uint32_t *slots = rehash(count, b->m, b, 1);
    if (!slots) {
      b->failed = 1;
      return;
    }
    free(b->tri_slots);
    b->tri_slots = slots;
    b->tri_slot_count = count;
  }
  size_t k = (size_t)hash_triangle(t) & (b->tri_slot_count - 1);
  for (; b->tri_slots[k]; k = (k + 1) & (b->tri_slot_count - 1))
    if (same_triangle(b->tris + 3 * (size_t)(b->tri_slots[k] - 1), t)) return;
  if (b->m == b->tri_capacity) {
    size_t capacity = b->tri_capacity ? 2 * b->tri_capacity : 64;
    uint32_t *tris = realloc(b->tris, 3 * capacity * sizeof *tris);
    if (!tris) {
      b->failed = 1;
      return;
    }
    b->tris = tris;
    b->tri_capacity = capacity;
  }
  memcpy(b->tris + 3 * b->m, t, sizeof t);
  b->tri_slots[k] = (uint32_t)(b->m + 1);
  b->m++;
}

/* Hands the arrays to `s` (named `name`), releases the rest; 1 on success. */
static int finish(Builder *b, Surface *s, const char *name) {
  free(b->vertex_slots);
  free(b->tri_slots);
  if (b->failed) {
    free(b->xyz);
    free(b->tris);
    memset(s, 0, sizeof *s);
    return 0;
  }
  memset(s, 0, sizeof *s);
  snprintf(s->name, sizeof s->name, "%s", name);
  s->xyz = b->xyz;
  s->n = b->n;
  s->tris = b->tris;
  s->m = b->m;
  s->expected_regions = 1;
  return 1;
}

void surface_free(Surface *s) {
  if (!s) return;
  free(s->xyz);
  free(s->tris);
  free(s->culprits);
  memset(s, 0, sizeof *s);
}

/* ---- Orientation of closed 2-manifold surfaces --------------------------------------------- */

typedef struct Edge {
  uint32_t lo, hi; /* lo < hi */
  uint32_t triangle;
  uint32_t forward; /* 1 when the triangle runs lo -> hi */
} Edge;

static int compare_edges(const void *pa, const void *pb) {
  const Edge *a = pa, *b = pb;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->triangle > b->triangle) - (a->triangle < b->triangle);
}

/* The 3m edge uses of the triangles, sorted by edge (NULL when out of memory). */
static Edge *edge_uses(const uint32_t *tris, size_t m) {
  Edge *e = malloc((m ? m : 1) * 3 * sizeof *e);
  if (!e) return NULL;
  for (size_t t = 0; t < m; t++)
    for (int k = 0; k < 3; k++) {
      uint32_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
      e[3 * t + k] = (Edge){a < b ? a : b, a < b ? b : a, (uint32_t)t, a < b};
    }
  qsort(e, 3 * m, sizeof *e, compare_edges);
  return e;
}

int surface_edges(const uint32_t *tris, size_t m, size_t n, SurfaceEdges *out) {
  memset(out, 0, sizeof *out);
  for (size_t t = 0; t < m; t++) {
    const uint32_t *v = tris + 3 * t;
    if (v[0] >= n || v[1] >= n || v[2] >= n || v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
      out->bad_triangles++;
  }
  Edge *e = edge_uses(tris, m);
  if (!e) return 0;
  for (size_t i = 0; i < 3 * m;) {
    size_t j = i + 1;
    while (j < 3 * m && e[j].lo == e[i].lo && e[j].hi == e[i].hi) j++;
    out->edges++;
    if (j - i == 1) out->open++;
    if (j - i >= 3) out->nonmanifold++;
    if (j - i == 2 && e[i].forward == e[i + 1].forward) out->misoriented++;
    i = j;
  }
  free(e);
  return out->open == 0 && out->bad_triangles == 0;
}

static double cone_volume(const double *o, const double *a, const double *b, const double *c) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) u[k] = a[k] - o[k], v[k] = b[k] - o[k], w[k] = c[k] - o[k];
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

/* Orients every connected component of a closed 2-manifold surface consistently (walking
 * across edges), then outward (positive enclosed volume). Returns 0 when out of memory or when
 * the surface is not an orientable closed 2-manifold. */
static int orient_outward(Surface *s) {
  size_t m = s->m;
  Edge *e = edge_uses(s->tris, m);
  uint32_t *mate = malloc((m ? m : 1) * 3 * sizeof *mate);       /* triangle across edge k */
  uint32_t *queue = malloc((m ? m : 1) * sizeof *queue);
  int32_t *component = malloc((m ? m : 1) * sizeof *component);
  unsigned char *flip = calloc(m ? m : 1, 1);
  int ok = e && mate && queue && component && flip;
  for (size_t i = 0; ok && i < 3 * m; i += 2) {
    if (i + 1 >= 3 * m || e[i].lo != e[i + 1].lo || e[i].hi != e[i + 1].hi ||
        (i + 2 < 3 * m && e[i + 2].lo == e[i].lo && e[i + 2].hi == e[i].hi)) {
      ok = 0;
      break;
    }
    /* Which of its three edges is this, in each triangle? */
    for (int side = 0; side < 2; side++) {
      const Edge *x = &e[i + (size_t)side], *y = &e[i + 1 - (size_t)side];
      const uint32_t *t = s->tris + 3 * (size_t)x->triangle;
      for (int k = 0; k < 3; k++) {
        uint32_t a = t[k], b = t[(k + 1) % 3];
        if ((a == x->lo && b == x->hi) || (a == x->hi && b == x->lo)) mate[3 * (size_t)x->triangle + (size_t)k] = y->triangle;
      }
    }
  }
  for (size_t t = 0; ok && t < m; t++) component[t] = -1;
  int32_t components = 0;
  for (size_t seed = 0; ok && seed < m; seed++) {
    if (component[seed] >= 0) continue;
    size_t head = 0, tail = 0;
    queue[tail++] = (uint32_t)seed;
    component[seed] = components;
    while (head < tail) {
      uint32_t t = queue[head++];
      const uint32_t *v = s->tris + 3 * (size_t)t;
      for (int k = 0; k < 3; k++) {
        uint32_t u = mate[3 * (size_t)t + (size_t)k];
        /* Direction of the edge (v[k], v[k+1]) in t as it will be, and in u as it is. */
        uint32_t a = flip[t] ? v[(k + 1) % 3] : v[k], b = flip[t] ? v[k] : v[(k + 1) % 3];
        const uint32_t *w = s->tris + 3 * (size_t)u;
        int same = 0;
        for (int j = 0; j < 3; j++)
          if (w[j] == a && w[(j + 1) % 3] == b) same = 1;
        if (component[u] < 0) {
          component[u] = components;
          flip[u] = (unsigned char)same; /* u must run the edge b -> a */
          queue[tail++] = u;
        } else if ((same != 0) != (flip[u] != 0)) {
          ok = 0; /* not orientable */
        }
      }
    }
    components++;
  }
  for (size_t t = 0; ok && t < m; t++)
    if (flip[t]) {
      uint32_t x = s->tris[3 * t + 1];
      s->tris[3 * t + 1] = s->tris[3 * t + 2];
      s->tris[3 * t + 2] = x;
    }
  /* Outward: the signed volume of each component positive. */
  for (int32_t c = 0; ok && c < components; c++) {
    double volume = 0;
    for (size_t t = 0; t < m; t++) {
      if (component[t] != c) continue;
      const uint32_t *v = s->tris + 3 * t;
      volume += cone_volume(s->xyz, s->xyz + 3 * (size_t)v[0], s->xyz + 3 * (size_t)v[1], s->xyz + 3 * (size_t)v[2]);
    }
    if (volume < 0)
      for (size_t t = 0; t < m; t++)
        if (component[t] == c) {
          uint32_t x = s->tris[3 * t + 1];
          s->tris[3 * t + 1] = s->tris[3 * t + 2];
          s->tris[3 * t + 2] = x;
        }
  }
  free(e);
  free(mate);
  free(queue);
  free(component);
  free(flip);
  return ok;
}

/* finish() then orient_outward(). */
static int finish_oriented(Builder *b, Surface *s, const char *name) {
  if (!finish(b, s, name)) return 0;
  if (!orient_outward(s)) {
    surface_free(s);
    return 0;
  }
  return 1;
}

/* ---- Boxes ------------------------------------------------------------------------------------ */

/* The box [lo, hi] with res[k] squares along axis k, each face oriented outward, each square
 * split along the diagonal from its lowest to its highest corner (so that two boxes sharing a
 * face triangulate it the same way). */
static void add_box(Builder *b, const double lo[3], const double hi[3], const int res[3]) {
  for (int d = 0; d < 3; d++) {
    int u = d == 0 ? 1 : 0, v = d == 2 ? 1 : 2; /* the other two axes, u < v */
    for (int side = 0; side < 2; side++) {
      /* e_u x e_v = +e_d for d = 0, 2 and -e_d for d = 1; outward is -e_d at side 0. */
      int natural = d == 1 ? -1 : 1, outward = side ? 1 : -1;
      for (int i = 0; i < res[u]; i++)
        for (int j = 0; j < res[v]; j++) {
          uint32_t c[4];
          for (int q = 0; q < 4; q++) {
            int di = q == 1 || q == 2, dj = q >= 2;
            double p[3];
            p[d] = side ? hi[d] : lo[d];
            int a = i + di, bb = j + dj;
            p[u] = a == res[u] ? hi[u] : lo[u] + (hi[u] - lo[u]) * a / res[u];
            p[v] = bb == res[v] ? hi[v] : lo[v] + (hi[v] - lo[v]) * bb / res[v];
            c[q] = add_vertex(b, p[0], p[1], p[2]); /* c: (i,j) (i+1,j) (i+1,j+1) (i,j+1) */
          }
          if (natural == outward) {
            add_triangle(b, c[0], c[1], c[2]);
            add_triangle(b, c[0], c[2], c[3]);
          } else {
            add_triangle(b, c[0], c[2], c[1]);
            add_triangle(b, c[0], c[3], c[2]);
          }
        }
    }
  }
}

int surface_cube(Surface *s) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1}, (const int[3]){1, 1, 1});
  return finish(&b, s, "cube");
}

int surface_cube_with_nodes(Surface *s, size_t *inside) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1}, (const int[3]){1, 1, 1});
  /* 27 nodes inside, on a grid off the cube's planes, then 2 outside. */
  for (int i = 0; i < 27; i++) add_vertex(&b, 0.2 + 0.3 * (i % 3), 0.25 + 0.3 * (i / 3 % 3), 0.3 + 0.2 * (i / 9));
  add_vertex(&b, 2, 2, 2);
  add_vertex(&b, -1, 0.5, 0.5);
  *inside = 27;
  return finish(&b, s, "cube with 27 nodes inside, 2 outside");
}

int surface_octahedron(Surface *s) {
  Builder b = {0};
  uint32_t v[6];
  for (int k = 0; k < 6; k++) {
    double p[3] = {0, 0, 0};
    p[k % 3] = k < 3 ? 1 : -1;
    v[k] = add_vertex(&b, p[0], p[1], p[2]);
  }
  /* v[0..2] = +x +y +z, v[3..5] = -x -y -z */
  for (int sx = 0; sx < 2; sx++)
    for (int sy = 0; sy < 2; sy++)
      for (int sz = 0; sz < 2; sz++) add_triangle(&b, v[sx ? 3 : 0], v[sy ? 4 : 1], v[sz ? 5 : 2]);
  return finish_oriented(&b, s, "octahedron");
}

/* The level-`level` icosphere of radius r around c, added to b. */
static void add_icosphere(Builder *b, int level, const double c[3], double r) {
  const double g = (1 + sqrt(5.0)) / 2;
  const double base[12][3] = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  /* Unit-sphere triangles as coordinates, subdivided level times. */
  size_t count = 20;
  double *tri = malloc(20 * 9 * sizeof *tri);
  if (!tri) {
    b->failed = 1;
    return;
  }
  for (int f = 0; f < 20; f++)
    for (int k = 0; k < 3; k++) {
      const double *p = base[faces[f][k]];
      double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      for (int a = 0; a < 3; a++) tri[9 * f + 3 * k + a] = p[a] / len;
    }
  for (int l = 0; l < level; l++) {
    double *next = malloc(4 * count * 9 * sizeof *next);
    if (!next) {
      free(tri);
      b->failed = 1;
      return;
    }
    for (size_t f = 0; f < count; f++) {
      const double *p = tri + 9 * f;
      double mid[3][3];
      for (int k = 0; k < 3; k++) {
        const double *a = p + 3 * k, *q = p + 3 * ((k + 1) % 3);
        double x = a[0] + q[0], y = a[1] + q[1], z = a[2] + q[2]; /* symmetric in a, q */
        double len = sqrt(x * x + y * y + z * z);
        mid[k][0] = x / len, mid[k][1] = y / len, mid[k][2] = z / len;
      }
      const double *corner[4][3] = {{p, mid[0], mid[2]},
                                    {mid[0], p + 3, mid[1]},
                                    {mid[2], mid[1], p + 6},
                                    {mid[0], mid[1], mid[2]}};
      for (int t = 0; t < 4; t++)
        for (int k = 0; k < 3; k++) memcpy(next + 9 * (4 * f + (size_t)t) + 3 * k, corner[t][k], 3 * sizeof *next);
    }
    free(tri);
    tri = next;
    count *= 4;
  }
  for (size_t f = 0; f < count; f++) {
    uint32_t v[3];
    for (int k = 0; k < 3; k++) {
      const double *p = tri + 9 * f + 3 * k;
      v[k] = add_vertex(b, c[0] + r * p[0], c[1] + r * p[1], c[2] + r * p[2]);
    }
    add_triangle(b, v[0], v[1], v[2]);
  }
  free(tri);
}

int surface_icosphere(Surface *s, int level) {
  Builder b = {0};
  add_icosphere(&b, level, (const double[3]){0, 0, 0}, 1.0);
  char name[64];
  snprintf(name, sizeof name, "icosphere level %d", level);
  return finish_oriented(&b, s, name);
}

int surface_twisted_prism(Surface *s, double degrees) {
  Builder b = {0};
  const double pi = 3.14159265358979323846;
  uint32_t bottom[3], top[3];
  for (int i = 0; i < 3; i++) {
    double a = pi / 2 + 2 * pi * i / 3, t = a + degrees * pi / 180;
    bottom[i] = add_vertex(&b, cos(a), sin(a), 0);
    top[i] = add_vertex(&b, cos(t), sin(t), 1);
  }
  add_triangle(&b, bottom[0], bottom[2], bottom[1]);
  add_triangle(&b, top[0], top[1], top[2]);
  /* Side i: bottom i, i+1, top i+1, i. The diagonal bottom i - top i+1 spans 120 + twist degrees
   * around the axis and passes inside the other one (120 - twist): the reflex one. */
  for (int i = 0; i < 3; i++) {
    int j = (i + 1) % 3;
    add_triangle(&b, bottom[i], bottom[j], top[j]);
    add_triangle(&b, bottom[i], top[j], top[i]);
  }
  char name[64];
  if (degrees == 30)
    snprintf(name, sizeof name, "Schonhardt prism (30 deg)");
  else
    snprintf(name, sizeof name, "twisted prism %g deg", degrees);
  return finish_oriented(&b, s, name);
}

/* ---- Chazelle's polyhedron --------------------------------------------------------------------- */

/* A wall of the box seen in 2D: u along the wall in [-1, 1], v in [-2, 2] with v = 2 the side
 * the crevices are cut from. Its top is the polyline top[0..count) from u = -1 to u = 1 (the
 * crevices' V shapes), its bottom the straight edge v = -2. Both vertical sides carry vertices
 * at v = -1 and v = 1 (this wall's row and the next wall's). The wall is triangulated over a
 * row of vertices at v = -1 below every top vertex: columns of two triangles down to that row,
 * then a fan from (-1, -2) below it. `map` places (u, v) in space. */
typedef struct Wall {
  void (*map)(double u, double v, double fixed, double p[3]);
  double fixed; /* the wall's constant coordinate */
} Wall;

static uint32_t wall_vertex(Builder *b, const Wall *w, double u, double v) {
  double p[3];
  w->map(u, v, w->fixed, p);
  return add_vertex(b, p[0], p[1], p[2]);
}

static void add_wall(Builder *b, const Wall *w, const double *top_u, const double *top_v, size_t count) {
  /* Upper band: column c between top vertices c and c+1, down to the row v = -1. */
  for (size_t c = 0; c + 1 < count; c++) {
    uint32_t t0 = wall_vertex(b, w, top_u[c], top_v[c]), t1 = wall_vertex(b, w, top_u[c + 1], top_v[c + 1]);
    uint32_t r0 = wall_vertex(b, w, top_u[c], -1), r1 = wall_vertex(b, w, top_u[c + 1], -1);
    if (c == 0) { /* left side: (-1, 2), (-1, 1), (-1, -1): fan from t1 */
      uint32_t mid = wall_vertex(b, w, -1, 1);
      add_triangle(b, t1, t0, mid);
      add_triangle(b, t1, mid, r0);
      add_triangle(b, t1, r0, r1);
    } else if (c + 2 == count) { /* right side: fan from t0 */
      uint32_t mid = wall_vertex(b, w, 1, 1);
      add_triangle(b, t0, r0, r1);
      add_triangle(b, t0, r1, mid);
      add_triangle(b, t0, mid, t1);
    } else {
      add_triangle(b, t0, r0, r1);
      add_triangle(b, t0, r1, t1);
    }
  }
  /* Lower band: the row (u_c, -1) and the corners (-1, -2), (1, -2): fan from (-1, -2). */
  uint32_t corner = wall_vertex(b, w, -1, -2);
  for (size_t c = 0; c + 1 < count; c++)
    add_triangle(b, corner, wall_vertex(b, w, top_u[c + 1], -1), wall_vertex(b, w, top_u[c], -1));
  add_triangle(b, corner, wall_vertex(b, w, 1, -2), wall_vertex(b, w, 1, -1));
}

/* Walls y = ±1 (crevices from the top, z = v) and x = ±1 (crevices from the bottom, z = -v). */
static void map_y_wall(double u, double v, double fixed, double p[3]) {
  p[0] = u, p[1] = fixed, p[2] = v;
}
static void map_x_wall(double u, double v, double fixed, double p[3]) {
  p[0] = fixed, p[1] = u, p[2] = -v;
}

int surface_chazelle(Surface *s, int k) {
  Builder b = {0};
  const double c = 0.25, d = 0.01, height = 2;
  const double spacing = 2.0 / (k + 1), w = 0.35 * spacing;
  size_t count = 3 * (size_t)k + 2;
  double *at = malloc((size_t)k * sizeof *at), *top_u = malloc(count * sizeof *top_u), *top_v = malloc(count * sizeof *top_v);
  if (!at || !top_u || !top_v) {
    free(at);
    free(top_u);
    free(top_v);
    return finish(&(Builder){.failed = 1}, s, "");
  }
  for (int i = 0; i < k; i++) at[i] = -1 + spacing * (i + 1);
  /* Crevice i's bottom edge from the top: x = at[i], z = c at[i] y + d; from the bottom, along
   * x at y = at[j]: z = c x at[j] - d. In wall coordinates both are v = c u s + d (s = ±1). */
  for (int wall = 0; wall < 4; wall++) {
    int y_wall = wall < 2;
    double side = wall % 2 ? 1 : -1;
    Wall wl = {y_wall ? map_y_wall : map_x_wall, side};
    size_t q = 0;
    top_u[q] = -1, top_v[q++] = height;
    for (int i = 0; i < k; i++) {
      double tip = y_wall ? c * at[i] * side + d : -(c * side * at[i] - d); /* v of the edge end */
      top_u[q] = at[i] - w, top_v[q++] = height;
      top_u[q] = at[i], top_v[q++] = tip;
      top_u[q] = at[i] + w, top_v[q++] = height;
    }
    top_u[q] = 1, top_v[q++] = height;
    add_wall(&b, &wl, top_u, top_v, q);
  }
  /* Top face z = 2: strips between the crevices from the top; bottom face z = -2 likewise. */
  for (int face = 0; face < 2; face++) {
    double z = face ? -height : height;
    for (int i = 0; i <= k; i++) {
      double a = i == 0 ? -1 : at[i - 1] + w, e = i == k ? 1 : at[i] - w;
      double p[4][3] = {{a, -1, z}, {e, -1, z}, {e, 1, z}, {a, 1, z}};
      uint32_t v[4];
      for (int q = 0; q < 4; q++) {
        if (face) { /* strips along x: swap the roles of x and y */
          double t = p[q][0];
          p[q][0] = p[q][1];
          p[q][1] = t;
        }
        v[q] = add_vertex(&b, p[q][0], p[q][1], p[q][2]);
      }
      add_triangle(&b, v[0], v[1], v[2]);
      add_triangle(&b, v[0], v[2], v[3]);
    }
  }
  /* Crevice walls: two ruled quadrilaterals per crevice, each split into two triangles. */
  for (int i = 0; i < k; i++)
    for (int family = 0; family < 2; family++)
      for (int half = 0; half < 2; half++) {
        double x0 = at[i] + (half ? w : -w);
        double p[4][3];
        if (family == 0) { /* from the top, along y */
          double p0[4][3] = {{x0, -1, height}, {x0, 1, height}, {at[i], 1, c * at[i] + d}, {at[i], -1, -c * at[i] + d}};
          memcpy(p, p0, sizeof p);
        } else { /* from the bottom, along x */
          double p1[4][3] = {{-1, x0, -height}, {1, x0, -height}, {1, at[i], c * at[i] - d}, {-1, at[i], -c * at[i] - d}};
          memcpy(p, p1, sizeof p);
        }
        uint32_t v[4];
        for (int q = 0; q < 4; q++) v[q] = add_vertex(&b, p[q][0], p[q][1], p[q][2]);
        add_triangle(&b, v[0], v[1], v[2]);
        add_triangle(&b, v[0], v[2], v[3]);
      }
  free(at);
  free(top_u);
  free(top_v);
  char name[64];
  snprintf(name, sizeof name, "Chazelle k=%d", k);
  return finish_oriented(&b, s, name);
}

/* ---- Terrain, slabs, several regions ------------------------------------------------------------ */

int surface_terrain(Surface *s, int grid) {
  Builder b = {0};
  Prng g = prng_new(0x7E22A1u);
  size_t side = (size_t)grid + 1;
  uint32_t *top = malloc(side * side * sizeof *top);
  if (!top) return finish(&(Builder){.failed = 1}, s, "");
  for (size_t j = 0; j < side; j++)
    for (size_t i = 0; i < side; i++) {
      double x = i == (size_t)grid ? 1 : (double)i / grid, y = j == (size_t)grid ? 1 : (double)j / grid;
      top[j * side + i] = add_vertex(&b, x, y, 0.5 + 0.01 * (2 * prng_uniform(&g) - 1));
    }
  for (size_t j = 0; j < (size_t)grid; j++)
    for (size_t i = 0; i < (size_t)grid; i++) {
      uint32_t a = top[j * side + i], c = top[j * side + i + 1], e = top[(j + 1) * side + i + 1], f = top[(j + 1) * side + i];
      add_triangle(&b, a, c, e);
      add_triangle(&b, a, e, f);
    }
  uint32_t corner[4] = {add_vertex(&b, 0, 0, 0), add_vertex(&b, 1, 0, 0), add_vertex(&b, 1, 1, 0), add_vertex(&b, 0, 1, 0)};
  add_triangle(&b, corner[0], corner[2], corner[1]);
  add_triangle(&b, corner[0], corner[3], corner[2]);
  /* Side faces: y = 0, x = 1, y = 1, x = 0, walking the top boundary counterclockwise (seen
   * from above); each a fan from its first bottom corner. */
  for (int f = 0; f < 4; f++) {
    for (size_t a = 0; a < (size_t)grid; a++) {
      size_t p[2];
      for (int q = 0; q < 2; q++) {
        size_t t = a + (size_t)q, i, j;
        switch (f) {
          case 0: i = t, j = 0; break;
          case 1: i = (size_t)grid, j = t; break;
          case 2: i = (size_t)grid - t, j = (size_t)grid; break;
          default: i = 0, j = (size_t)grid - t; break;
        }
        p[q] = j * side + i;
      }
      add_triangle(&b, corner[f], top[p[0]], top[p[1]]);
    }
    size_t last = f == 0 ? (size_t)grid : f == 1 ? side * side - 1 : f == 2 ? (size_t)grid * side : 0;
    add_triangle(&b, corner[f], top[last], corner[(f + 1) % 4]);
  }
  free(top);
  char name[64];
  snprintf(name, sizeof name, "terrain %dx%d", grid, grid);
  return finish_oriented(&b, s, name);
}

int surface_slab(Surface *s, int split) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 0.01}, (const int[3]){split, split, 1});
  char name[64];
  snprintf(name, sizeof name, "slab 1x1x0.01, %dx%d", split, split);
  return finish(&b, s, name);
}

static void set_region(Surface *s, double x, double y, double z, double label, double max_volume) {
  double *r = s->regions + 5 * s->n_regions++;
  r[0] = x, r[1] = y, r[2] = z, r[3] = label, r[4] = max_volume;
}

int surface_nested_cubes(Surface *s, int variant) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){3, 3, 3}, (const int[3]){1, 1, 1});
  add_box(&b, (const double[3]){1, 1, 1}, (const double[3]){2, 2, 2}, (const int[3]){1, 1, 1});
  static const char *const names[4] = {"nested cubes", "nested cubes, hole", "nested cubes, seeds 7/3",
                                       "nested cubes, seeds, max volume"};
  if (!finish(&b, s, names[variant & 3])) return 0;
  s->expected_regions = 2;
  if (variant == 1) {
    s->holes[0] = s->holes[1] = s->holes[2] = 1.5;
    s->n_holes = 1;
    s->expected_regions = 1;
  } else if (variant >= 2) {
    set_region(s, 0.5, 0.5, 0.5, 7, 0);
    set_region(s, 1.5, 1.5, 1.5, 3, variant == 3 ? 0.02 : 0);
  }
  return 1;
}

int surface_glued_boxes(Surface *s) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1}, (const int[3]){1, 2, 2});
  add_box(&b, (const double[3]){1, 0, 0}, (const double[3]){2, 1, 1}, (const int[3]){2, 2, 2});
  if (!finish(&b, s, "glued boxes")) return 0;
  s->expected_regions = 2;
  return 1;
}

int surface_edge_cubes(Surface *s) {
  Builder b = {0};
  add_box(&b, (const double[3]){0, 0, 0}, (const double[3]){1, 1, 1}, (const int[3]){1, 1, 1});
  add_box(&b, (const double[3]){1, 1, 0}, (const double[3]){2, 2, 1}, (const int[3]){1, 1, 1});
  if (!finish(&b, s, "cubes sharing an edge")) return 0;
  s->expected_regions = 2;
  return 1;
}

/* ---- Invalid surfaces -------------------------------------------------------------------------- */

static int set_culprits(Surface *s, const unsigned char *is_culprit) {
  size_t count = 0;
  for (size_t t = 0; t < s->m; t++) count += is_culprit[t] != 0;
  s->culprits = malloc((count ? count : 1) * sizeof *s->culprits);
  if (!s->culprits) return 0;
  for (size_t t = 0; t < s->m; t++)
    if (is_culprit[t]) s->culprits[s->culprit_count++] = (uint32_t)t;
  return 1;
}

int surface_open_cube(Surface *s) {
  if (!surface_cube(s)) return 0;
  snprintf(s->name, sizeof s->name, "open cube (one triangle removed)");
  s->defect = "open";
  s->expected_regions = 0;
  uint32_t removed[3];
  memcpy(removed, s->tris + 3 * (s->m - 1), sizeof removed);
  s->m--;
  unsigned char *is_culprit = calloc(s->m, 1);
  if (!is_culprit) return surface_free(s), 0;
  for (size_t t = 0; t < s->m; t++) {
    int shared = 0;
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) shared += s->tris[3 * t + k] == removed[j];
    is_culprit[t] = shared >= 2; /* shares an edge with the removed triangle */
  }
  int ok = set_culprits(s, is_culprit);
  free(is_culprit);
  if (!ok) surface_free(s);
  return ok;
}

static int orient(const double *a, const double *b, const double *c, const double *d) {
  return ref_orient3d_exact(a, b, c, d);
}

/* Whether the segment pq meets the closed triangle abc (exact; a segment in the triangle's plane
 * counts as meeting it, which two overlapping spheres in general position never produce). */
static int segment_meets_triangle(const double *p, const double *q, const double *a, const double *b, const double *c) {
  int sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if (sp != 0 && sp == sq) return 0;
  if (sp == 0 && sq == 0) return 1;
  int o1 = orient(p, q, a, b), o2 = orient(p, q, b, c), o3 = orient(p, q, c, a);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

static int triangles_meet(const Surface *s, size_t t, size_t u) {
  const double *p[3], *q[3];
  for (int k = 0; k < 3; k++) {
    p[k] = s->xyz + 3 * (size_t)s->tris[3 * t + k];
    q[k] = s->xyz + 3 * (size_t)s->tris[3 * u + k];
  }
  for (int k = 0; k < 3; k++) { /* bounding boxes first */
    double lo = fmin(fmin(p[0][k], p[1][k]), p[2][k]), hi = fmax(fmax(p[0][k], p[1][k]), p[2][k]);
    double lo2 = fmin(fmin(q[0][k], q[1][k]), q[2][k]), hi2 = fmax(fmax(q[0][k], q[1][k]), q[2][k]);
    if (hi < lo2 || hi2 < lo) return 0;
  }
  for (int k = 0; k < 3; k++) {
    if (segment_meets_triangle(p[k], p[(k + 1) % 3], q[0], q[1], q[2])) return 1;
    if (segment_meets_triangle(q[k], q[(k + 1) % 3], p[0], p[1], p[2])) return 1;
  }
  return 0;
}

int surface_intersecting_spheres(Surface *s) {
  Builder b = {0};
  add_icosphere(&b, 2, (const double[3]){0, 0, 0}, 1.0);
  size_t first = b.m;
  add_icosphere(&b, 2, (const double[3]){0.9, 0.13, 0.07}, 0.8);
  if (!finish_oriented(&b, s, "two intersecting spheres")) return 0;
  s->defect = "self-intersecting";
  s->expected_regions = 0;
  unsigned char *is_culprit = calloc(s->m, 1);
  if (!is_culprit) return surface_free(s), 0;
  for (size_t t = 0; t < first; t++)
    for (size_t u = first; u < s->m; u++)
      if (triangles_meet(s, t, u)) is_culprit[t] = is_culprit[u] = 1;
  int ok = set_culprits(s, is_culprit);
  free(is_culprit);
  if (!ok) surface_free(s);
  return ok;
}

int surface_zero_area(Surface *s) {
  Builder b = {0};
  uint32_t v[8];
  for (int k = 0; k < 8; k++) v[k] = add_vertex(&b, k & 1, (k >> 1) & 1, (k >> 2) & 1); /* v[x + 2y + 4z] */
  uint32_t m = add_vertex(&b, 0.5, 0, 1);                                                /* on the edge v4 v5 */
  static const int quads[5][4] = {{0, 2, 3, 1}, {0, 1, 5, 4}, {1, 3, 7, 5}, {3, 2, 6, 7}, {2, 0, 4, 6}};
  for (int f = 0; f < 5; f++) { /* bottom and the four sides */
    const int *q = quads[f];
    add_triangle(&b, v[q[0]], v[q[1]], v[q[2]]);
    add_triangle(&b, v[q[0]], v[q[2]], v[q[3]]);
  }
  /* Top z = 1: v4 v5 v7 v6; the triangle (v4, v5, v7) beside the edge v4 v5 becomes
   * (v4, m, v7) and (m, v5, v7), and the zero-area (v4, v5, m) closes the edges. */
  add_triangle(&b, v[4], m, v[7]);
  add_triangle(&b, m, v[5], v[7]);
  add_triangle(&b, v[4], v[7], v[6]);
  add_triangle(&b, v[4], v[5], m);
  if (!finish_oriented(&b, s, "cube with a zero-area triangle")) return 0;
  s->defect = "zero-area";
  s->expected_regions = 0;
  unsigned char *is_culprit = calloc(s->m, 1);
  if (!is_culprit) return surface_free(s), 0;
  is_culprit[s->m - 1] = 1;
  int ok = set_culprits(s, is_culprit);
  free(is_culprit);
  if (!ok) surface_free(s);
  return ok;
}
