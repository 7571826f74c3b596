/* CGAL 5.5 planar triangulations behind a C interface (ref_cgal2d.cpp), in the conventions of
 * ref.h: 0 on success, -1 and ref_last_error() on failure, malloc'd results, no C++ exception
 * crosses. */
#ifndef DELMESH_C_TESTS_REF_CGAL2D_H
#define DELMESH_C_TESTS_REF_CGAL2D_H

#include "ref.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* CGAL::Constrained_Delaunay_triangulation_2<Epick> of the n points xy (x y interleaved) and
 * the segments (2 point indices each), then CGAL::make_conforming_Delaunay_2: the conforming
 * Delaunay triangulation CGAL builds by splitting constrained edges. Writes the number of its
 * vertices (identical input points count once), of its constrained sub-edges, and whether
 * it passes CGAL's own validity check and is a Delaunay triangulation (every constrained edge
 * locally Delaunay). */
typedef struct RefConforming2d {
  size_t vertex_count;
  size_t constrained_edge_count;
  int valid;
  size_t intersection_count; /* vertices the constraints added (crossing variant; else 0) */
  /* Pebay's degradation alpha h / r (h the longest edge, r the inradius, alpha = sqrt(3) / 6:
   * 1 for the equilateral triangle) over the finite triangles: the worst and the mean. */
  double worst_degradation, mean_degradation;
} RefConforming2d;
int ref_cgal_conforming_2d(const double *xy, size_t n, const uint32_t *segments,
                           size_t n_segments, RefConforming2d *out, RefTiming *timing);

/* ref_cgal_conforming_2d with constraints that may cross: the triangulation takes
 * CGAL::Exact_predicates_tag, so inserting a constraint that crosses another inserts their
 * intersection point (computed in doubles, Epick); intersection_count is the number of
 * vertices the constraints added that way, before make_conforming_Delaunay_2. */
int ref_cgal_conforming_2d_crossing(const double *xy, size_t n, const uint32_t *segments,
                                    size_t n_segments, RefConforming2d *out);

/* CGAL::refine_Delaunay_mesh_2 with Delaunay_mesh_size_criteria_2 (shape bound
 * sin^2(min_angle_degrees), no size bound) on the constrained Delaunay triangulation of the
 * points and segments, the components holding a hole seed left out (seeds not marked as
 * inside), as CGAL's mesher meshes the bounded components by default. Writes the number of
 * vertices, of triangles in the domain, their smallest angle (degrees) and how many have an
 * angle below the bound. */
typedef struct RefMesh2d {
  size_t vertex_count;
  size_t triangle_count;
  double min_angle_degrees;
  size_t below_bound;
} RefMesh2d;
int ref_cgal_mesh_2d(const double *xy, size_t n, const uint32_t *segments, size_t n_segments,
                     const double *holes, size_t n_holes, double min_angle_degrees,
                     RefMesh2d *out, RefTiming *timing);

/* CGAL::Delaunay_triangulation_2<Epick> of the n points xy, built from (point, index) pairs at
 * once (CGAL sorts them spatially), its finite faces exported as counter-clockwise index
 * triples into *triangles (malloc'd, 3 * *triangle_count). The timing covers construction and
 * export, not destruction. */
int ref_cgal_delaunay_2d(const double *xy, size_t n, uint32_t **triangles,
                         size_t *triangle_count, RefTiming *timing);

/* Exact planar predicates (CGAL, Epick):
 * - ref_small_disk_side(a, b, q): +1 when q is strictly inside the disk of diameter [a b],
 *   0 on its circle, -1 outside (CGAL::side_of_bounded_circle);
 * - ref_incircle_2(a, b, c, d): for counter-clockwise a, b, c, +1 when d is strictly inside
 *   their circumcircle, 0 on it, -1 outside (CGAL::side_of_oriented_circle);
 * - ref_orient_2(a, b, c): +1 counter-clockwise, 0 collinear, -1 clockwise. */
int ref_small_disk_side(const double a[2], const double b[2], const double q[2]);
int ref_incircle_2(const double a[2], const double b[2], const double c[2], const double d[2]);
int ref_orient_2(const double a[2], const double b[2], const double c[2]);

#ifdef __cplusplus
}
#endif

#endif
