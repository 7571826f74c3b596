/* Checks of a tetrahedralization of a closed surface (delmesh_tetrahedralize_surface, TetGen -p)
 * against its input, with exact predicates where a decision is made (ref_orient3d_exact):
 *
 * - validity (metrics_validity): indices, exact positive orientation, every face in one
 *   tetrahedron or in two from opposite sides, every surface vertex used;
 * - boundary conformity: every surface triangle is a face of the tetrahedra, and the faces
 *   between different labels (label 0 beyond a face of one tetrahedron) are exactly the surface
 *   triangles (as sets of vertex triples);
 * - reported facets (optional): the same array as the surface triangles, and per facet the
 *   labels (from, to) of the tetrahedra on each side, the right-hand normal pointing from
 *   `from` to `to`;
 * - volume per label: the tetrahedra's against the volume the surface triangles enclose
 *   (divergence theorem: the cone of each triangle from a fixed point, counted + for the label
 *   its normal leaves and - for the one it enters, sides read from the tetrahedra), in long
 *   double with compensated sums (surface_check.c states the rounding bound);
 * - regions: the number of labels, each region seed inside a tetrahedron of its label, no
 *   tetrahedron over a hole seed, the seeds' volume bounds;
 * - Steiner points (vertices >= n): none on a surface triangle (exactly: coplanar with it and
 *   inside it, closed), found through a bucket grid of the triangles' bounding boxes;
 * - quality (when a radius-edge bound is given): the tetrahedra above it (1e-9 relative
 *   allowance for the double-precision figure), how many vertices on the surface each has, and
 *   for those with fewer than 3, whether the surface forces them: refinement that keeps every
 *   surface triangle whole must decline their circumcenter, which lies
 *   - in the diametral ball of a surface triangle or edge (it would encroach it),
 *   - within the protecting ball of a surface vertex, radius its shortest surface edge (an
 *     upper bound of the local feature size TetGen -Y and delmesh use: the distance to the
 *     nearest vertex, edge or triangle of the vertex's link), or
 *   - beyond the surface: in no tetrahedron of the same label (exact location);
 *   or whose circumsphere holds a vertex nearer its center than the tetrahedron's shortest edge
 *   (refinement declines a point that would make an edge shorter than the one it fixes; in a
 *   Delaunay mesh the circumsphere is empty, so this happens only where the surface keeps the
 *   mesh from being Delaunay; counted apart); distances with the same 1e-9 relative allowance.
 *
 * "Surface triangles" are the input triangles, or for a polygonal input the triangles that
 * cover its polygons (surface_check_polygons checks that cover). */
#ifndef DELMESH_C_TESTS_SURFACE_CHECK_H
#define DELMESH_C_TESTS_SURFACE_CHECK_H

#include "quality.h"

#include <stddef.h>
#include <stdint.h>

typedef struct SurfaceInput {
  const double *xyz; /* the n input vertices */
  size_t n;
  const uint32_t *tris; /* the m surface triangles */
  size_t m;
  const double *regions; /* n_regions records x, y, z, label, max volume */
  size_t n_regions;
  const double *holes; /* n_holes points */
  size_t n_holes;
  int expected_regions; /* labels in a correct result; 0: not checked */
} SurfaceInput;

typedef struct SurfaceResult {
  const double *xyz; /* vertex_count >= n: the input vertices first */
  size_t vertex_count;
  const uint32_t *tets;
  const int32_t *labels;
  size_t tet_count;
  const uint32_t *facets; /* reported facets (NULL: not checked) */
  const int32_t *facet_labels;
  size_t facet_count;
} SurfaceResult;

typedef struct SurfaceReport {
  int valid;
  char validity[256];
  size_t steiner;               /* vertices >= n */
  size_t missing;               /* surface triangles that are not faces */
  size_t same_label;            /* surface triangles with the same label on both sides */
  size_t extra;                 /* label-change faces that are not surface triangles */
  int facets_checked;
  size_t facets_misplaced;      /* facet k is not surface triangle k, vertex for vertex */
  size_t facets_mislabeled;     /* (from, to) other than the tetrahedra's */
  int regions;                  /* distinct labels */
  size_t seeds_wrong;           /* region seeds not inside a tetrahedron of their label */
  size_t holes_covered;         /* hole seeds inside a tetrahedron */
  size_t above_max_volume;      /* tetrahedra above their region seed's volume bound */
  double volume_error;          /* max over labels of |tets - surface| / |surface| */
  double volume_error_bound;    /* a priori bound of that figure's rounding (relative) */
  double volume;                /* of all tetrahedra */
  size_t surface_steiner;       /* Steiner points on a surface triangle */
  long first_surface_steiner;   /* one of them, -1 if none */
  double max_radius_edge;
  size_t above_radius_edge;     /* tetrahedra above the bound */
  size_t above_with_3_surface;  /* of which with >= 3 vertices on the surface */
  size_t above_with_4_surface;  /* of which with 4 */
  size_t above_forced;          /* of those with < 3, the ones the surface forces (see above) */
  size_t above_near_vertex;     /* of the others, those with a vertex nearer their circumcenter
                                 * than their shortest edge (see above) */
  int shapes_measured;          /* the mesh is valid: `shapes` holds its figures */
  QualitySummary shapes;        /* METRICS.md "Quality" of every tetrahedron, printed */
} SurfaceReport;

/* Every figure of `r` against `in`; `radius_edge_bound` 0 skips the quality figures. Returns 0
 * when out of memory. */
int surface_check(const SurfaceInput *in, const SurfaceResult *r, double radius_edge_bound,
                  SurfaceReport *out);

/* The relative tolerance of the volume check. */
#define SURFACE_VOLUME_TOLERANCE 1e-12
/* The relative allowance of the double-precision radius-edge figure. */
#define SURFACE_QUALITY_ROUNDING 1e-9

/* Checks that pass, as the tests assert them: valid, conforming, facets (when checked),
 * volume, regions and seeds, no Steiner point on the surface; `quality` adds "every tetrahedron
 * above the radius-edge bound has >= 3 surface vertices or is forced by the surface", `volume_bounds` "no tetrahedron above
 * its region seed's max volume". */
int surface_report_ok(const SurfaceReport *r, int expected_regions, int quality, int volume_bounds);

/* One line: the figures, or the failed checks first. */
void surface_report_describe(const SurfaceReport *r, int expected_regions, int quality, char *buffer,
                             size_t size);

/* ---- Polygonal inputs ------------------------------------------------------------------------ */

typedef struct PolygonCover {
  size_t triangles;
  size_t outside;        /* triangles not inside one polygon (vertices among its corners, centroid inside) */
  size_t polygons_off;   /* polygons whose triangles' areas differ from its area by > 1e-12 relative */
  double max_area_error; /* relative */
} PolygonCover;

/* Whether the `count` triangles cover exactly the polygons (corners / offsets as in
 * surface_io.h): each triangle lies in one polygon and per polygon the triangle areas sum to
 * its area within 1e-12 relative (long double). Returns 1 when so. */
int surface_check_polygons(const double *xyz, const uint32_t *corners, const size_t *offsets,
                           size_t polygon_count, const uint32_t *tris, size_t count, PolygonCover *out);

/* The volume a closed 2-manifold surface of planar polygons encloses: |sum of cones|, the
 * polygons oriented consistently first (files need not do it). NaN when the polygons do not form
 * an orientable closed 2-manifold (or out of memory). */
double surface_polygons_volume(const double *xyz, const uint32_t *corners, const size_t *offsets,
                               size_t polygon_count);

/* How many polygons are not planar (exactly: a corner off the plane of three others). */
size_t surface_polygons_nonplanar(const double *xyz, const uint32_t *corners, const size_t *offsets,
                                  size_t polygon_count);

/* The label-change faces of the tetrahedra (as in boundary.h), as a triangle array (malloc'd). */
uint32_t *surface_label_change_faces(const uint32_t *tets, const int32_t *labels, size_t tet_count,
                                     size_t *count);

#endif
