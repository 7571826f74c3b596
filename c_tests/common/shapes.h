/* Test shapes for oracle-driven meshing: implicit functions and labeling functions with their
 * bounding boxes, reference volumes, boundary topology and distance to the true surface. Shared
 * by the tests, the demo and the benchmark. No shape uses its user_data (NULL is fine).
 *
 * "The surface" of a shape is the union of its interfaces: the points where the label changes
 * (label 0 outside), e.g. for the three sectors the unit sphere and the three half-disks. */
#ifndef DELMESH_C_TESTS_SHAPES_H
#define DELMESH_C_TESTS_SHAPES_H

#include <stddef.h>
#include <stdint.h>

#define SHAPE_MAX_LABELS 3     /* subdomains 1..labels */
#define SHAPE_MAX_COMPONENTS 2 /* boundary components of one subdomain */

typedef enum ShapeId {
  SHAPE_SPHERE,         /* unit sphere x²+y²+z²-1 */
  SHAPE_TORUS,          /* R = 1, r = 0.35, around the z axis */
  SHAPE_TANGLECUBE,     /* x⁴-5x²+y⁴-5y²+z⁴-5z²+11.8, genus 5 */
  SHAPE_TWO_SPHERES,    /* radius 0.6 at (±0.8, 0, 0): one subdomain, two components */
  SHAPE_ELLIPSOID,      /* semi-axes (1, 0.6, 0.15) */
  SHAPE_NESTED_SPHERES, /* labeling: r < 0.5 → 1, r < 1 → 2, else 0 */
  SHAPE_SECTORS,        /* labeling: the unit ball in three 120° sectors around z, labels 1,2,3 */
  SHAPE_COUNT
} ShapeId;

typedef struct Shape {
  const char *name;
  /* Implicit domain (< 0 inside, label 1), or NULL for a labeling-function domain. */
  double (*implicit)(const double p[3], void *user_data);
  /* The label of a point (always set; for implicit shapes f < 0 → 1, else 0). */
  int32_t (*label)(const double p[3], void *user_data);
  /* Distance to the surface: exact where a closed form exists, else the distance to the foot
   * point found by Newton projection along ∇f (shape_implicit_distance). */
  double (*distance)(const double p[3]);
  double bbox[6]; /* xmin ymin zmin xmax ymax zmax; the shape is well inside */
  int labels;     /* subdomains are 1..labels */
  double volume[SHAPE_MAX_LABELS + 1]; /* volume[k] of subdomain k (index 0 unused) */
  const char *volume_source;           /* "analytic" or "numerical integration" */
  /* Boundary of subdomain k: its number of connected components and their Euler
   * characteristics V-E+F, ascending. */
  int components[SHAPE_MAX_LABELS + 1];
  int euler[SHAPE_MAX_LABELS + 1][SHAPE_MAX_COMPONENTS];
} Shape;

/* The shape `id` (the tanglecube's volume is integrated numerically on the first call). */
Shape shape_get(ShapeId id);

/* Diagonal of the bounding box. */
double shape_bbox_diagonal(const Shape *s);

/* Points on the surface: `lines` random lines through the bounding box (uniform point, uniform
 * direction), each marched in steps of diagonal / `steps_per_diagonal`; every label change
 * between two steps is bisected to machine precision. Malloc'd xyz array, *count points. */
double *shape_surface_samples(const Shape *s, size_t lines, unsigned steps_per_diagonal,
                              uint64_t seed, size_t *count);

/* Distance from p to the zero set of f near p: Newton projection along ∇f onto f = 0, then
 * foot-point iterations (move within the tangent plane toward p, project again) until p - q is
 * normal to the surface. For p near the surface (well within the curvature radius). */
double shape_implicit_distance(double (*f)(const double p[3], void *user_data),
                               void (*gradient)(const double p[3], double g[3]),
                               const double p[3]);

#endif
