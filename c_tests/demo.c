/* delmesh demo: the Delaunay tetrahedralization of a real point set through the C API.
 *
 *   demo [--off FILE.off] [--out FILE.vtu]
 *
 * Points: the vertices of FILE.off; by default those of surfaces/elephant.off from the shared
 * corpus ($DELMESH_CORPUS, else ../shared/data seen from the repository root, where `make demo`
 * runs); when that is absent, 20000 generated points near a sphere (the demo says which).
 * Prints the counts (points, duplicates, tetrahedra), validity, volume against the convex hull,
 * and the time of the call; writes the mesh with delmesh_mesh_write (default
 * c_tests/build/demo.vtu). Exits non-zero on any failure. */
#define _POSIX_C_SOURCE 200809L

#include "metrics.h"
#include "points.h"
#include "ref.h"

#include <delmesh.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double seconds_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int file_exists(const char *path) {
  FILE *f = fopen(path, "r");
  if (f) fclose(f);
  return f != NULL;
}

int main(int argc, char **argv) {
  const char *off = NULL, *out_path = "c_tests/build/demo.vtu";
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--off") == 0 && i + 1 < argc)
      off = argv[++i];
    else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
      out_path = argv[++i];
    else {
      fprintf(stderr, "usage: %s [--off FILE.off] [--out FILE.vtu]\n", argv[0]);
      return 2;
    }
  }

  char corpus_path[4096];
  if (!off) {
    const char *corpus = getenv("DELMESH_CORPUS");
    snprintf(corpus_path, sizeof corpus_path, "%s/surfaces/elephant.off",
             corpus && corpus[0] ? corpus : "../shared/data");
    if (file_exists(corpus_path)) off = corpus_path;
  }

  double *xyz;
  size_t n = 0;
  if (off) {
    char error[512];
    xyz = points_read_off(off, &n, error, sizeof error);
    if (!xyz) {
      fprintf(stderr, "demo: %s\n", error);
      return 1;
    }
    printf("points:      %zu, the vertices of %s\n", n, off);
  } else {
    n = 20000;
    xyz = points_thin_shell(n, 0.05, 0xDE70u);
    if (!xyz) {
      fprintf(stderr, "demo: out of memory\n");
      return 1;
    }
    printf("points:      %zu generated near the unit sphere (no corpus: %s not found; set DELMESH_CORPUS)\n",
           n, corpus_path);
  }

  DelmeshMesh *mesh = NULL;
  double t0 = seconds_now();
  DelmeshStatus status = delmesh_delaunay_tetrahedralize(xyz, n, &mesh);
  double elapsed = seconds_now() - t0;
  if (status != DELMESH_OK) {
    fprintf(stderr, "demo: delmesh_delaunay_tetrahedralize failed (status %d): %s\n", (int)status,
            delmesh_last_error_message());
    free(xyz);
    return 1;
  }
  const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
  size_t count = delmesh_mesh_tetrahedron_count(mesh);
  size_t duplicates = delmesh_mesh_duplicate_count(mesh);
  int failed = 0;

  /* Duplicates: the library's report against our own count. */
  uint32_t *first = metrics_first_occurrence(xyz, n);
  unsigned char *expect = malloc(n ? n : 1);
  size_t expected_duplicates = 0;
  if (!first || !expect) {
    fprintf(stderr, "demo: out of memory\n");
    return 1;
  }
  for (size_t i = 0; i < n; i++) {
    expect[i] = first[i] == i ? VERTEX_MUST_BE_USED : VERTEX_MUST_BE_UNUSED;
    expected_duplicates += first[i] != i;
  }
  printf("duplicates:  %zu merged (independent count: %zu)\n", duplicates, expected_duplicates);
  failed |= duplicates != expected_duplicates;
  printf("tetrahedra:  %zu\n", count);
  printf("time:        %.3f s for delmesh_delaunay_tetrahedralize (%.0f points/s)\n", elapsed,
         elapsed > 0 ? (double)n / elapsed : 0.0);

  /* Validity and volume against the convex hull (CGAL convex_hull_3). */
  uint32_t *hull_triangles = NULL, *hull = NULL;
  size_t hull_triangle_count = 0, hull_count = 0;
  if (ref_cgal_convex_hull(xyz, n, &hull_triangles, &hull_triangle_count) != 0) {
    fprintf(stderr, "demo: convex hull failed: %s\n", ref_last_error());
    return 1;
  }
  hull = metrics_triangle_vertices(hull_triangles, hull_triangle_count, &hull_count);
  Validity v;
  char text[512];
  int valid = hull && metrics_validity(xyz, n, tets, count, expect, hull, hull_count, &v);
  if (hull) metrics_validity_describe(&v, text, sizeof text);
  printf("validity:    %s\n", valid ? text : hull ? text : "could not be checked");
  failed |= !valid;
  double volume = metrics_tetrahedra_volume(xyz, tets, count);
  double hull_volume = metrics_polyhedron_volume(xyz, hull_triangles, hull_triangle_count);
  double error = metrics_relative_error(volume, hull_volume);
  printf("volume:      %.15g (convex hull %.15g, relative error %.2g)\n", volume, hull_volume, error);
  failed |= !(error <= 1e-12);

  status = delmesh_mesh_write(mesh, out_path);
  if (status == DELMESH_OK) {
    printf("written:     %s\n", out_path);
  } else {
    fprintf(stderr, "demo: delmesh_mesh_write(%s) failed (status %d): %s\n", out_path, (int)status,
            delmesh_last_error_message());
    failed = 1;
  }

  printf("%s\n", failed ? "demo FAILED" : "demo OK");
  delmesh_mesh_free(mesh);
  free(hull);
  free(hull_triangles);
  free(first);
  free(expect);
  free(xyz);
  return failed ? 1 : 0;
}
