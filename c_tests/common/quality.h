/* Element quality, as METRICS.md "Quality" defines it, computed in double precision.
 *
 * Per tetrahedron: the six dihedral angles (between the two facets at each edge, inside the
 * tetrahedron), the radius-edge ratio (circumradius / shortest edge) and the radius ratio
 * 3·r_in / r_circ (1 for the regular tetrahedron, 0 for a flat one). Per triangle: its smallest
 * angle. Angles are in degrees. Either orientation of a tetrahedron gives the same figures. */
#ifndef DELMESH_C_TESTS_QUALITY_H
#define DELMESH_C_TESTS_QUALITY_H

#include <stddef.h>
#include <stdint.h>

typedef struct TetQuality {
  double min_dihedral, max_dihedral; /* degrees */
  double circumradius;
  double shortest_edge;
  double radius_edge;  /* circumradius / shortest edge; +inf when flat */
  double radius_ratio; /* 3·r_in / r_circ in [0, 1]; 0 when flat */
} TetQuality;

/* The figures of one tetrahedron. A flat one (zero volume) has dihedral angles 0 and 180. */
TetQuality quality_tetrahedron(const double a[3], const double b[3], const double c[3],
                               const double d[3]);

#define QUALITY_HISTOGRAM_BINS 10
#define QUALITY_DIHEDRAL_THRESHOLDS 3

/* The dihedral thresholds of QualitySummary.dihedral_below: 5, 10 and 15 degrees. */
extern const double quality_dihedral_thresholds[QUALITY_DIHEDRAL_THRESHOLDS];

typedef struct QualitySummary {
  size_t tetrahedra;
  double min_dihedral, max_dihedral;
  double max_radius_edge;
  double min_radius_ratio, mean_radius_ratio;
  double max_circumradius;
  /* Tetrahedra with a dihedral angle below quality_dihedral_thresholds[k]. */
  size_t dihedral_below[QUALITY_DIHEDRAL_THRESHOLDS];
  /* Radius ratio histogram: bin k counts [k/10, (k+1)/10), the last bin includes 1. */
  size_t radius_ratio_histogram[QUALITY_HISTOGRAM_BINS];
  /* The tetrahedron of smallest dihedral angle, of largest radius-edge ratio (-1 if none). */
  long worst_dihedral, worst_radius_edge;
} QualitySummary;

/* The summary over `count` tetrahedra (4 indices each into xyz). With count 0 the extremes are
 * NaN and the counts 0. */
QualitySummary quality_tetrahedra(const double *xyz, const uint32_t *tets, size_t count);

/* Smallest angle of the triangle (a, b, c), degrees; 0 when two vertices coincide. */
double quality_triangle_min_angle(const double a[3], const double b[3], const double c[3]);

/* Smallest angle over `count` triangles (3 indices each into xyz); NaN when count is 0. */
double quality_triangles_min_angle(const double *xyz, const uint32_t *triangles, size_t count);

/* Prints the summary as indented lines (`indent` before each), e.g. for the demo and bench. */
void quality_print(const QualitySummary *q, const char *indent);

#endif
