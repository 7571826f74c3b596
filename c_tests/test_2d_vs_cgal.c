/* Conforming Delaunay triangulation of planar straight-line graphs (API.md "2D"), against CGAL's
 * Constrained_Delaunay_triangulation_2 + make_conforming_Delaunay_2 on generated cases: Pébay's
 * situations (fans of acute edges at one point, chains of acute angles, closed nodes, discretized
 * arcs), cocircular grids, tiny angles, long thin domains, random polygons.
 *
 * For each case, through the C API and with CGAL's exact predicates only:
 * - validity: every triangle counter-clockwise, every edge in one or two triangles, the
 *   triangulation Delaunay (every interior edge locally Delaunay), every vertex used;
 * - every constraint sub-edge strongly Delaunay-admissible: no vertex in its closed small disk
 *   but its ends, or else an edge between two triangles that are not cocircular (Pébay's types
 *   1.0 / 1.2.0) or on the hull;
 * - every input segment the union of its sub-edges (listed in order, through added points);
 * - inserted points, ours beside CGAL's (CGAL's output must be valid too), printed: ours must
 *   not exceed CGAL's on each case, nor over all cases together.
 *
 * Crossing segments split at their intersections (split_crossing_segments = 1: lines crossing
 * in a grid, a star through one point, random segments): the same checks, and as many
 * intersection points as CGAL's constrained triangulation with Exact_predicates_tag inserts
 * (its crossing constraints split there too); inserted points, these included, at most
 * CGAL's on each case.
 *
 * Quality mode at 25 and 30 degrees, against CGAL's refine_Delaunay_mesh_2 with
 * Delaunay_mesh_size_criteria_2 at the same angle bound, on closed domains (a letter A with its
 * counter as a hole, a thin rhombus, a square with a square hole, the closed cases above):
 * triangles counter-clockwise, interior edges locally Delaunay, sub-segments strongly
 * admissible and chained as above; every triangle's smallest angle at least the bound except
 * at input angles below 60 degrees (its shortest edge joining two segments that meet there;
 * counted and printed); our triangle count at most CGAL's + 15% (both printed, with the
 * smallest angles). */
#include "check.h"
#include "prng.h"
#include "ref_cgal2d.h"

#include <delmesh.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ITEMS 4096

typedef struct Case {
  char name[96];
  double xy[2 * MAX_ITEMS];
  size_t n;
  uint32_t seg[2 * MAX_ITEMS];
  size_t m;
} Case;

static const double PI = 3.14159265358979323846;

static uint32_t add_point(Case *c, double x, double y) {
  c->xy[2 * c->n] = x;
  c->xy[2 * c->n + 1] = y;
  return (uint32_t)c->n++;
}

static void add_segment(Case *c, uint32_t a, uint32_t b) {
  c->seg[2 * c->m] = a;
  c->seg[2 * c->m + 1] = b;
  c->m++;
}

static void polyline(Case *c, uint32_t first, uint32_t count, int closed) {
  for (uint32_t i = 0; i + 1 < count; ++i) add_segment(c, first + i, first + i + 1);
  if (closed) add_segment(c, first + count - 1, first);
}

/* ---------------------------------------------------------------- generated cases */

static void make_fan(Case *c, int k, double spread) {
  snprintf(c->name, sizeof c->name, "fan of %d edges over %.0f degrees", k, spread);
  add_point(c, 0.0, 0.0);
  for (int i = 0; i < k; ++i) {
    double a = spread * i / k * PI / 180.0, r = 1.0 + 0.37 * ((i * 7) % 5);
    add_segment(c, 0, add_point(c, r * cos(a), r * sin(a)));
  }
}

static void make_zigzag(Case *c) {
  snprintf(c->name, sizeof c->name, "zigzag of acute angles");
  for (int i = 0; i < 12; ++i) add_point(c, i % 2 ? 3.0 : 0.0, 0.3 * (i / 2) + (i % 2 ? 1.0 : 0.0));
  polyline(c, 0, 12, 0);
}

static void make_spiral(Case *c) {
  snprintf(c->name, sizeof c->name, "spiral of acute turns");
  for (int i = 0; i < 30; ++i) {
    double a = 1.2 * i, r = 1.0 + 0.15 * i;
    add_point(c, r * cos(a), r * sin(a));
  }
  polyline(c, 0, 30, 0);
}

static void make_closed_nodes(Case *c) {
  snprintf(c->name, sizeof c->name, "two closed nodes");
  double centre[2][2] = {{0.0, 0.0}, {3.0, 0.2}};
  add_point(c, 0.0, 0.0);
  add_point(c, 3.0, 0.2);
  for (int s = 0; s < 2; ++s) {
    for (int i = 0; i < 9; ++i) {
      double a = (i * 40.0 + 10.0 * s) * PI / 180.0, r = i % 2 ? 0.6 : 1.0;
      add_segment(c, (uint32_t)s, add_point(c, centre[s][0] + r * cos(a), centre[s][1] + r * sin(a)));
    }
  }
}

static void make_arcs(Case *c) {
  snprintf(c->name, sizeof c->name, "discretized arcs splitting a box");
  add_point(c, -1, -1);
  add_point(c, 5, -1);
  add_point(c, 5, 4);
  add_point(c, -1, 4);
  polyline(c, 0, 4, 1);
  uint32_t first = (uint32_t)c->n;
  for (int i = 0; i <= 16; ++i) {
    double a = PI * (1.0 - i / 16.0);
    add_point(c, 2.0 + 2.0 * cos(a), 2.0 * sin(a));
  }
  polyline(c, first, 17, 0);
  add_segment(c, 0, first);
  add_segment(c, 1, first + 16);
  for (int k = 0; k < 2; ++k) {
    double radius = k ? 2.1 : 1.9;
    uint32_t start = (uint32_t)c->n;
    for (int i = 0; i < 16; ++i) {
      double a = PI * (1.0 - (i + 0.5) / 16.0);
      add_point(c, 2.0 + radius * cos(a), radius * sin(a));
    }
    polyline(c, start, 16, 0);
  }
}

static void make_grid(Case *c) {
  snprintf(c->name, sizeof c->name, "cocircular 8x8 grid with constraints");
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) add_point(c, x, y);
#define ID(x, y) ((uint32_t)((y) * 8 + (x)))
  for (int i = 0; i < 7; ++i) {
    add_segment(c, ID(i, 0), ID(i + 1, 0));
    add_segment(c, ID(i, 7), ID(i + 1, 7));
    add_segment(c, ID(0, i), ID(0, i + 1));
    add_segment(c, ID(7, i), ID(7, i + 1));
  }
  add_segment(c, ID(1, 1), ID(6, 3));
  add_segment(c, ID(1, 6), ID(6, 5));
  add_segment(c, ID(2, 2), ID(3, 5));
#undef ID
}

static void make_tiny_angle(Case *c, double degrees) {
  snprintf(c->name, sizeof c->name, "%.0f degree angle", degrees);
  double a = degrees * PI / 180.0;
  add_point(c, 0, 0);
  add_point(c, 1, 0);
  add_point(c, 0.8 * cos(a), 0.8 * sin(a));
  add_point(c, 0.5, -0.5);
  add_segment(c, 0, 1);
  add_segment(c, 0, 2);
  add_segment(c, 0, 3);
}

static void make_thin_domain(Case *c) {
  snprintf(c->name, sizeof c->name, "long thin domain with a wavy midline");
  add_point(c, 0, 0);
  add_point(c, 40, 0);
  add_point(c, 40, 1);
  add_point(c, 0, 1);
  polyline(c, 0, 4, 1);
  uint32_t first = (uint32_t)c->n;
  for (int i = 0; i <= 40; ++i) add_point(c, 0.5 + 0.975 * i, 0.5 + 0.3 * sin(1.3 * i));
  polyline(c, first, 41, 0);
}

static void make_thin_rhombus(Case *c) {
  snprintf(c->name, sizeof c->name, "thin rhombus with interior points");
  add_point(c, 0, 0);
  add_point(c, 10, 0.7);
  add_point(c, 20, 0);
  add_point(c, 10, -0.7);
  polyline(c, 0, 4, 1);
  for (int i = 1; i < 10; ++i) add_point(c, 2.0 * i, 0.05 * ((i * 3) % 5 - 2));
}

static void make_star_polygon(Case *c, int k, uint64_t seed) {
  snprintf(c->name, sizeof c->name, "random star polygon of %d edges", k);
  Prng g = prng_new(seed);
  double angle[MAX_ITEMS];
  for (int i = 0; i < k; ++i) angle[i] = prng_uniform(&g) * 2.0 * PI;
  for (int i = 1; i < k; ++i) /* insertion sort */
    for (int j = i; j > 0 && angle[j] < angle[j - 1]; --j) {
      double t = angle[j];
      angle[j] = angle[j - 1];
      angle[j - 1] = t;
    }
  for (int i = 0; i < k; ++i) {
    double r = 0.3 + 0.7 * prng_uniform(&g);
    add_point(c, r * cos(angle[i]), r * sin(angle[i]));
  }
  polyline(c, 0, (uint32_t)k, 1);
  for (int i = 0; i < k; ++i) add_point(c, 0.4 * prng_uniform(&g) - 0.2, 0.4 * prng_uniform(&g) - 0.2);
}

/* ---------------------------------------------------------------- checks */

static const double *vtx(const double *xyz, uint32_t i, double out[2]) {
  out[0] = xyz[3 * (size_t)i];
  out[1] = xyz[3 * (size_t)i + 1];
  return out;
}

typedef struct EdgeUse {
  uint32_t a, b; /* a < b */
  uint32_t opposite[2];
  int count;
} EdgeUse;

static int cmp_edge(const void *x, const void *y) {
  const EdgeUse *e = x, *f = y;
  if (e->a != f->a) return e->a < f->a ? -1 : 1;
  if (e->b != f->b) return e->b < f->b ? -1 : 1;
  return 0;
}

/* The triangle edges with their opposite vertices, sorted; NULL when an edge is in more than
 * two triangles. */
static EdgeUse *edge_table(const uint32_t *tri, size_t nt, size_t *count) {
  EdgeUse *all = malloc(3 * nt * sizeof *all + 1);
  if (!all) return NULL;
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = tri[3 * t + k], b = tri[3 * t + (k + 1) % 3];
      EdgeUse *e = &all[3 * t + k];
      e->a = a < b ? a : b;
      e->b = a < b ? b : a;
      e->opposite[0] = tri[3 * t + (k + 2) % 3];
      e->count = 1;
    }
  qsort(all, 3 * nt, sizeof *all, cmp_edge);
  size_t out = 0;
  for (size_t i = 0; i < 3 * nt; ++i) {
    if (out > 0 && cmp_edge(&all[out - 1], &all[i]) == 0) {
      if (all[out - 1].count == 2) {
        free(all);
        return NULL;
      }
      all[out - 1].opposite[1] = all[i].opposite[0];
      all[out - 1].count = 2;
    } else {
      all[out++] = all[i];
    }
  }
  *count = out;
  return all;
}

static const EdgeUse *find_edge(const EdgeUse *table, size_t count, uint32_t a, uint32_t b) {
  EdgeUse key;
  key.a = a < b ? a : b;
  key.b = a < b ? b : a;
  return bsearch(&key, table, count, sizeof *table, cmp_edge);
}

/* Validity and the Delaunay property; writes the edge table for the later checks. */
/* Every edge shared by two triangles of `table` is locally Delaunay (exact, CGAL). */
static int locally_delaunay(const double *xyz, const EdgeUse *table, size_t count, char *why, size_t why_len) {
  double p[3][2], q[2];
  for (size_t e = 0; e < count; ++e) {
    const EdgeUse *u = &table[e];
    if (u->count != 2) continue;
    /* Counter-clockwise (a, b, opposite[0]) or (b, a, opposite[0]). */
    vtx(xyz, u->a, p[0]);
    vtx(xyz, u->b, p[1]);
    vtx(xyz, u->opposite[0], p[2]);
    if (ref_orient_2(p[0], p[1], p[2]) < 0) {
      double t[2] = {p[0][0], p[0][1]};
      memcpy(p[0], p[1], sizeof t);
      memcpy(p[1], t, sizeof t);
    }
    if (ref_incircle_2(p[0], p[1], p[2], vtx(xyz, u->opposite[1], q)) > 0)
      return snprintf(why, why_len, "edge (%u, %u) is not locally Delaunay", u->a, u->b), 0;
  }
  return 1;
}

static int check_triangulation(const DelmeshMesh *mesh, size_t n_input, EdgeUse **table,
                               size_t *table_count, char *why, size_t why_len) {
  size_t nv = delmesh_mesh_vertex_count(mesh), nt = delmesh_mesh_triangle_count(mesh);
  const double *xyz = delmesh_mesh_vertices(mesh);
  const uint32_t *tri = delmesh_mesh_triangles(mesh);
  const uint32_t *dup = delmesh_mesh_duplicate_of(mesh);
  double p[3][2];
  char *used = calloc(nv + 1, 1);
  if (!used) return snprintf(why, why_len, "out of memory"), 0;
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      if (tri[3 * t + k] >= nv) return free(used), snprintf(why, why_len, "index out of range"), 0;
      used[tri[3 * t + k]] = 1;
      vtx(xyz, tri[3 * t + k], p[k]);
    }
    if (ref_orient_2(p[0], p[1], p[2]) != 1) {
      free(used);
      return snprintf(why, why_len, "triangle %zu not counter-clockwise", t), 0;
    }
  }
  for (size_t i = 0; i < nv; ++i) {
    int copy = i < n_input && dup && dup[i] != i;
    if (!used[i] && !copy) return free(used), snprintf(why, why_len, "vertex %zu unused", i), 0;
  }
  free(used);
  *table = edge_table(tri, nt, table_count);
  if (!*table) return snprintf(why, why_len, "an edge is in more than two triangles"), 0;
  return locally_delaunay(xyz, *table, *table_count, why, why_len);
}

/* Strong admissibility of every sub-edge (see the file comment). */
static int check_admissible(const DelmeshMesh *mesh, size_t n_input, const EdgeUse *table,
                            size_t table_count, char *why, size_t why_len) {
  size_t nv = delmesh_mesh_vertex_count(mesh), ne = delmesh_mesh_edge_count(mesh);
  const double *xyz = delmesh_mesh_vertices(mesh);
  const uint32_t *edges = delmesh_mesh_edges(mesh);
  const uint32_t *dup = delmesh_mesh_duplicate_of(mesh);
  double a[2], b[2], q[2], c[2], d[2];
  for (size_t e = 0; e < ne; ++e) {
    uint32_t i = edges[2 * e], j = edges[2 * e + 1];
    vtx(xyz, i, a);
    vtx(xyz, j, b);
    int empty = 1;
    for (size_t v = 0; v < nv && empty; ++v) {
      if (v == i || v == j || (v < n_input && dup && dup[v] != v)) continue;
      if (ref_small_disk_side(a, b, vtx(xyz, (uint32_t)v, q)) >= 0) empty = 0;
    }
    if (empty) continue;
    const EdgeUse *u = find_edge(table, table_count, i, j);
    if (!u) return snprintf(why, why_len, "sub-edge %zu (%u, %u) is not a triangle edge", e, i, j), 0;
    if (u->count == 1) continue; /* a hull edge */
    vtx(xyz, u->opposite[0], c);
    vtx(xyz, u->opposite[1], d);
    int o = ref_orient_2(a, b, c);
    int side = o > 0 ? ref_incircle_2(a, b, c, d) : ref_incircle_2(b, a, c, d);
    if (side == 0)
      return snprintf(why, why_len, "sub-edge %zu (%u, %u) is a diagonal of cocircular points", e, i, j), 0;
  }
  return 1;
}

/* Every input segment is the chain of the next sub-edges of the list, through added points
 * close to the segment. */
static int check_union(const DelmeshMesh *mesh, const Case *c, char *why, size_t why_len) {
  size_t ne = delmesh_mesh_edge_count(mesh), pos = 0;
  const uint32_t *edges = delmesh_mesh_edges(mesh);
  const double *xyz = delmesh_mesh_vertices(mesh);
  for (size_t k = 0; k < c->m; ++k) {
    uint32_t a = c->seg[2 * k], b = c->seg[2 * k + 1], cur = a;
    const double *pa = &c->xy[2 * (size_t)a], *pb = &c->xy[2 * (size_t)b];
    double len2 = (pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]);
    while (cur != b) {
      if (pos >= ne || edges[2 * pos] != cur)
        return snprintf(why, why_len, "segment %zu is not a chain of sub-edges", k), 0;
      cur = edges[2 * pos + 1];
      pos++;
      if (cur != b) {
        double p[2];
        vtx(xyz, cur, p);
        double h = fabs((p[0] - pa[0]) * (pb[1] - pa[1]) - (p[1] - pa[1]) * (pb[0] - pa[0])) / len2;
        if (cur < c->n || h > 1e-12)
          return snprintf(why, why_len, "segment %zu passes through vertex %u", k, cur), 0;
      }
    }
  }
  if (pos != ne) return snprintf(why, why_len, "%zu sub-edges belong to no segment", ne - pos), 0;
  return 1;
}

static size_t total_ours, total_cgal;

/* The conforming triangulation of c (crossing segments split when `split`), checked as every
 * conforming result is: valid Delaunay, every sub-edge strongly Delaunay-admissible, every
 * segment the union of its sub-edges. NULL when the call fails (reported). */
static DelmeshMesh *conforming_checked(const Case *c, int split) {
  DelmeshOptions2d options;
  memset(&options, 0, sizeof options);
  options.mode = DELMESH_MODE2D_CONFORMING;
  options.split_crossing_segments = split;
  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = delmesh_triangulate_2d(c->xy, c->n, c->seg, c->m, &options, &mesh);
  if (!check_case(s == DELMESH_OK, "%s: delmesh_triangulate_2d%s (%s)", c->name, split ? ", crossings split" : "",
                  s == DELMESH_OK ? "ok" : delmesh_last_error_message()))
    return NULL;
  char why[256] = "";
  EdgeUse *table = NULL;
  size_t table_count = 0;
  int valid = check_triangulation(mesh, c->n, &table, &table_count, why, sizeof why);
  check_case(valid, "%s: valid Delaunay triangulation%s%s", c->name, valid ? "" : ": ", why);
  if (valid) {
    int ok = check_admissible(mesh, c->n, table, table_count, why, sizeof why);
    check_case(ok, "%s: every sub-edge strongly Delaunay-admissible%s%s", c->name, ok ? "" : ": ", why);
  }
  int chained = check_union(mesh, c, why, sizeof why);
  check_case(chained, "%s: every segment the union of its sub-edges%s%s", c->name, chained ? "" : ": ", why);
  free(table);
  return mesh;
}

/* Pebay's degradation alpha h / r of the triangle abc (h the longest edge, r the inradius). */
static double degradation(const double *a, const double *b, const double *c) {
  double x = hypot(b[0] - a[0], b[1] - a[1]), y = hypot(c[0] - b[0], c[1] - b[1]), z = hypot(a[0] - c[0], a[1] - c[1]);
  double area = fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
  return sqrt(3.0) / 6.0 * fmax(x, fmax(y, z)) * (x + y + z) / (2 * area);
}

/* delmesh_mesh_triangle_degradation against the same figures computed here from the mesh's
 * arrays; both printed beside CGAL's. */
static void check_degradation(const Case *c, const DelmeshMesh *mesh, const RefConforming2d *cgal) {
  double best = 0, worst = 0, mean = 0;
  DelmeshStatus s = delmesh_mesh_triangle_degradation(mesh, &best, &worst, &mean);
  const double *v = delmesh_mesh_vertices(mesh);
  const uint32_t *t = delmesh_mesh_triangles(mesh);
  size_t count = delmesh_mesh_triangle_count(mesh);
  double lo = INFINITY, hi = 0, sum = 0;
  for (size_t k = 0; k < count; ++k) {
    double d = degradation(v + 3 * t[3 * k], v + 3 * t[3 * k + 1], v + 3 * t[3 * k + 2]);
    lo = fmin(lo, d), hi = fmax(hi, d), sum += d;
  }
  double m = count ? sum / (double)count : 0;
  int same = s == DELMESH_OK && fabs(best - lo) <= 1e-12 * lo && fabs(worst - hi) <= 1e-12 * hi &&
             fabs(mean - m) <= 1e-12 * m;
  check_case(same, "%s: delmesh_mesh_triangle_degradation %.6g / %.6g / %.6g = best / worst / mean of the triangles",
             c->name, best, worst, mean);
  check_note("%-40s degradation worst / mean: delmesh %.4g / %.4g, CGAL %.4g / %.4g", c->name, worst, mean,
             cgal->worst_degradation, cgal->mean_degradation);
}

/* Circumcenter of the triangle a, b, c (z ignored). */
static void circumcenter(const double *a, const double *b, const double *c, double out[2]) {
  double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  double d = 2 * (bx * cy - by * cx), b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  out[0] = a[0] + (cy * b2 - by * c2) / d;
  out[1] = a[1] + (bx * c2 - cx * b2) / d;
}

/* The Delaunay cover cells: the triangles of a cell share their circumcircle (floating point,
 * relative to the triangle's size), and no cell spans a constraint sub-edge (Theorem 2.1:
 * strongly admissible edges are cover edges). Cell and triangle counts printed. */
static void check_cover(const Case *c, const DelmeshMesh *mesh) {
  size_t count = delmesh_mesh_triangle_count(mesh), cells = delmesh_mesh_cover_cell_count(mesh);
  const uint32_t *cell = delmesh_mesh_triangle_cover_cells(mesh);
  const uint32_t *t = delmesh_mesh_triangles(mesh), *e = delmesh_mesh_edges(mesh);
  const double *v = delmesh_mesh_vertices(mesh);
  size_t ne = delmesh_mesh_edge_count(mesh), spans = 0, apart = 0;
  double *centre = calloc(2 * (cells ? cells : 1), sizeof *centre);
  int *seen = calloc(cells ? cells : 1, sizeof *seen);
  int ok = cell != NULL && cells >= 1 && cells <= count && centre && seen;
  for (size_t k = 0; ok && k < count; ++k) {
    const double *a = v + 3 * t[3 * k], *b = v + 3 * t[3 * k + 1], *d = v + 3 * t[3 * k + 2];
    double o[2], size = fmax(fabs(b[0] - a[0]) + fabs(b[1] - a[1]), fabs(d[0] - a[0]) + fabs(d[1] - a[1]));
    circumcenter(a, b, d, o);
    if (cell[k] >= cells) {
      ok = 0;
    } else if (!seen[cell[k]]) {
      seen[cell[k]] = 1, centre[2 * cell[k]] = o[0], centre[2 * cell[k] + 1] = o[1];
    } else if (fabs(o[0] - centre[2 * cell[k]]) + fabs(o[1] - centre[2 * cell[k] + 1]) > 1e-9 * size) {
      apart++;
    }
  }
  /* Each constraint sub-edge, and the triangles on its two sides. */
  for (size_t j = 0; ok && j < ne; ++j) {
    size_t side[2] = {SIZE_MAX, SIZE_MAX};
    for (size_t k = 0; k < count; ++k) {
      for (int r = 0; r < 3; ++r) {
        uint32_t p = t[3 * k + r], q = t[3 * k + (r + 1) % 3];
        if (p == e[2 * j] && q == e[2 * j + 1]) side[0] = k;
        if (p == e[2 * j + 1] && q == e[2 * j]) side[1] = k;
      }
    }
    if (side[0] != SIZE_MAX && side[1] != SIZE_MAX && cell[side[0]] == cell[side[1]]) spans++;
  }
  check_case(ok && apart == 0 && spans == 0,
             "%s: %zu Delaunay cover cells for %zu triangles; %zu cells spanning a sub-edge, %zu triangles off "
             "their cell's circle",
             c->name, cells, count, spans, apart);
  free(centre);
  free(seen);
}

static void run_case(const Case *c) {
  DelmeshMesh *mesh = conforming_checked(c, 0);
  if (!mesh) return;
  size_t ours = delmesh_mesh_vertex_count(mesh) - c->n;
  RefConforming2d cgal;
  if (ref_cgal_conforming_2d(c->xy, c->n, c->seg, c->m, &cgal, NULL) != 0) {
    check_case(0, "%s: CGAL conforming Delaunay: %s", c->name, ref_last_error());
  } else {
    size_t theirs = cgal.vertex_count - c->n;
    check_case(cgal.valid, "%s: CGAL's conforming triangulation is valid", c->name);
    check_note("%-40s inserted points: delmesh %4zu  CGAL %4zu  (sub-edges %zu / %zu)", c->name, ours,
               theirs, delmesh_mesh_edge_count(mesh), cgal.constrained_edge_count);
    check_case(ours <= theirs, "%s: %zu inserted points, at most CGAL's %zu", c->name, ours, theirs);
    check_degradation(c, mesh, &cgal);
    check_cover(c, mesh);
    total_ours += ours;
    total_cgal += theirs;
  }
  delmesh_mesh_free(mesh);
}

/* ---------------------------------------------------------------- crossing segments */

static void make_hash(Case *c, int k) {
  snprintf(c->name, sizeof c->name, "%d x %d crossing lines", k, k);
  for (int i = 0; i < k; ++i) {
    double t = 1.0 + 0.9 * i + 0.05 * (i % 3);
    add_segment(c, add_point(c, 0.0, t), add_point(c, 1.0 + 0.9 * k, t + 0.1));
    add_segment(c, add_point(c, t, 0.0), add_point(c, t - 0.15, 1.0 + 0.9 * k));
  }
}

static void make_star(Case *c, int k) {
  snprintf(c->name, sizeof c->name, "star of %d segments through one point", k);
  for (int i = 0; i < k; ++i) {
    double a = 0.2 + PI * i / k, r = 1.0 + 0.25 * (i % 3);
    add_segment(c, add_point(c, r * cos(a), r * sin(a)), add_point(c, -r * cos(a), -r * sin(a)));
  }
}

static void make_random_segments(Case *c, int k, uint64_t seed) {
  snprintf(c->name, sizeof c->name, "%d random crossing segments", k);
  Prng g = prng_new(seed);
  for (int i = 0; i < k; ++i) {
    uint32_t a = add_point(c, prng_uniform(&g), prng_uniform(&g));
    add_segment(c, a, add_point(c, prng_uniform(&g), prng_uniform(&g)));
  }
}

/* Split crossing segments: the checks of run_case on the result, and the intersection points
 * (our vertices of dimension 0 past the input points) as many as CGAL's constrained
 * triangulation with Exact_predicates_tag inserts; inserted points printed beside CGAL's. */
static void run_crossing_case(const Case *c) {
  DelmeshMesh *mesh = conforming_checked(c, 1);
  if (!mesh) return;
  size_t nv = delmesh_mesh_vertex_count(mesh), crossings = 0;
  const int8_t *dims = delmesh_mesh_vertex_dimensions(mesh);
  while (c->n + crossings < nv && dims[c->n + crossings] == 0) crossings++;
  RefConforming2d cgal;
  if (ref_cgal_conforming_2d_crossing(c->xy, c->n, c->seg, c->m, &cgal) != 0) {
    check_case(0, "%s: CGAL conforming Delaunay: %s", c->name, ref_last_error());
  } else {
    check_case(cgal.valid, "%s: CGAL's conforming triangulation is valid", c->name);
    check_case(crossings == cgal.intersection_count, "%s: %zu intersection points, as CGAL's %zu", c->name,
               crossings, cgal.intersection_count);
    check_note("%-40s inserted points: delmesh %4zu  CGAL %4zu  (sub-edges %zu / %zu)", c->name, nv - c->n,
               cgal.vertex_count - c->n, delmesh_mesh_edge_count(mesh), cgal.constrained_edge_count);
    check_case(nv <= cgal.vertex_count, "%s: %zu inserted points, at most CGAL's %zu", c->name, nv - c->n,
               cgal.vertex_count - c->n);
  }
  delmesh_mesh_free(mesh);
}

static void crossing_cases(void) {
  static Case c;
  memset(&c, 0, sizeof c);
  make_hash(&c, 2);
  run_crossing_case(&c);
  memset(&c, 0, sizeof c);
  make_hash(&c, 6);
  run_crossing_case(&c);
  memset(&c, 0, sizeof c);
  make_star(&c, 8);
  run_crossing_case(&c);
  memset(&c, 0, sizeof c);
  make_random_segments(&c, 40, 0x5e65);
  run_crossing_case(&c);
}

/* One bad call: the status, *out untouched, and the message containing `word`. */
static void expect_failure(const char *what, const double *xy, size_t n, const uint32_t *seg,
                           size_t m, const DelmeshOptions2d *options, DelmeshStatus want,
                           const char *word) {
  static double sentinel_storage;
  DelmeshMesh *sentinel = (DelmeshMesh *)(void *)&sentinel_storage, *out = sentinel;
  DelmeshStatus s = delmesh_triangulate_2d(xy, n, seg, m, options, &out);
  const char *message = delmesh_last_error_message();
  check_case(s == want && out == sentinel && strstr(message, word) != NULL, "%s: status %d, message \"%s\"",
             what, (int)s, message);
}

static void error_paths(void) {
  const double xy[] = {0, 0, 2, 0, 2, 2, 0, 2, 1, 0, 1, 1};
  const uint32_t cross[] = {4, 2, 1, 5}, through[] = {0, 1}, zero[] = {2, 2}, range[] = {0, 9};
  DelmeshOptions2d options;
  memset(&options, 0, sizeof options);
  options.mode = DELMESH_MODE2D_CONFORMING;
  expect_failure("crossing segments", xy, 6, cross, 2, &options, DELMESH_ERROR_INVALID_INPUT,
                 "segments 0 and 1 cross");
  options.split_crossing_segments = 2;
  expect_failure("split_crossing_segments neither 0 nor 1", xy, 6, cross, 2, &options,
                 DELMESH_ERROR_INVALID_ARGUMENT, "split_crossing_segments");
  options.split_crossing_segments = 1;
  expect_failure("split crossing segments, a point still on a segment", xy, 6, through, 1, &options,
                 DELMESH_ERROR_INVALID_INPUT, "point 4 lies on segment 0");
  options.split_crossing_segments = 0;
  expect_failure("point on a segment", xy, 6, through, 1, NULL, DELMESH_ERROR_INVALID_INPUT,
                 "point 4 lies on segment 0");
  expect_failure("zero-length segment", xy, 6, zero, 1, NULL, DELMESH_ERROR_INVALID_INPUT, "zero length");
  expect_failure("index out of range", xy, 6, range, 1, NULL, DELMESH_ERROR_INVALID_INPUT, "out of range");
  double nan_xy[12];
  memcpy(nan_xy, xy, sizeof nan_xy);
  nan_xy[7] = NAN;
  expect_failure("NaN coordinate", nan_xy, 6, through, 1, NULL, DELMESH_ERROR_INVALID_INPUT, "point 3");
  expect_failure("collinear points", xy, 2, NULL, 0, NULL, DELMESH_ERROR_INVALID_INPUT, "points");
  expect_failure("NULL segments", xy, 6, NULL, 1, NULL, DELMESH_ERROR_NULL_ARGUMENT, "segments");
  options.mode = DELMESH_MODE2D_QUALITY;
  options.min_angle_degrees = 35;
  expect_failure("quality mode, angle bound above 34 degrees", xy, 6, NULL, 0, &options,
                 DELMESH_ERROR_INVALID_ARGUMENT, "min_angle_degrees");
  options.min_angle_degrees = 20;
  options.n_holes = 1;
  expect_failure("quality mode, NULL holes", xy, 6, NULL, 0, &options, DELMESH_ERROR_NULL_ARGUMENT, "holes");
  options.n_holes = 0;
  options.min_angle_degrees = 0;
  options.mode = DELMESH_MODE2D_DELAUNAY;
  options.max_area = -1;
  expect_failure("negative max_area", xy, 6, NULL, 0, &options, DELMESH_ERROR_INVALID_ARGUMENT, "max_area");
  options.max_area = 0;
  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = delmesh_triangulate_2d(xy, 6, NULL, 0, &options, &mesh);
  check_case(s == DELMESH_OK && delmesh_mesh_triangle_count(mesh) == 5,
             "Delaunay mode: 6 points, 5 on the hull, give 5 triangles");
  double worst = 0;
  s = delmesh_mesh_triangle_degradation(mesh, NULL, &worst, NULL);
  check_case(s == DELMESH_OK && worst >= 1, "degradation with NULL outputs skipped: worst %g >= 1", worst);
  check_case(delmesh_mesh_triangle_degradation(NULL, NULL, &worst, NULL) == DELMESH_ERROR_NULL_ARGUMENT,
             "degradation of a NULL mesh: DELMESH_ERROR_NULL_ARGUMENT");
  check_case(delmesh_mesh_cover_cell_count(mesh) == 5 && delmesh_mesh_triangle_cover_cells(NULL) == NULL &&
                 delmesh_mesh_cover_cell_count(NULL) == 0,
             "Delaunay cover of 6 points in general position: 5 cells; NULL mesh: 0 cells, NULL array");
  delmesh_mesh_free(mesh);
}

/* ---------------------------------------------------------------- quality mode */

static void make_letter_a(Case *c) {
  snprintf(c->name, sizeof c->name, "letter A with its counter as a hole");
  static const double outer[][2] = {{0.0, 0.0},  {1.4, 0.0},  {1.4, 0.25}, {1.05, 0.3},
                                    {1.5, 1.5},  {3.5, 1.5},  {3.95, 0.3}, {3.6, 0.25},
                                    {3.6, 0.0},  {5.0, 0.0},  {5.0, 0.25}, {4.7, 0.35},
                                    {2.95, 6.0}, {2.05, 6.0}, {0.3, 0.35}, {0.0, 0.25}};
  for (size_t i = 0; i < 16; ++i) add_point(c, outer[i][0], outer[i][1]);
  polyline(c, 0, 16, 1);
  add_point(c, 1.75, 2.1);
  add_point(c, 3.25, 2.1);
  add_point(c, 2.5, 4.5);
  polyline(c, 16, 3, 1);
}

static void make_rhombus_25(Case *c) {
  snprintf(c->name, sizeof c->name, "thin rhombus (17 degree angles)");
  add_point(c, 0, 0);
  add_point(c, 4, 0.6);
  add_point(c, 8, 0);
  add_point(c, 4, -0.6);
  polyline(c, 0, 4, 1);
}

static void make_square_with_hole(Case *c) {
  snprintf(c->name, sizeof c->name, "square with a square hole");
  add_point(c, 0, 0);
  add_point(c, 4, 0);
  add_point(c, 4, 4);
  add_point(c, 0, 4);
  polyline(c, 0, 4, 1);
  add_point(c, 1.5, 1.5);
  add_point(c, 2.5, 1.5);
  add_point(c, 2.5, 2.5);
  add_point(c, 1.5, 2.5);
  polyline(c, 4, 4, 1);
}

/* Whether p lies on the segment [a b] up to rounding. */
static int on_segment(const double p[2], const double a[2], const double b[2]) {
  double len2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
  double t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2;
  double h = fabs((p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])) / len2;
  return t >= -1e-12 && t <= 1 + 1e-12 && h < 1e-9;
}

/* Whether the edge (p, q) joins two points on two input segments that meet at an input point
 * at an angle below 60 degrees. */
static int at_small_input_angle(const double p[2], const double q[2], const Case *c) {
  for (size_t i = 0; i < c->m; ++i)
    for (size_t j = i + 1; j < c->m; ++j) {
      const uint32_t *s = &c->seg[2 * i], *r = &c->seg[2 * j];
      uint32_t z = (s[0] == r[0] || s[0] == r[1]) ? s[0] : (s[1] == r[0] || s[1] == r[1]) ? s[1] : UINT32_MAX;
      if (z == UINT32_MAX) continue;
      uint32_t f1 = s[0] == z ? s[1] : s[0], f2 = r[0] == z ? r[1] : r[0];
      const double *pz = &c->xy[2 * (size_t)z], *p1 = &c->xy[2 * (size_t)f1], *p2 = &c->xy[2 * (size_t)f2];
      double u[2] = {p1[0] - pz[0], p1[1] - pz[1]}, w[2] = {p2[0] - pz[0], p2[1] - pz[1]};
      double cosine = (u[0] * w[0] + u[1] * w[1]) / (hypot(u[0], u[1]) * hypot(w[0], w[1]));
      if (cosine <= 0.5) continue;
#define ON(x, g) (((x)[0] == pz[0] && (x)[1] == pz[1]) || on_segment((x), pz, (g)))
      if ((ON(p, p1) && ON(q, p2)) || (ON(p, p2) && ON(q, p1))) return 1;
#undef ON
    }
  return 0;
}

/* Triangles counter-clockwise, interior edges locally Delaunay; writes the edge table. */
static int check_quality_triangles(const DelmeshMesh *mesh, EdgeUse **table, size_t *table_count,
                                   char *why, size_t why_len) {
  size_t nv = delmesh_mesh_vertex_count(mesh), nt = delmesh_mesh_triangle_count(mesh);
  const double *xyz = delmesh_mesh_vertices(mesh);
  const uint32_t *tri = delmesh_mesh_triangles(mesh);
  double p[3][2];
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      if (tri[3 * t + k] >= nv) return snprintf(why, why_len, "index out of range"), 0;
      vtx(xyz, tri[3 * t + k], p[k]);
    }
    if (ref_orient_2(p[0], p[1], p[2]) != 1)
      return snprintf(why, why_len, "triangle %zu not counter-clockwise", t), 0;
  }
  *table = edge_table(tri, nt, table_count);
  if (!*table) return snprintf(why, why_len, "an edge is in more than two triangles"), 0;
  return locally_delaunay(xyz, *table, *table_count, why, why_len);
}

static size_t quality_ours[2], quality_cgal[2];

static void run_quality_case(const Case *c, const double *holes, size_t n_holes, double bound, int slot) {
  DelmeshOptions2d options;
  memset(&options, 0, sizeof options);
  options.mode = DELMESH_MODE2D_QUALITY;
  options.min_angle_degrees = bound;
  options.holes = holes;
  options.n_holes = n_holes;
  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = delmesh_triangulate_2d(c->xy, c->n, c->seg, c->m, &options, &mesh);
  if (!check_case(s == DELMESH_OK, "%s at %.0f degrees: quality triangulation (%s)", c->name, bound,
                  s == DELMESH_OK ? "ok" : delmesh_last_error_message()))
    return;
  char why[256] = "";
  EdgeUse *table = NULL;
  size_t table_count = 0;
  int valid = check_quality_triangles(mesh, &table, &table_count, why, sizeof why);
  check_case(valid, "%s at %.0f degrees: counter-clockwise, locally Delaunay%s%s", c->name, bound,
             valid ? "" : ": ", why);
  if (valid) {
    int ok = check_admissible(mesh, c->n, table, table_count, why, sizeof why);
    check_case(ok, "%s at %.0f degrees: every sub-edge strongly Delaunay-admissible%s%s", c->name, bound,
               ok ? "" : ": ", why);
  }
  int chained = check_union(mesh, c, why, sizeof why);
  check_case(chained, "%s at %.0f degrees: every segment the union of its sub-edges%s%s", c->name, bound,
             chained ? "" : ": ", why);
  size_t nt = delmesh_mesh_triangle_count(mesh), near = 0, away = 0;
  const double *xyz = delmesh_mesh_vertices(mesh);
  const uint32_t *tri = delmesh_mesh_triangles(mesh);
  double worst = 180.0;
  for (size_t t = 0; t < nt; ++t) {
    double p[3][2], l[3];
    for (int k = 0; k < 3; ++k) vtx(xyz, tri[3 * t + k], p[k]);
    for (int k = 0; k < 3; ++k) {
      const double *a = p[(k + 1) % 3], *b = p[(k + 2) % 3];
      l[k] = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]);
    }
    int k = l[0] <= l[1] && l[0] <= l[2] ? 0 : l[1] <= l[2] ? 1 : 2;
    double x = l[(k + 1) % 3], y = l[(k + 2) % 3];
    double cosine = (x + y - l[k]) / (2.0 * sqrt(x * y));
    double angle = acos(cosine > 1 ? 1 : cosine < -1 ? -1 : cosine) * 180.0 / PI;
    if (angle < worst) worst = angle;
    if (angle >= bound) continue;
    if (at_small_input_angle(p[(k + 1) % 3], p[(k + 2) % 3], c))
      near++;
    else
      away++;
  }
  check_case(away == 0, "%s at %.0f degrees: every angle at least the bound but at small input angles "
             "(%zu below it there, %zu elsewhere)", c->name, bound, near, away);
  RefMesh2d cgal;
  if (ref_cgal_mesh_2d(c->xy, c->n, c->seg, c->m, holes, n_holes, bound, &cgal, NULL) != 0) {
    check_case(0, "%s: CGAL mesher: %s", c->name, ref_last_error());
  } else {
    check_note("%-40s %2.0f deg: triangles delmesh %5zu  CGAL %5zu   smallest angle %6.2f / %6.2f   "
               "below the bound %zu / %zu", c->name, bound, nt, cgal.triangle_count, worst,
               cgal.min_angle_degrees, near + away, cgal.below_bound);
    check_case((double)nt <= 1.15 * (double)cgal.triangle_count,
               "%s at %.0f degrees: %zu triangles, at most CGAL's %zu + 15%%", c->name, bound, nt,
               cgal.triangle_count);
    quality_ours[slot] += nt;
    quality_cgal[slot] += cgal.triangle_count;
  }
  free(table);
  delmesh_mesh_free(mesh);
}

static void quality_cases(void) {
  static Case c;
  struct {
    void (*make)(Case *);
    double hole[2];
    size_t n_holes;
  } cases[] = {{make_letter_a, {2.5, 3.0}, 1},   {make_rhombus_25, {0, 0}, 0},
               {make_square_with_hole, {2, 2}, 1}, {make_grid, {0, 0}, 0},
               {make_thin_domain, {0, 0}, 0},      {make_arcs, {0, 0}, 0}};
  double bounds[] = {25.0, 30.0};
  for (int b = 0; b < 2; ++b) {
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
      memset(&c, 0, sizeof c);
      cases[i].make(&c);
      run_quality_case(&c, cases[i].hole, cases[i].n_holes, bounds[b], b);
    }
    for (int k = 20; k <= 80; k *= 2) {
      memset(&c, 0, sizeof c);
      make_star_polygon(&c, k, 0x2d2d + (uint64_t)k);
      run_quality_case(&c, NULL, 0, bounds[b], b);
    }
    check_note("quality at %.0f degrees, all cases: triangles delmesh %zu, CGAL %zu", bounds[b],
               quality_ours[b], quality_cgal[b]);
  }
}

int main(int argc, char **argv) {
  (void)argc;
  (void)argv;
  static Case c;
  error_paths();
  struct {
    int k;
    double spread;
  } fans[] = {{2, 20}, {3, 60}, {6, 80}, {8, 360}, {12, 360}, {24, 360}, {5, 10}};
  for (size_t i = 0; i < sizeof fans / sizeof fans[0]; ++i) {
    memset(&c, 0, sizeof c);
    make_fan(&c, fans[i].k, fans[i].spread);
    run_case(&c);
  }
  void (*makers[])(Case *) = {make_zigzag, make_spiral, make_closed_nodes, make_arcs,
                              make_grid, make_thin_domain, make_thin_rhombus};
  for (size_t i = 0; i < sizeof makers / sizeof makers[0]; ++i) {
    memset(&c, 0, sizeof c);
    makers[i](&c);
    run_case(&c);
  }
  double degrees[] = {1, 2, 5, 10};
  for (size_t i = 0; i < 4; ++i) {
    memset(&c, 0, sizeof c);
    make_tiny_angle(&c, degrees[i]);
    run_case(&c);
  }
  for (int k = 20; k <= 160; k *= 2) {
    memset(&c, 0, sizeof c);
    make_star_polygon(&c, k, 0x2d2d + (uint64_t)k);
    run_case(&c);
  }
  check_note("inserted points over all cases: delmesh %zu, CGAL %zu", total_ours, total_cgal);
  check_case(total_ours <= total_cgal, "delmesh inserts no more points than CGAL over all cases");
  crossing_cases();
  quality_cases();
  return check_finish();
}
