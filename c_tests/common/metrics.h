/* The figures of METRICS.md that the C tests, the demo and the benchmark report, each defined
 * here once. Exact decisions (orientation) go through ref_orient3d_exact (shims/ref.h).
 *
 * Tetrahedra are 4 vertex indices each. A tetrahedron (a,b,c,d) is positively oriented when
 * orient3d(a,b,c,d) = dot(b-a, cross(c-a, d-a)) > 0 (API.md); its outward facets are then
 * (b,c,d), (a,d,c), (a,b,d), (a,c,b). */
#ifndef DELMESH_C_TESTS_METRICS_H
#define DELMESH_C_TESTS_METRICS_H

#include <stddef.h>
#include <stdint.h>

/* ---- Validity (METRICS.md "Validity") ------------------------------------------------------ */

/* What a caller expects of input point i (the `expect` array of metrics_validity). */
enum {
  VERTEX_MUST_BE_USED = 0,   /* a vertex of the triangulation */
  VERTEX_MUST_BE_UNUSED = 1, /* e.g. a duplicate merged onto an earlier copy */
  VERTEX_MAY_BE_UNUSED = 2   /* e.g. a weighted point that may be hidden */
};

typedef struct Validity {
  size_t tetrahedra;
  size_t index_out_of_range;  /* tetrahedra naming an index >= n */
  size_t repeated_vertex;     /* tetrahedra naming one vertex twice */
  size_t not_positive;        /* exact orient3d <= 0 */
  size_t interior_facets;     /* shared by exactly two tetrahedra, on opposite sides: fine */
  size_t boundary_facets;     /* in exactly one tetrahedron */
  size_t facets_same_side;    /* shared by two tetrahedra lying on the same side (overlap) */
  size_t facets_overshared;   /* in three or more tetrahedra */
  size_t boundary_off_hull;   /* a boundary facet with a hull vertex strictly outside it */
  size_t unused_vertices;     /* expected used, referenced by no tetrahedron */
  size_t used_but_unexpected; /* expected unused, referenced */
  size_t coincident_used;     /* used vertices with the coordinates of another used vertex */
  long first_bad_tetrahedron; /* the first tetrahedron found wrong, -1 if none */
} Validity;

/* Checks every tetrahedron (exact orientation, indices), conformity (facets shared by two
 * tetrahedra from opposite sides, or by one on the boundary), that every boundary facet lies on
 * the convex hull given by `hull_vertices` (skipped when hull_count is 0), and the use of every
 * input point against `expect` (NULL: every point must be used). Returns 1 when all holds. */
int metrics_validity(const double *xyz, size_t n, const uint32_t *tets, size_t tet_count,
                     const unsigned char *expect, const uint32_t *hull_vertices, size_t hull_count,
                     Validity *result);

/* One line naming every nonzero defect count (or "valid"). */
void metrics_validity_describe(const Validity *v, char *buffer, size_t size);

/* The distinct vertices of `count` triangles (sorted, malloc'd, *vertex_count of them). */
uint32_t *metrics_triangle_vertices(const uint32_t *triangles, size_t count, size_t *vertex_count);

/* first[i] = the smallest j with the same coordinates as point i (i itself when unique);
 * malloc'd, n entries. The reference for "duplicates are merged onto their first occurrence". */
uint32_t *metrics_first_occurrence(const double *xyz, size_t n);

/* ---- Volume (METRICS.md "Volume") ------------------------------------------------------------ */

/* Sum of the signed tetrahedron volumes (compensated summation). */
double metrics_tetrahedra_volume(const double *xyz, const uint32_t *tets, size_t count);

/* Volume enclosed by a closed triangle surface oriented outward (signed-volume sum of the cones
 * from its first vertex). */
double metrics_polyhedron_volume(const double *xyz, const uint32_t *triangles, size_t count);

/* |v - reference| / |reference|. */
double metrics_relative_error(double v, double reference);

/* ---- Identity of two triangulations -------------------------------------------------------- */

/* The tetrahedra as a set: each quadruple sorted ascending, the quadruples sorted
 * lexicographically (malloc'd, 4 * count entries). `rename` (NULL: identity) maps every index
 * first, e.g. onto the first occurrence of a duplicated point. */
uint32_t *metrics_tetrahedron_set(const uint32_t *tets, size_t count, const uint32_t *rename);

typedef struct SetComparison {
  size_t common, only_first, only_second;
} SetComparison;

/* Compares two sets from metrics_tetrahedron_set (multiplicities count). */
SetComparison metrics_compare_tetrahedron_sets(const uint32_t *a, size_t a_count,
                                               const uint32_t *b, size_t b_count);

#endif
