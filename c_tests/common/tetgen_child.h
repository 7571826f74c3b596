/* TetGen's surface tetrahedralization (ref_tetgen_surface, ref_tetgen_polygons) and its
 * self-intersection check (ref_tetgen_intersections) run in a child process: TetGen 1.5.0 stops
 * on failed assert()s (abort) on some inputs with -Y, loops on others, and in library mode can
 * crash in its own cleanup when it stops on an error (a self-intersecting input), none of which
 * may end the test program. The child sends the result back through a pipe. */
#ifndef DELMESH_C_TESTS_TETGEN_CHILD_H
#define DELMESH_C_TESTS_TETGEN_CHILD_H

#include "ref.h"

#include <stddef.h>
#include <stdint.h>

/* As ref_tetgen_polygons (offsets NULL: `corners` holds m triangles, as ref_tetgen_surface).
 * The child is stopped after `time_limit` seconds (0: no limit; TetGen 1.5.0 also loops without
 * end on some inputs with -Y). Returns 0 and fills *out (free with ref_surface_mesh_free), or -1
 * with the reason in `error`: TetGen's failure, the time limit, or the signal that ended the
 * child. */
int tetgen_child_run(const double *xyz, size_t n, const uint32_t *corners, const size_t *offsets, size_t m,
                     const double *regions, size_t n_regions, const double *holes, size_t n_holes,
                     const char *switches, unsigned time_limit, RefSurfaceMesh *out, RefTiming *timing,
                     char *error, size_t error_size);

/* ref_tetgen_intersections in a child process, with the same time limit and reports. */
int tetgen_child_intersections(const double *xyz, size_t n, const uint32_t *tris, size_t m, unsigned time_limit,
                               uint32_t **culprits, size_t *count, char *error, size_t error_size);

#endif
