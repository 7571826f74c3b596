/* Closed triangulated surfaces made by code, the inputs of surface tetrahedralization tests
 * (delmesh_tetrahedralize_surface beside TetGen -p): classic hard cases for boundary recovery,
 * surfaces bounding several regions, and a few invalid surfaces.
 *
 * Every surface is a vertex array and a triangle array (3 vertex indices each); every vertex is
 * used by a triangle and no two vertices coincide. The valid ones are closed (every edge in two
 * or more triangles); each closed 2-manifold one is oriented outward; the others (an interface,
 * two solids touching along an edge) keep each box's outward orientation and list a shared face
 * once. Region seeds are (x, y, z, label, max volume) records and hole seeds points, as in
 * TetGen's .poly files (ref_tetgen_surface, delmesh_tetrahedralize_surface_regions). */
#ifndef DELMESH_C_TESTS_SURFACES_H
#define DELMESH_C_TESTS_SURFACES_H

#include <stddef.h>
#include <stdint.h>

#define SURFACE_MAX_SEEDS 4

typedef struct Surface {
  char name[64];
  double *xyz; /* 3 * n */
  size_t n;
  uint32_t *tris; /* 3 * m */
  size_t m;
  double regions[5 * SURFACE_MAX_SEEDS]; /* n_regions records x, y, z, label, max volume */
  size_t n_regions;
  double holes[3 * SURFACE_MAX_SEEDS];
  size_t n_holes;
  int expected_regions; /* regions (distinct labels) of a correct tetrahedralization */
  /* Invalid surfaces: the triangles an error message may name (sorted), else none. */
  uint32_t *culprits;
  size_t culprit_count;
  const char *defect; /* "open", "self-intersecting", "zero-area", or NULL when valid */
} Surface;

/* ---- Valid surfaces. Each returns 1, or 0 when out of memory (*s is then empty). ---------- */

/* The unit cube [0,1]^3, 12 triangles. */
int surface_cube(Surface *s);
/* The unit cube and vertices no triangle uses: *inside of them inside (numbered 8, 9, ...),
 * then 2 outside. */
int surface_cube_with_nodes(Surface *s, size_t *inside);
/* The octahedron with vertices ±e_i, 8 triangles. */
int surface_octahedron(Surface *s);
/* The icosahedron subdivided `level` times (each triangle into 4), projected on the unit
 * sphere: 20 * 4^level triangles. */
int surface_icosphere(Surface *s, int level);
/* The triangular prism twisted by `degrees` (in (0, 60)): bottom triangle on the unit circle
 * at z = 0, the top one rotated by `degrees` at z = 1, each side quadrilateral split along its
 * reflex diagonal. No tetrahedralization without Steiner points exists (Schönhardt 1928 at
 * 30 degrees; Rambau 2005 for every twist). */
int surface_twisted_prism(Surface *s, double degrees);
/* Chazelle's polyhedron (1984) with k notches from the top and k from the bottom: the box
 * [-1,1]^2 x [-2,2] with k V-shaped crevices along y cut from the top, their bottom edges the
 * lines x = x_i, z = c x_i y + d of the saddle z = c x y (c = 1/4) lifted by d = 0.01, and k
 * crevices along x cut from the bottom up to the lines y = y_j, z = c x y_j - d. The edges of
 * the two families pass at distance about 2d of each other in a k x k grid; the crevice walls
 * are ruled quadrilaterals split into two triangles. Needs Omega(k^2) Steiner points. */
int surface_chazelle(Surface *s, int k);
/* George and Borouchaki's terrain: the box over [0,1]^2 from z = 0 to a top face of `grid` x
 * `grid` cells at heights 0.5 + 0.01 * (pseudo-random in [-1, 1]), each cell two triangles;
 * the bottom face is two triangles, each side face a fan from a bottom corner. */
int surface_terrain(Surface *s, int grid);
/* The slab [0,1] x [0,1] x [0, 0.01]: each large face `split` x `split` squares of two
 * triangles, the thin sides strips of `split` squares. */
int surface_slab(Surface *s, int split);
/* The cube [1,2]^3 inside the cube [0,3]^3 (24 triangles). variant 0: no seeds, two regions;
 * 1: a hole seed in the inner cube, one region (the shell); 2: region seeds, label 7 in the
 * shell and 3 in the inner cube; 3: as 2 with a max volume of 0.02 in the inner cube. */
int surface_nested_cubes(Surface *s, int variant);
/* Two boxes [0,1]^3 and [1,2] x [0,1]^2 glued along x = 1 (that face triangulated once, 2x2
 * squares; the first box is 1x2x2 squares, the second 2x2x2): two regions and an interface. */
int surface_glued_boxes(Surface *s);
/* The cubes [0,1]^3 and [1,2] x [1,2] x [0,1], which share only the edge x = y = 1: two
 * regions, an edge in four triangles. */
int surface_edge_cubes(Surface *s);

/* ---- Invalid surfaces (defect and culprits set) ---------------------------------------------- */

/* The unit cube without its last triangle: culprits are the triangles with an edge in one
 * triangle only. */
int surface_open_cube(Surface *s);
/* Two level-2 icospheres that overlap (radius 1 at the origin, radius 0.8 at (0.9, 0.13,
 * 0.07)): culprits are the triangles that intersect a triangle of the other sphere (exact
 * predicates, shims/ref.h). */
int surface_intersecting_spheres(Surface *s);
/* The unit cube with its top edge y = 0 split at its midpoint m: the top triangle beside that
 * edge uses m, and the zero-area triangle (a, b, m) closes the surface. Culprit: that one. */
int surface_zero_area(Surface *s);

void surface_free(Surface *s);

/* ---- Checks of a triangle surface (any input, e.g. read from a file) ------------------------- */

typedef struct SurfaceEdges {
  size_t edges;
  size_t open;          /* in one triangle */
  size_t nonmanifold;   /* in three or more */
  size_t misoriented;   /* in two triangles that run it the same direction */
  size_t bad_triangles; /* an index out of range or repeated */
} SurfaceEdges;

/* The edges of the triangles. Returns 1 when the surface is closed (no open edge, no bad
 * triangle), 0 otherwise or when out of memory (edges = 0 then). */
int surface_edges(const uint32_t *tris, size_t m, size_t n, SurfaceEdges *out);

#endif
