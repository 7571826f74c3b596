#include "points.h"

#include "prng.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double *alloc_points(size_t n) { return malloc((n ? n : 1) * 3 * sizeof(double)); }

static void shuffle(double *xyz, size_t n, Prng *g) {
  for (size_t i = n; i > 1; i--) {
    size_t j = prng_below(g, i);
    for (int k = 0; k < 3; k++) {
      double t = xyz[3 * (i - 1) + k];
      xyz[3 * (i - 1) + k] = xyz[3 * j + k];
      xyz[3 * j + k] = t;
    }
  }
}

double *points_uniform_cube(size_t n, uint64_t seed) {
  Prng g = prng_new(seed);
  double *xyz = alloc_points(n);
  if (!xyz) return NULL;
  for (size_t i = 0; i < 3 * n; i++) xyz[i] = prng_uniform(&g);
  return xyz;
}

double *points_thin_shell(size_t n, double thickness, uint64_t seed) {
  Prng g = prng_new(seed);
  double *xyz = alloc_points(n);
  if (!xyz) return NULL;
  for (size_t i = 0; i < n; i++) {
    double d[3], r2;
    do { /* uniform direction: rejection in the ball, then normalization */
      for (int k = 0; k < 3; k++) d[k] = 2.0 * prng_uniform(&g) - 1.0;
      r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (r2 > 1.0 || r2 < 1e-6);
    double radius = 1.0 + thickness * (prng_uniform(&g) - 0.5);
    double s = radius / sqrt(r2);
    for (int k = 0; k < 3; k++) xyz[3 * i + k] = s * d[k];
  }
  return xyz;
}

double *points_grid(unsigned k, uint64_t seed) {
  size_t n = (size_t)k * k * k;
  double *xyz = alloc_points(n);
  if (!xyz) return NULL;
  size_t i = 0;
  for (unsigned x = 0; x < k; x++)
    for (unsigned y = 0; y < k; y++)
      for (unsigned z = 0; z < k; z++) {
        xyz[3 * i] = x;
        xyz[3 * i + 1] = y;
        xyz[3 * i + 2] = z;
        i++;
      }
  Prng g = prng_new(seed);
  shuffle(xyz, n, &g);
  return xyz;
}

double *points_integer_sphere(long r2, uint64_t seed, size_t *n) {
  long r = (long)floor(sqrt((double)r2));
  while ((r + 1) * (r + 1) <= r2) r++;
  while (r * r > r2) r--;
  size_t cap = 64, count = 0;
  double *xyz = alloc_points(cap);
  if (!xyz) return NULL;
  for (long x = -r; x <= r; x++)
    for (long y = -r; y <= r; y++) {
      long rest = r2 - x * x - y * y;
      if (rest < 0) continue;
      long z = (long)floor(sqrt((double)rest));
      while ((z + 1) * (z + 1) <= rest) z++;
      while (z * z > rest) z--;
      if (z * z != rest) continue;
      for (int s = (z == 0 ? 1 : -1); s <= 1; s += 2) {
        if (count == cap) {
          double *grown = realloc(xyz, 2 * cap * 3 * sizeof(double));
          if (!grown) {
            free(xyz);
            return NULL;
          }
          xyz = grown;
          cap *= 2;
        }
        xyz[3 * count] = (double)x;
        xyz[3 * count + 1] = (double)y;
        xyz[3 * count + 2] = (double)(s * z);
        count++;
      }
    }
  Prng g = prng_new(seed);
  shuffle(xyz, count, &g);
  *n = count;
  return xyz;
}

double *points_layers(unsigned layers, size_t per_layer, uint64_t seed) {
  size_t n = (size_t)layers * per_layer;
  double *xyz = alloc_points(n);
  if (!xyz) return NULL;
  Prng g = prng_new(seed);
  for (size_t i = 0; i < n; i++) {
    xyz[3 * i] = prng_uniform(&g);
    xyz[3 * i + 1] = prng_uniform(&g);
    xyz[3 * i + 2] = (double)(i % layers);
  }
  shuffle(xyz, n, &g);
  return xyz;
}

double *points_with_duplicates(const double *xyz, size_t n, size_t extra, uint64_t seed) {
  double *out = alloc_points(n + extra);
  if (!out || n == 0) {
    free(out);
    return NULL;
  }
  memcpy(out, xyz, 3 * n * sizeof(double));
  Prng g = prng_new(seed);
  for (size_t i = 0; i < extra; i++) {
    size_t j = prng_below(&g, n);
    memcpy(out + 3 * (n + i), xyz + 3 * j, 3 * sizeof(double));
  }
  shuffle(out, n + extra, &g);
  return out;
}

/* Next whitespace-separated token of an OFF file, skipping '#' comments; the character that
 * ended the token is left unread. */
static int off_token(FILE *f, char *buf, size_t size) {
  int c;
  size_t len = 0;
  for (;;) {
    c = fgetc(f);
    if (c == EOF) return 0;
    if (c == '#') {
      while (c != '\n' && c != EOF) c = fgetc(f);
      continue;
    }
    if (c != ' ' && c != '\t' && c != '\r' && c != '\n') break;
  }
  while (c != EOF && c != ' ' && c != '\t' && c != '\r' && c != '\n' && c != '#') {
    if (len + 1 < size) buf[len++] = (char)c;
    c = fgetc(f);
  }
  if (c != EOF) ungetc(c, f); /* the caller decides whether the rest of the line matters */
  buf[len] = '\0';
  return 1;
}

static void skip_line(FILE *f) {
  int c;
  do c = fgetc(f);
  while (c != '\n' && c != EOF);
}

double *points_read_off(const char *path, size_t *n, char *error, size_t error_size) {
  char tok[128];
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(error, error_size, "cannot open %s: %s", path, strerror(errno));
    return NULL;
  }
  if (!off_token(f, tok, sizeof tok) || strcmp(tok, "OFF") != 0) {
    snprintf(error, error_size, "%s: not an OFF file (no OFF header)", path);
    fclose(f);
    return NULL;
  }
  long counts[3];
  for (int k = 0; k < 3; k++) {
    char *end;
    if (!off_token(f, tok, sizeof tok) || (counts[k] = strtol(tok, &end, 10), *end != '\0') ||
        counts[k] < 0) {
      snprintf(error, error_size, "%s: bad vertex/face/edge counts", path);
      fclose(f);
      return NULL;
    }
  }
  size_t nv = (size_t)counts[0];
  double *xyz = alloc_points(nv);
  if (!xyz) {
    snprintf(error, error_size, "out of memory");
    fclose(f);
    return NULL;
  }
  skip_line(f);
  for (size_t i = 0; i < nv; i++) {
    for (int k = 0; k < 3; k++) {
      char *end;
      if (!off_token(f, tok, sizeof tok) || (xyz[3 * i + k] = strtod(tok, &end), *end != '\0')) {
        snprintf(error, error_size, "%s: bad coordinate of vertex %zu", path, i);
        free(xyz);
        fclose(f);
        return NULL;
      }
    }
    skip_line(f); /* optional per-vertex colour or normal */
  }
  fclose(f);
  *n = nv;
  return xyz;
}
