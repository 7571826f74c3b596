/* Checks shared by the triangulation tests: each prints one case line through check.h. */
#ifndef DELMESH_C_TESTS_COMPARE_H
#define DELMESH_C_TESTS_COMPARE_H

#include <delmesh.h>

#include <stddef.h>
#include <stdint.h>

/* Index correspondence (API.md): vertex_count == n, vertex i has the coordinates of input
 * point i (bit for bit), and every tetrahedron has label 1. */
int compare_mesh_arrays(const char *name, const DelmeshMesh *mesh, const double *xyz, size_t n);

/* The tetrahedron sets of `ours` and `theirs` (each renamed through its own map, NULL =
 * identity) are equal. With `assert_equal` 0 the comparison is only printed (a note) and 1 is
 * returned. */
int compare_tetrahedron_sets(const char *name, const char *reference,
                             const uint32_t *ours, size_t our_count, const uint32_t *our_rename,
                             const uint32_t *theirs, size_t their_count,
                             const uint32_t *their_rename, int assert_equal);

/* Total volume against a reference: relative error <= tolerance. */
int compare_volume(const char *name, const char *reference, double volume, double reference_volume,
                   double tolerance);

/* The convex hull of the points (CGAL convex_hull_3): its distinct vertices (malloc'd) and its
 * volume. Returns 0 on failure (after printing a failed case). */
int compare_convex_hull(const char *name, const double *xyz, size_t n, uint32_t **hull_vertices,
                        size_t *hull_count, double *hull_volume);

#endif
