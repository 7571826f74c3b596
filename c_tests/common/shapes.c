#include "shapes.h"

#include "prng.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

static double dist3(const double a[3], const double b[3]) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return norm3(d);
}

/* ---- Distance to an implicit surface --------------------------------------------------------- */

/* q moves along ∇f until f(q) = 0 (to rounding). */
static void newton_project(double (*f)(const double p[3], void *user_data),
                           void (*gradient)(const double p[3], double g[3]), double q[3]) {
  for (int it = 0; it < 100; it++) {
    double g[3], value = f(q, NULL);
    gradient(q, g);
    double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (value == 0 || gg == 0) return;
    double step = value / gg;
    for (int k = 0; k < 3; k++) q[k] -= step * g[k];
    if (fabs(step) * sqrt(gg) <= 1e-15 * (1.0 + norm3(q))) return;
  }
}

double shape_implicit_distance(double (*f)(const double p[3], void *user_data),
                               void (*gradient)(const double p[3], double g[3]),
                               const double p[3]) {
  double q[3] = {p[0], p[1], p[2]};
  newton_project(f, gradient, q);
  for (int it = 0; it < 100; it++) {
    double g[3], w[3], t[3];
    gradient(q, g);
    double gn = norm3(g);
    if (gn == 0) break;
    for (int k = 0; k < 3; k++) w[k] = p[k] - q[k];
    double wn = (w[0] * g[0] + w[1] * g[1] + w[2] * g[2]) / gn;
    for (int k = 0; k < 3; k++) t[k] = w[k] - wn * g[k] / gn; /* tangential part of p - q */
    if (norm3(t) <= 1e-14 * (1.0 + norm3(q))) break;
    for (int k = 0; k < 3; k++) q[k] += t[k];
    newton_project(f, gradient, q);
  }
  return dist3(p, q);
}

/* ---- The shapes ------------------------------------------------------------------------------- */

static int32_t inside_label(double value) { return value < 0 ? 1 : 0; }

/* Unit sphere. */
static double sphere_f(const double p[3], void *u) {
  (void)u;
  return p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0;
}
static int32_t sphere_label(const double p[3], void *u) { return inside_label(sphere_f(p, u)); }
static double sphere_distance(const double p[3]) { return fabs(norm3(p) - 1.0); }

/* Torus. */
#define TORUS_R 1.0
#define TORUS_r 0.35
static double torus_tube(const double p[3]) { /* distance to the core circle */
  double rho = hypot(p[0], p[1]) - TORUS_R;
  return hypot(rho, p[2]);
}
static double torus_f(const double p[3], void *u) {
  (void)u;
  double rho = hypot(p[0], p[1]) - TORUS_R;
  return rho * rho + p[2] * p[2] - TORUS_r * TORUS_r;
}
static int32_t torus_label(const double p[3], void *u) { return inside_label(torus_f(p, u)); }
static double torus_distance(const double p[3]) { return fabs(torus_tube(p) - TORUS_r); }

/* Tanglecube. */
static double tangle_g(double x) { return x * x * x * x - 5.0 * x * x; }
static double tanglecube_f(const double p[3], void *u) {
  (void)u;
  return tangle_g(p[0]) + tangle_g(p[1]) + tangle_g(p[2]) + 11.8;
}
static void tanglecube_gradient(const double p[3], double g[3]) {
  for (int k = 0; k < 3; k++) g[k] = 4.0 * p[k] * p[k] * p[k] - 10.0 * p[k];
}
static int32_t tanglecube_label(const double p[3], void *u) { return inside_label(tanglecube_f(p, u)); }
static double tanglecube_distance(const double p[3]) {
  return shape_implicit_distance(tanglecube_f, tanglecube_gradient, p);
}

/* Volume of {f < 0} by symmetry: 8 ∫∫_{x,y>0} L(x,y) dx dy, where L is the exact length of
 * {z > 0 : z⁴ - 5z² + c < 0}, c = g(x) + g(y) + 11.8 (a quadratic in u = z²); midpoint rule on
 * an n x n grid over [0, 2.3]² (the shape ends at |x| < 2.27). */
static double tanglecube_volume(void) {
  const int n = 6000;
  const double extent = 2.3, h = extent / n;
  double total = 0.0;
  for (int i = 0; i < n; i++) {
    double gx = tangle_g((i + 0.5) * h) + 11.8, row = 0.0;
    for (int j = 0; j < n; j++) {
      double c = gx + tangle_g((j + 0.5) * h), disc = 25.0 - 4.0 * c;
      if (disc <= 0) continue;
      double s = sqrt(disc), u1 = 0.5 * (5.0 - s), u2 = 0.5 * (5.0 + s);
      row += sqrt(u2) - (u1 > 0 ? sqrt(u1) : 0.0);
    }
    total += row;
  }
  return 8.0 * total * h * h;
}

/* Two disjoint spheres. */
#define TWO_R 0.6
#define TWO_X 0.8
static double two_spheres_f(const double p[3], void *u) {
  (void)u;
  double a[3] = {p[0] - TWO_X, p[1], p[2]}, b[3] = {p[0] + TWO_X, p[1], p[2]};
  return fmin(norm3(a), norm3(b)) - TWO_R;
}
static int32_t two_spheres_label(const double p[3], void *u) { return inside_label(two_spheres_f(p, u)); }
static double two_spheres_distance(const double p[3]) {
  double a[3] = {p[0] - TWO_X, p[1], p[2]}, b[3] = {p[0] + TWO_X, p[1], p[2]};
  return fmin(fabs(norm3(a) - TWO_R), fabs(norm3(b) - TWO_R));
}

/* Thin ellipsoid. */
static const double ellipsoid_axes[3] = {1.0, 0.6, 0.15};
static double ellipsoid_f(const double p[3], void *u) {
  (void)u;
  double s = 0.0;
  for (int k = 0; k < 3; k++) s += (p[k] / ellipsoid_axes[k]) * (p[k] / ellipsoid_axes[k]);
  return s - 1.0;
}
static void ellipsoid_gradient(const double p[3], double g[3]) {
  for (int k = 0; k < 3; k++) g[k] = 2.0 * p[k] / (ellipsoid_axes[k] * ellipsoid_axes[k]);
}
static int32_t ellipsoid_label(const double p[3], void *u) { return inside_label(ellipsoid_f(p, u)); }
static double ellipsoid_distance(const double p[3]) {
  return shape_implicit_distance(ellipsoid_f, ellipsoid_gradient, p);
}

/* Nested spheres. */
static int32_t nested_label(const double p[3], void *u) {
  (void)u;
  double r = norm3(p);
  return r < 0.5 ? 1 : r < 1.0 ? 2 : 0;
}
static double nested_distance(const double p[3]) {
  double r = norm3(p);
  return fmin(fabs(r - 0.5), fabs(r - 1.0));
}

/* Three sectors: the half-planes at angles 15°, 135°, 255° around the z axis cut the unit ball. */
#define SECTOR_START (15.0 * PI / 180.0)
static int32_t sectors_label(const double p[3], void *u) {
  (void)u;
  if (norm3(p) >= 1.0) return 0;
  double phi = atan2(p[1], p[0]) - SECTOR_START;
  while (phi < 0) phi += 2.0 * PI;
  int sector = (int)(phi / (2.0 * PI / 3.0));
  return sector > 2 ? 3 : sector + 1;
}
static double sectors_distance(const double p[3]) {
  double d = fabs(norm3(p) - 1.0);
  for (int k = 0; k < 3; k++) {
    /* The half-disk {t·e + z·ẑ : t >= 0, t² + z² <= 1}, e the unit direction at its angle. */
    double angle = SECTOR_START + k * 2.0 * PI / 3.0, e[2] = {cos(angle), sin(angle)};
    double t = p[0] * e[0] + p[1] * e[1], normal = -p[0] * e[1] + p[1] * e[0];
    double ct = t > 0 ? t : 0.0, cz = p[2], r = hypot(ct, cz); /* nearest point in the plane: */
    if (r > 1.0) ct /= r, cz /= r;                              /* the half-plane, then the disk */
    d = fmin(d, sqrt(normal * normal + (t - ct) * (t - ct) + (p[2] - cz) * (p[2] - cz)));
  }
  return d;
}

Shape shape_get(ShapeId id) {
  const double ball = 4.0 * PI / 3.0;
  Shape s = {0};
  switch (id) {
    case SHAPE_SPHERE:
      s = (Shape){"unit sphere", sphere_f, sphere_label, sphere_distance, {-2, -2, -2, 2, 2, 2}, 1,
                  {0, ball}, "analytic", {0, 1}, {{0}, {2}}};
      break;
    case SHAPE_TORUS:
      s = (Shape){"torus R=1 r=0.35", torus_f, torus_label, torus_distance, {-1.6, -1.6, -0.6, 1.6, 1.6, 0.6},
                  1, {0, 2.0 * PI * PI * TORUS_R * TORUS_r * TORUS_r}, "analytic", {0, 1}, {{0}, {0}}};
      break;
    case SHAPE_TANGLECUBE: {
      static double volume = 0.0;
      if (volume == 0.0) volume = tanglecube_volume();
      s = (Shape){"tanglecube (genus 5)", tanglecube_f, tanglecube_label, tanglecube_distance,
                  {-2.5, -2.5, -2.5, 2.5, 2.5, 2.5}, 1, {0, volume}, "numerical integration", {0, 1}, {{0}, {-8}}};
      break;
    }
    case SHAPE_TWO_SPHERES:
      s = (Shape){"two disjoint spheres", two_spheres_f, two_spheres_label, two_spheres_distance,
                  {-1.6, -0.8, -0.8, 1.6, 0.8, 0.8}, 1, {0, 2.0 * ball * TWO_R * TWO_R * TWO_R}, "analytic",
                  {0, 2}, {{0}, {2, 2}}};
      break;
    case SHAPE_ELLIPSOID:
      s = (Shape){"thin ellipsoid (1, 0.6, 0.15)", ellipsoid_f, ellipsoid_label, ellipsoid_distance,
                  {-1.2, -0.8, -0.3, 1.2, 0.8, 0.3}, 1,
                  {0, ball * ellipsoid_axes[0] * ellipsoid_axes[1] * ellipsoid_axes[2]}, "analytic", {0, 1}, {{0}, {2}}};
      break;
    case SHAPE_NESTED_SPHERES:
      s = (Shape){"nested spheres (labels 1, 2)", NULL, nested_label, nested_distance, {-1.2, -1.2, -1.2, 1.2, 1.2, 1.2},
                  2, {0, ball * 0.125, ball * 0.875}, "analytic", {0, 1, 2}, {{0}, {2}, {2, 2}}};
      break;
    case SHAPE_SECTORS:
      s = (Shape){"three 120-degree sectors of the ball (labels 1, 2, 3)", NULL, sectors_label, sectors_distance,
                  {-1.2, -1.2, -1.2, 1.2, 1.2, 1.2}, 3, {0, ball / 3, ball / 3, ball / 3}, "analytic",
                  {0, 1, 1, 1}, {{0}, {2}, {2}, {2}}};
      break;
    case SHAPE_COUNT:
      break;
  }
  return s;
}

double shape_bbox_diagonal(const Shape *s) {
  double d[3] = {s->bbox[3] - s->bbox[0], s->bbox[4] - s->bbox[1], s->bbox[5] - s->bbox[2]};
  return norm3(d);
}

/* ---- Samples of the surface ----------------------------------------------------------------- */

static void at(const double o[3], const double d[3], double t, double p[3]) {
  for (int k = 0; k < 3; k++) p[k] = o[k] + t * d[k];
}

double *shape_surface_samples(const Shape *s, size_t lines, unsigned steps_per_diagonal,
                              uint64_t seed, size_t *count) {
  Prng g = prng_new(seed);
  double step = shape_bbox_diagonal(s) / steps_per_diagonal;
  size_t n = 0, capacity = 1024;
  double *xyz = malloc(capacity * 3 * sizeof *xyz);
  if (!xyz) return NULL;
  for (size_t line = 0; line < lines; line++) {
    double o[3], d[3], r2;
    for (int k = 0; k < 3; k++) o[k] = s->bbox[k] + prng_uniform(&g) * (s->bbox[k + 3] - s->bbox[k]);
    do { /* uniform direction */
      for (int k = 0; k < 3; k++) d[k] = 2.0 * prng_uniform(&g) - 1.0;
      r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (r2 > 1.0 || r2 < 1e-6);
    for (int k = 0; k < 3; k++) d[k] /= sqrt(r2);
    /* The line's parameter range inside the box. */
    double t0 = -INFINITY, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
      if (d[k] == 0) continue;
      double a = (s->bbox[k] - o[k]) / d[k], b = (s->bbox[k + 3] - o[k]) / d[k];
      t0 = fmax(t0, fmin(a, b));
      t1 = fmin(t1, fmax(a, b));
    }
    double p[3];
    at(o, d, t0, p);
    int32_t previous = s->label(p, NULL);
    for (double t = t0 + step, last = t0; last < t1; last = t, t += step) {
      if (t > t1) t = t1;
      at(o, d, t, p);
      int32_t label = s->label(p, NULL);
      if (label != previous) {
        double lo = last, hi = t; /* label(lo) = previous, label(hi) = label */
        for (int it = 0; it < 200; it++) {
          double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi) break;
          at(o, d, mid, p);
          if (s->label(p, NULL) == previous) lo = mid; else hi = mid;
        }
        if (n == capacity) {
          double *grown = realloc(xyz, 2 * capacity * 3 * sizeof *xyz);
          if (!grown) {
            free(xyz);
            return NULL;
          }
          xyz = grown;
          capacity *= 2;
        }
        at(o, d, 0.5 * (lo + hi), xyz + 3 * n++);
        previous = label;
      }
    }
  }
  *count = n;
  return xyz;
}
