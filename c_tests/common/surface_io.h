/* Readers of the corpus's surface files: OFF (ASCII, polygons of any size) and TetGen's .smesh
 * (a node list, one polygon per facet, hole and region seeds). Both give polygons over a
 * vertex array; a file whose polygons are all triangles is a triangle surface. */
#ifndef DELMESH_C_TESTS_SURFACE_IO_H
#define DELMESH_C_TESTS_SURFACE_IO_H

#include <stddef.h>
#include <stdint.h>

typedef struct SurfaceFile {
  double *xyz; /* 3 * n */
  size_t n;
  uint32_t *corners; /* polygon f is corners[offsets[f] .. offsets[f + 1]), 0-based */
  size_t *offsets;   /* polygon_count + 1 entries */
  size_t polygon_count;
  int all_triangles;  /* every polygon has 3 corners: corners is then a triangle array */
  double *regions;    /* n_regions records x, y, z, label, max volume (.smesh) */
  size_t n_regions;
  double *holes;      /* n_holes points (.smesh) */
  size_t n_holes;
} SurfaceFile;

/* Reads `path` by its extension (.off or .smesh). Returns 1 on success; 0 with a message in
 * `error` otherwise (*out is then empty). Indices are checked against the vertex count. */
int surface_file_read(const char *path, SurfaceFile *out, char *error, size_t error_size);

void surface_file_free(SurfaceFile *f);

#endif
