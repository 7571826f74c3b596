/* Deterministic input point sets for the tests, the demo and the benchmark. Every generator
 * returns a malloc'd xyz array (free() it) or NULL when out of memory, and is a pure function of
 * its arguments (seeded prng.h). */
#ifndef DELMESH_C_TESTS_POINTS_H
#define DELMESH_C_TESTS_POINTS_H

#include <stddef.h>
#include <stdint.h>

/* n points uniform in the unit cube [0,1)^3. */
double *points_uniform_cube(size_t n, uint64_t seed);

/* n points near the unit sphere: uniform direction, radius uniform in [1 - t/2, 1 + t/2). */
double *points_thin_shell(size_t n, double thickness, uint64_t seed);

/* The k^3 integer points {0..k-1}^3, in a shuffled order. Hull volume (k-1)^3. */
double *points_grid(unsigned k, uint64_t seed);

/* Every integer point with x^2 + y^2 + z^2 = r2 (all exactly cospherical), shuffled; *n receives
 * their number. */
double *points_integer_sphere(long r2, uint64_t seed, size_t *n);

/* `layers` planes z = 0, 1, ..., layers-1, each with `per_layer` points uniform in [0,1)^2
 * (many exactly coplanar quadruples). */
double *points_layers(unsigned layers, size_t per_layer, uint64_t seed);

/* The n points followed by `extra` exact copies of randomly chosen ones, all shuffled together
 * (so a copy may come before its original). */
double *points_with_duplicates(const double *xyz, size_t n, size_t extra, uint64_t seed);

/* Vertices of an OFF file (the faces are ignored); NULL on failure with a reason in `error`. */
double *points_read_off(const char *path, size_t *n, char *error, size_t error_size);

#endif
