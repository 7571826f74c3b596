/* Figures of METRICS.md for meshes of oracle domains (labeled tetrahedra): boundary conformity,
 * volume per subdomain, Hausdorff distance to the true surface, radius-edge ratio and facet
 * angles. Validity itself is metrics_validity (metrics.h).
 *
 * The boundary of a labeled mesh is the set of faces between tetrahedra of different labels
 * (label 0 beyond a face that has a single tetrahedron). Each such face is listed once, as a
 * BoundaryFace oriented so that its normal (right-hand rule) points from label `from` to label
 * `to`, with from > to (so a face on the outside has from = its subdomain, to = 0, normal
 * outward). */
#ifndef DELMESH_C_TESTS_BOUNDARY_H
#define DELMESH_C_TESTS_BOUNDARY_H

#include <stddef.h>
#include <stdint.h>

typedef struct BoundaryFace {
  uint32_t v[3];
  int32_t from, to;
} BoundaryFace;

/* The label-change faces of the tetrahedra (positively oriented, valid mesh), malloc'd. */
BoundaryFace *boundary_faces(const uint32_t *tets, const int32_t *labels, size_t tet_count,
                             size_t *face_count);

/* The same faces built from a mesher's reported facets: (from, to) pairs with the normal from
 * `from` to `to`; those with from < to are flipped. Malloc'd, `count` entries. */
BoundaryFace *boundary_faces_from_facets(const uint32_t *facets, const int32_t *facet_labels,
                                         size_t count);

/* Two face lists compared as sets (by vertex triple). */
typedef struct FaceComparison {
  size_t common;       /* same vertices, same orientation, same labels */
  size_t misoriented;  /* same vertices and labels, opposite orientation */
  size_t wrong_labels; /* same vertices, other labels */
  size_t missing;      /* in `expected` only */
  size_t extra;        /* in `reported` only (or reported twice) */
} FaceComparison;

FaceComparison boundary_compare_faces(const BoundaryFace *expected, size_t expected_count,
                                      const BoundaryFace *reported, size_t reported_count);

/* The surface of one subdomain: the faces with it on one side, oriented outward from it. */
#define BOUNDARY_MAX_COMPONENTS 8
typedef struct SubdomainSurface {
  int32_t label;
  size_t faces;
  size_t open_edges;        /* in one face */
  size_t nonmanifold_edges; /* in three or more faces */
  size_t misoriented_edges; /* in two faces that run it the same direction */
  size_t components;        /* connected through edges */
  int euler[BOUNDARY_MAX_COMPONENTS]; /* V-E+F of the first components, ascending */
} SubdomainSurface;

/* Surface of subdomain `label`. Returns 1 when closed, consistently oriented and edge-manifold. */
int boundary_subdomain_surface(const BoundaryFace *faces, size_t count, int32_t label,
                               SubdomainSurface *out);

/* Vertices that must lie on the surface: those of dimension 2 (dimensions may be NULL) and
 * those of the boundary faces. Counts those farther than `tolerance` from it. */
typedef struct SurfaceVertices {
  size_t checked, far;
  size_t volume_on_boundary; /* boundary-face vertices reported of dimension 3 */
  double max_distance;
} SurfaceVertices;

SurfaceVertices boundary_surface_vertices(const double *xyz, size_t n, const int8_t *dimensions,
                                          const BoundaryFace *faces, size_t count,
                                          double (*distance)(const double p[3]), double tolerance);

/* Sum of the tetrahedron volumes of each label 0..max_label (volumes[max_label + 1]). */
void boundary_volumes(const double *xyz, const uint32_t *tets, const int32_t *labels,
                      size_t tet_count, int32_t max_label, double *volumes);

/* Two-sided Hausdorff distance between the boundary faces and the true surface, both
 * directions' max and RMS (absolute; divide by the box diagonal to report):
 * - mesh -> surface: every face sampled at its vertices, centroid and edge midpoints, and the
 *   `distance` of each sample to the surface;
 * - surface -> mesh: the given surface samples (shape_surface_samples) and their distance to
 *   the nearest boundary triangle (bucket grid). */
typedef struct Hausdorff {
  double mesh_to_surface_max, mesh_to_surface_rms;
  double surface_to_mesh_max, surface_to_mesh_rms;
  double max; /* of both directions */
  size_t mesh_samples, surface_samples;
} Hausdorff;

int boundary_hausdorff(const double *xyz, const BoundaryFace *faces, size_t count,
                       double (*distance)(const double p[3]), const double *samples,
                       size_t sample_count, Hausdorff *out);

#endif
