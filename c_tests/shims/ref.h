/* Reference implementations behind a C interface: CGAL 5.5 (ref_cgal.cpp) and TetGen 1.5
 * (ref_tetgen.cpp). Only the C test programs, the demo and the benchmark link these; the delmesh
 * library never does.
 *
 * Conventions:
 * - points are `double` xyz interleaved, `n` of them; results name points by their 0-based
 *   input index;
 * - every producing call returns 0 on success and writes malloc'd arrays the caller frees with
 *   free(); on failure it returns -1, writes nothing, and ref_last_error() says why (a C++
 *   exception never crosses this interface);
 * - tetrahedra are 4 indices each, in the reference's own vertex order (CGAL: positively
 *   oriented in delmesh's convention; TetGen: its own). Compare them as sets of sorted
 *   quadruples (metrics.h).
 * - `timing` (may be NULL) receives the wall time from entry until the index arrays are filled,
 *   excluding the destruction of the reference's data structure: the benchmark's figure. */
#ifndef DELMESH_C_TESTS_REF_H
#define DELMESH_C_TESTS_REF_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct RefTiming {
  double seconds;
} RefTiming;

/* Message of the last failed call of this interface (never NULL; "" if none). */
const char *ref_last_error(void);

/* Exact sign of dot(b-a, cross(c-a, d-a)): +1, 0 or -1 (CGAL::orientation, Epick: exact
 * predicates). Positive for a positively oriented tetrahedron in delmesh's convention. */
int ref_orient3d_exact(const double a[3], const double b[3], const double c[3], const double d[3]);

/* CGAL Delaunay_triangulation_3<Epick> built by bulk insertion of (point, index) pairs (spatial
 * sort inside). All finite cells. Duplicate points: one of the copies (CGAL's choice) is the
 * vertex, the others are referenced by nothing. */
int ref_cgal_delaunay(const double *xyz, size_t n, uint32_t **tets, size_t *tet_count,
                      RefTiming *timing);

/* CGAL Regular_triangulation_3<Epick> of the weighted points (power distance |p-x|^2 - w), bulk
 * insertion of (weighted point, index) pairs. All finite cells; hidden[i] = 1 when input i is
 * not a vertex of the triangulation (redundant, or a copy of a point with a larger weight), else 0. */
int ref_cgal_regular(const double *xyz, const double *weights, size_t n, uint32_t **tets,
                     size_t *tet_count, unsigned char **hidden, RefTiming *timing);

/* CGAL convex_hull_3 of the points (must span 3D): outward-oriented triangles (counter-clockwise
 * seen from outside) as input indices (the first occurrence among identical points). */
int ref_cgal_convex_hull(const double *xyz, size_t n, uint32_t **triangles, size_t *triangle_count);

/* TetGen tetrahedralize("QzJ") of the point set: Delaunay tetrahedralization, quiet, 0-based,
 * and `J` so that TetGen keeps every input point (duplicates included) and the output numbering
 * stays the input numbering. Fails if TetGen renumbered the points anyway. */
int ref_tetgen_delaunay(const double *xyz, size_t n, uint32_t **tets, size_t *tet_count,
                        RefTiming *timing);

#ifdef __cplusplus
}
#endif

#endif
