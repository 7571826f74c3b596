#include "compare.h"

#include "check.h"
#include "metrics.h"
#include "ref.h"

#include <stdlib.h>
#include <string.h>

int compare_mesh_arrays(const char *name, const DelmeshMesh *mesh, const double *xyz, size_t n) {
  size_t vc = delmesh_mesh_vertex_count(mesh);
  const double *v = delmesh_mesh_vertices(mesh);
  size_t tc = delmesh_mesh_tetrahedron_count(mesh);
  const int32_t *labels = delmesh_mesh_tetrahedron_labels(mesh);
  size_t moved = 0, bad_labels = 0;
  if (vc == n && v)
    for (size_t i = 0; i < n; i++)
      if (memcmp(v + 3 * i, xyz + 3 * i, 3 * sizeof(double)) != 0) moved++;
  if (labels)
    for (size_t t = 0; t < tc; t++)
      if (labels[t] != 1) bad_labels++;
  return check_case(vc == n && v && moved == 0 && tc > 0 && labels && bad_labels == 0,
                    "%s: %zu vertices for %zu points, %zu moved, %zu tetrahedra, %zu labels != 1",
                    name, vc, n, moved, tc, bad_labels);
}

int compare_tetrahedron_sets(const char *name, const char *reference,
                             const uint32_t *ours, size_t our_count, const uint32_t *our_rename,
                             const uint32_t *theirs, size_t their_count,
                             const uint32_t *their_rename, int assert_equal) {
  uint32_t *a = metrics_tetrahedron_set(ours, our_count, our_rename);
  uint32_t *b = metrics_tetrahedron_set(theirs, their_count, their_rename);
  if (!a || !b) {
    free(a);
    free(b);
    return check_case(0, "%s: out of memory comparing with %s", name, reference);
  }
  SetComparison c = metrics_compare_tetrahedron_sets(a, our_count, b, their_count);
  free(a);
  free(b);
  int same = c.only_first == 0 && c.only_second == 0;
  if (!assert_equal) {
    check_note("%s: tetrahedron set %s %s's (ours %zu, %s %zu, common %zu, only ours %zu, only %s %zu) [reported, not asserted]",
               name, same ? "EQUALS" : "differs from", reference, our_count, reference,
               their_count, c.common, c.only_first, reference, c.only_second);
    return 1;
  }
  return check_case(same, "%s: tetrahedron set equals %s's (ours %zu, %s %zu, common %zu, only ours %zu, only %s %zu)",
                    name, reference, our_count, reference, their_count, c.common, c.only_first,
                    reference, c.only_second);
}

int compare_volume(const char *name, const char *reference, double volume, double reference_volume,
                   double tolerance) {
  double e = metrics_relative_error(volume, reference_volume);
  return check_case(e <= tolerance, "%s: volume %.17g vs %s %.17g, relative error %.3g (<= %.0e)",
                    name, volume, reference, reference_volume, e, tolerance);
}

int compare_convex_hull(const char *name, const double *xyz, size_t n, uint32_t **hull_vertices,
                        size_t *hull_count, double *hull_volume) {
  uint32_t *triangles = NULL;
  size_t count = 0;
  if (ref_cgal_convex_hull(xyz, n, &triangles, &count) != 0)
    return check_case(0, "%s: CGAL convex_hull_3 failed: %s", name, ref_last_error());
  *hull_volume = metrics_polyhedron_volume(xyz, triangles, count);
  *hull_vertices = metrics_triangle_vertices(triangles, count, hull_count);
  free(triangles);
  if (!*hull_vertices) return check_case(0, "%s: out of memory", name);
  return 1;
}
