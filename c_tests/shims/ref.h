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

/* ---- Surfaces (piecewise linear complexes) ------------------------------------------------- */

/* TetGen's tetrahedralization of a closed surface (ref_tetgen_surface, ref_tetgen_polygons). */
typedef struct RefSurfaceMesh {
  double *xyz;          /* 3 * vertex_count: the n input points first (same order, bit for bit),
                           then the Steiner points the tetrahedra use, in TetGen's order */
  size_t vertex_count;
  size_t steiner_count; /* vertex_count - n */
  size_t boundary_steiner; /* of them, those on TetGen's boundary faces: it split the surface */
  uint32_t *tets;       /* 4 * tet_count, TetGen's vertex order (positively oriented in
                           delmesh's convention; the tests check it) */
  int32_t *labels;      /* tet_count: TetGen's region attribute (switch A), rounded */
  size_t tet_count;
} RefSurfaceMesh;

/* Releases the arrays of `m` (NULL allowed) and zeroes it. */
void ref_surface_mesh_free(RefSurfaceMesh *m);

/* TetGen tetrahedralize() of the surface made of the `m` triangles `tris` (3 input indices
 * each) over the `n` points `xyz`: one facet of one polygon per triangle. `regions` holds
 * `n_regions` records (x, y, z, label, max volume) and `holes` `n_holes` points (x, y, z), as
 * in TetGen's .poly files (NULL with a count of 0 when none). `switches` are the caller's, e.g.
 * "pYQ" or "pq1.414YQ"; the shim puts "zJA" in front (0-based output; keep every input point
 * so that the numbering stays the input's; region attributes, which TetGen also gives when no
 * seed is given: one number per region it finds), and "a" when a region has a max volume > 0.
 * Output points beyond the input's that no tetrahedron uses (Steiner points TetGen inserted and
 * then suppressed) are dropped. TetGen 1.5.0 leaves attribute 0 on tetrahedra it creates when
 * suppressing boundary Steiner points (-Y); the shim gives them their region's attribute
 * (ref_tetgen.cpp). Fails if TetGen throws (it reports errors by throwing an int), or if its
 * output does not start with the n input points unchanged. TetGen 1.5.0 also stops on failed
 * assert()s (abort) on some inputs with -Y: callers that must survive that run this in a child
 * process. `timing` as for the Delaunay calls, the shim's renumbering included. */
int ref_tetgen_surface(const double *xyz, size_t n, const uint32_t *tris, size_t m,
                       const double *regions, size_t n_regions, const double *holes,
                       size_t n_holes, const char *switches, RefSurfaceMesh *out,
                       RefTiming *timing);

/* The same with polygonal facets: facet f is the polygon corners[offsets[f] .. offsets[f+1])
 * (offsets has m + 1 entries), one polygon per facet, as in TetGen's .smesh files. */
int ref_tetgen_polygons(const double *xyz, size_t n, const uint32_t *corners,
                        const size_t *offsets, size_t m, const double *regions, size_t n_regions,
                        const double *holes, size_t n_holes, const char *switches,
                        RefSurfaceMesh *out, RefTiming *timing);

/* TetGen's self-intersection check ("pdzQ") of the surface of `m` triangles: *culprits (malloc'd,
 * sorted, *count of them) receives the indices of the triangles TetGen reports as intersecting
 * another one other than along their shared vertices and edge; *count = 0 when none. */
int ref_tetgen_intersections(const double *xyz, size_t n, const uint32_t *tris, size_t m,
                             uint32_t **culprits, size_t *count);

#ifdef __cplusplus
}
#endif

#endif
