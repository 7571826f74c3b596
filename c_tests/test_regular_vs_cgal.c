/* delmesh_regular_tetrahedralize against CGAL's Regular_triangulation_3, through the C API:
 * the same set of finite tetrahedra and the same hidden points, on random weighted points
 * (weights up to a fraction of the squared mean spacing, so that some points are hidden; and a
 * case with many hidden points), on duplicates with different weights (the copy with the
 * largest weight is the vertex), on equal weights (then the Delaunay triangulation), and on a
 * degenerate weighted grid. Every result is valid (METRICS.md) over the hull of its vertices.
 * Usage: test_regular_vs_cgal [--small]   (--small: the sanitizer sizes) */
#include "check.h"
#include "compare.h"
#include "metrics.h"
#include "points.h"
#include "prng.h"
#include "ref.h"

#include <delmesh.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define VOLUME_TOLERANCE 1e-12

/* How coincident input points carry their weights. */
typedef enum Copies {
  NO_COPIES,
  SAME_WEIGHT_COPIES,    /* exact duplicates (position and weight): merged onto the first
                            occurrence (API.md); CGAL keeps an arbitrary copy, so its indices
                            are renamed onto the first occurrence */
  DISTINCT_WEIGHT_COPIES /* same position, different weights: the heaviest copy is the vertex,
                            the others are redundant (hidden), as in CGAL */
} Copies;

typedef struct Case {
  const char *name;
  double *xyz, *w; /* owned */
  size_t n;
  Copies copies;
  int also_delaunay; /* equal weights: the result must also be CGAL's Delaunay triangulation */
} Case;

/* Uniform weights in [0, fraction * h^2], h = n^(-1/3) the mean spacing of n points in the unit cube. */
static double *uniform_weights(size_t n, double fraction, uint64_t seed) {
  double *w = malloc((n ? n : 1) * sizeof *w);
  if (!w) return NULL;
  double h = cbrt(1.0 / (double)n);
  Prng g = prng_new(seed);
  for (size_t i = 0; i < n; i++) w[i] = fraction * h * h * prng_uniform(&g);
  return w;
}

/* Weights in [0, fraction * h^2] that are a (pseudo-random) function of the position, so that
 * exact copies of a point carry the same weight. */
static double *weights_of_position(const double *xyz, size_t n, double fraction) {
  double *w = malloc((n ? n : 1) * sizeof *w);
  if (!w) return NULL;
  double h = cbrt(1.0 / (double)n);
  for (size_t i = 0; i < n; i++) {
    uint64_t bits[3];
    memcpy(bits, xyz + 3 * i, sizeof bits);
    Prng g = prng_new(bits[0] ^ (bits[1] * UINT64_C(0x9E3779B97F4A7C15)) ^ (bits[2] << 1));
    w[i] = fraction * h * h * prng_uniform(&g);
  }
  return w;
}

/* The convex hull of the points CGAL keeps (its vertices as indices of the whole input). */
static int hull_of_kept(const char *name, const double *xyz, size_t n, const unsigned char *hidden,
                        uint32_t **hull, size_t *hull_count, double *hull_volume) {
  double *sub = malloc((n ? n : 1) * 3 * sizeof *sub);
  uint32_t *index = malloc((n ? n : 1) * sizeof *index);
  size_t m = 0;
  int ok = 0;
  if (sub && index) {
    for (size_t i = 0; i < n; i++)
      if (!hidden[i]) {
        memcpy(sub + 3 * m, xyz + 3 * i, 3 * sizeof *sub);
        index[m++] = (uint32_t)i;
      }
    ok = compare_convex_hull(name, sub, m, hull, hull_count, hull_volume);
    if (ok)
      for (size_t h = 0; h < *hull_count; h++) (*hull)[h] = index[(*hull)[h]];
  } else {
    check_case(0, "%s: out of memory", name);
  }
  free(sub);
  free(index);
  return ok;
}

static void run_case(Case k) {
  char name[160];
  snprintf(name, sizeof name, "%s (n=%zu)", k.name, k.n);
  if (!k.xyz || !k.w) {
    check_case(0, "%s: could not generate the input", name);
    free(k.xyz);
    free(k.w);
    return;
  }

  DelmeshMesh *mesh = NULL;
  DelmeshStatus s = delmesh_regular_tetrahedralize(k.xyz, k.w, k.n, &mesh);
  if (!check_case(s == DELMESH_OK && mesh, "%s: delmesh_regular_tetrahedralize -> %d %s", name,
                  (int)s, s == DELMESH_OK ? "" : delmesh_last_error_message())) {
    free(k.xyz);
    free(k.w);
    return;
  }
  compare_mesh_arrays(name, mesh, k.xyz, k.n);
  const uint32_t *tets = delmesh_mesh_tetrahedra(mesh);
  size_t count = delmesh_mesh_tetrahedron_count(mesh);

  uint32_t *ref = NULL;
  unsigned char *hidden = NULL;
  size_t ref_count = 0;
  int rc = ref_cgal_regular(k.xyz, k.w, k.n, &ref, &ref_count, &hidden, NULL);
  if (!check_case(rc == 0, "%s: CGAL Regular_triangulation_3 ran%s%s", name, rc ? ": " : "",
                  rc ? ref_last_error() : "")) {
    delmesh_mesh_free(mesh);
    free(k.xyz);
    free(k.w);
    return;
  }

  /* The expected hidden set: CGAL's, or with exact duplicates, per group of copies: the first
   * occurrence is hidden iff CGAL kept no copy, every later copy is unused. */
  uint32_t *first = metrics_first_occurrence(k.xyz, k.n);
  const uint32_t *rename = k.copies == SAME_WEIGHT_COPIES ? first : NULL;
  if (!first) {
    check_case(0, "%s: out of memory", name);
    delmesh_mesh_free(mesh);
    free(ref);
    free(hidden);
    free(k.xyz);
    free(k.w);
    return;
  }
  if (k.copies == SAME_WEIGHT_COPIES) {
    unsigned char *group_kept = calloc(k.n ? k.n : 1, 1);
    if (group_kept) {
      for (size_t i = 0; i < k.n; i++) group_kept[first[i]] |= !hidden[i];
      for (size_t i = 0; i < k.n; i++) hidden[i] = first[i] != i || !group_kept[i];
      free(group_kept);
    }
  }

  /* Hidden set: ours = the points no tetrahedron uses. */
  unsigned char *used = calloc(k.n ? k.n : 1, 1);
  size_t ours_hidden = 0, cgal_hidden = 0, mismatched = 0;
  long first_mismatch = -1;
  if (used) {
    for (size_t i = 0; i < 4 * count; i++)
      if (tets[i] < k.n) used[tets[i]] = 1;
    for (size_t i = 0; i < k.n; i++) {
      ours_hidden += !used[i];
      cgal_hidden += hidden[i];
      if (!used[i] != !!hidden[i]) {
        mismatched++;
        if (first_mismatch < 0) first_mismatch = (long)i;
      }
    }
  }
  check_case(used && mismatched == 0,
             "%s: hidden points: ours %zu, CGAL %zu, %zu differ (first: point %ld)", name,
             ours_hidden, cgal_hidden, mismatched, first_mismatch);
  free(used);

  /* What delmesh reports as duplicates (API.md: merged onto the first occurrence). With
   * different weights that contract contradicts itself (the merged copy would be the one
   * referenced), so it is only reported there. */
  const uint32_t *dup = delmesh_mesh_duplicate_of(mesh);
  size_t dup_wrong = 0, expected_dups = 0, dup_count = delmesh_mesh_duplicate_count(mesh);
  for (size_t i = 0; i < k.n; i++) {
    expected_dups += first[i] != i;
    if (dup) dup_wrong += dup[i] != first[i];
  }
  if (k.copies == DISTINCT_WEIGHT_COPIES)
    check_note("%s: duplicate_of: %zu points share the position of an earlier one; delmesh reports %zu duplicates, %zu entries differ from the first occurrence [reported, not asserted]",
               name, expected_dups, dup_count, dup ? dup_wrong : k.n);
  else
    check_case(dup && dup_wrong == 0 && dup_count == expected_dups,
               "%s: duplicate_of names the first occurrence of each point (%zu duplicates reported, %zu expected, %zu wrong entries)",
               name, dup_count, expected_dups, dup_wrong);

  /* Validity over the hull of the vertices CGAL keeps; volume against that hull. */
  uint32_t *hull = NULL;
  size_t hull_count = 0;
  double hull_volume = NAN;
  if (hull_of_kept(name, k.xyz, k.n, hidden, &hull, &hull_count, &hull_volume)) {
    unsigned char *expect = malloc(k.n ? k.n : 1);
    if (expect) {
      memset(expect, VERTEX_MAY_BE_UNUSED, k.n);
      Validity v;
      char text[512];
      int ok = metrics_validity(k.xyz, k.n, tets, count, expect, hull, hull_count, &v);
      metrics_validity_describe(&v, text, sizeof text);
      check_case(ok, "%s: valid: %s", name, text);
      compare_volume(name, "convex hull of CGAL's vertices", metrics_tetrahedra_volume(k.xyz, tets, count),
                     hull_volume, VOLUME_TOLERANCE);
      free(expect);
    }
  }
  free(hull);

  check_case(count == ref_count, "%s: %zu tetrahedra, CGAL %zu", name, count, ref_count);
  compare_tetrahedron_sets(name, "CGAL regular", tets, count, NULL, ref, ref_count, rename, 1);
  free(ref);
  free(hidden);

  if (k.also_delaunay) {
    rc = ref_cgal_delaunay(k.xyz, k.n, &ref, &ref_count, NULL);
    if (check_case(rc == 0, "%s: CGAL Delaunay_triangulation_3 ran%s%s", name, rc ? ": " : "",
                   rc ? ref_last_error() : "")) {
      compare_tetrahedron_sets(name, "CGAL Delaunay", tets, count, NULL, ref, ref_count, rename, 1);
      free(ref);
    }
  }

  free(first);
  delmesh_mesh_free(mesh);
  free(k.xyz);
  free(k.w);
}

int main(int argc, char **argv) {
  int small = argc > 1 && strcmp(argv[1], "--small") == 0;

  /* Random points, weights up to 0.5 h^2: a few hidden points. */
  size_t sizes[] = {1000, 10000, 100000};
  size_t n_sizes = small ? 2 : 3;
  for (size_t i = 0; i < n_sizes; i++)
    run_case((Case){"uniform cube, weights in [0, 0.5 h^2]", points_uniform_cube(sizes[i], 0x7E160000u + i),
                    uniform_weights(sizes[i], 0.5, 0x7E161000u + i), sizes[i], NO_COPIES, 0});

  /* Many hidden points: weights up to 4 h^2. */
  size_t n = small ? 2000 : 20000;
  run_case((Case){"uniform cube, weights in [0, 4 h^2] (many hidden)", points_uniform_cube(n, 0x7E170000u),
                  uniform_weights(n, 4.0, 0x7E171000u), n, NO_COPIES, 0});

  /* Duplicates with different weights: the copy with the largest weight is the vertex. */
  n = small ? 2000 : 10000;
  double *cube = points_uniform_cube(n, 0x7E180000u);
  double *xyz = cube ? points_with_duplicates(cube, n, n / 5, 0x7E180001u) : NULL;
  double *w = uniform_weights(n + n / 5, 0.5, 0x7E180002u);
  run_case((Case){"uniform cube + 20% duplicates, distinct weights", xyz, w, n + n / 5, DISTINCT_WEIGHT_COPIES, 0});
  free(cube);

  /* Exact duplicates (same position, same weight): merged onto the first occurrence. */
  cube = points_uniform_cube(n, 0x7E1B0000u);
  xyz = cube ? points_with_duplicates(cube, n, n / 5, 0x7E1B0001u) : NULL;
  w = xyz ? weights_of_position(xyz, n + n / 5, 0.5) : NULL;
  run_case((Case){"uniform cube + 20% exact duplicates (same weights)", xyz, w, n + n / 5, SAME_WEIGHT_COPIES, 0});
  free(cube);

  /* The smallest form of the above: exact copies of points that are hidden (the unit cube's
   * corners with weight 1 hide the 3 points inside with weight 0; each of those appears twice). */
  xyz = malloc(14 * 3 * sizeof *xyz);
  w = malloc(14 * sizeof *w);
  if (xyz && w) {
    for (int i = 0; i < 8; i++) {
      xyz[3 * i] = i & 1;
      xyz[3 * i + 1] = (i >> 1) & 1;
      xyz[3 * i + 2] = (i >> 2) & 1;
      w[i] = 1.0;
    }
    for (int i = 8; i < 14; i++) {
      xyz[3 * i] = 0.3 + 0.4 * ((i - 8) % 3) / 3.0;
      xyz[3 * i + 1] = 0.5;
      xyz[3 * i + 2] = 0.5;
      w[i] = 0.0;
    }
  }
  run_case((Case){"cube corners (weight 1) + 3 hidden points each given twice", xyz, w, 14, SAME_WEIGHT_COPIES, 0});

  /* Equal weights: the regular triangulation is the Delaunay triangulation. */
  n = small ? 2000 : 10000;
  w = uniform_weights(n, 0.0, 0);
  if (w)
    for (size_t i = 0; i < n; i++) w[i] = 0.125;
  run_case((Case){"uniform cube, all weights 0.125", points_uniform_cube(n, 0x7E190000u), w, n, NO_COPIES, 1});

  /* Degenerate: an integer grid, weight 0.25 on the points with x+y+z even, 0 elsewhere (exact
   * ties in the power tests, resolved by the symbolic perturbation). */
  unsigned side = 10;
  double *grid = points_grid(side, 0x7E1A0000u);
  w = malloc((size_t)side * side * side * sizeof *w);
  if (grid && w)
    for (size_t i = 0; i < (size_t)side * side * side; i++)
      w[i] = ((long)(grid[3 * i] + grid[3 * i + 1] + grid[3 * i + 2]) % 2 == 0) ? 0.25 : 0.0;
  run_case((Case){"integer grid 10^3, weights 0.25 / 0 by parity", grid, w, (size_t)side * side * side, NO_COPIES, 0});

  return check_finish();
}
