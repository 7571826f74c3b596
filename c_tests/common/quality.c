#include "quality.h"

#include <math.h>
#include <stdio.h>

const double quality_dihedral_thresholds[QUALITY_DIHEDRAL_THRESHOLDS] = {5.0, 10.0, 15.0};

static const double DEGREES = 180.0 / 3.14159265358979323846;

static void sub(const double a[3], const double b[3], double out[3]) {
  for (int k = 0; k < 3; k++) out[k] = a[k] - b[k];
}

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm(const double a[3]) { return sqrt(dot(a, a)); }

/* The angle between two vectors in radians, accurate near 0 and pi (atan2 of |u×v| and u·v). */
static double angle_between(const double u[3], const double v[3]) {
  double w[3];
  cross(u, v, w);
  return atan2(norm(w), dot(u, v));
}

TetQuality quality_tetrahedron(const double a[3], const double b[3], const double c[3],
                               const double d[3]) {
  const double *p[4] = {a, b, c, d};
  /* Facet k is the one opposite vertex k, listed so that its normal points outward when
   * (a, b, c, d) is positively oriented (metrics.h): (b,c,d), (a,d,c), (a,b,d), (a,c,b). */
  static const int facet[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  double normal[4][3], area2[4]; /* unnormalized normals, twice the areas */
  for (int k = 0; k < 4; k++) {
    double u[3], v[3];
    sub(p[facet[k][1]], p[facet[k][0]], u);
    sub(p[facet[k][2]], p[facet[k][0]], v);
    cross(u, v, normal[k]);
    area2[k] = norm(normal[k]);
  }

  TetQuality q;
  /* The edge between vertices i and j is shared by the facets opposite the two other vertices
   * k and l; the dihedral angle there is pi minus the angle between their outward normals. */
  q.min_dihedral = INFINITY;
  q.max_dihedral = -INFINITY;
  q.shortest_edge = INFINITY;
  for (int i = 0; i < 4; i++) {
    for (int j = i + 1; j < 4; j++) {
      int k = -1, l = -1;
      for (int m = 0; m < 4; m++) {
        if (m == i || m == j) continue;
        if (k < 0)
          k = m;
        else
          l = m;
      }
      double dihedral = (3.14159265358979323846 - angle_between(normal[k], normal[l])) * DEGREES;
      if (dihedral < q.min_dihedral) q.min_dihedral = dihedral;
      if (dihedral > q.max_dihedral) q.max_dihedral = dihedral;
      double e[3];
      sub(p[j], p[i], e);
      double length = norm(e);
      if (length < q.shortest_edge) q.shortest_edge = length;
    }
  }

  /* Circumcenter relative to a: (|u|²(v×w) + |v|²(w×u) + |w|²(u×v)) / (2 det). */
  double u[3], v[3], w[3], vw[3], wu[3], uv[3];
  sub(b, a, u);
  sub(c, a, v);
  sub(d, a, w);
  cross(v, w, vw);
  cross(w, u, wu);
  cross(u, v, uv);
  double det = dot(u, vw); /* 6 × signed volume */
  double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
  double center[3];
  for (int m = 0; m < 3; m++) center[m] = (uu * vw[m] + vv * wu[m] + ww * uv[m]) / (2.0 * det);
  double total_area2 = area2[0] + area2[1] + area2[2] + area2[3];
  if (det == 0.0 || !isfinite(center[0] + center[1] + center[2]) || total_area2 == 0.0) {
    q.circumradius = INFINITY;
    q.radius_edge = INFINITY;
    q.radius_ratio = 0.0;
    q.min_dihedral = 0.0;
    q.max_dihedral = 180.0;
    return q;
  }
  q.circumradius = norm(center);
  q.radius_edge = q.circumradius / q.shortest_edge;
  /* r_in = 3 V / (total facet area) = |det| / (sum of twice the facet areas). */
  double inradius = fabs(det) / total_area2;
  q.radius_ratio = 3.0 * inradius / q.circumradius;
  return q;
}

QualitySummary quality_tetrahedra(const double *xyz, const uint32_t *tets, size_t count) {
  QualitySummary s = {0};
  s.tetrahedra = count;
  s.worst_dihedral = s.worst_radius_edge = -1;
  if (count == 0) {
    s.min_dihedral = s.max_dihedral = s.max_radius_edge = NAN;
    s.min_radius_ratio = s.mean_radius_ratio = s.max_circumradius = NAN;
    return s;
  }
  s.min_dihedral = s.min_radius_ratio = INFINITY;
  s.max_dihedral = s.max_radius_edge = s.max_circumradius = -INFINITY;
  double ratio_sum = 0.0;
  for (size_t t = 0; t < count; t++) {
    const uint32_t *v = tets + 4 * t;
    TetQuality q = quality_tetrahedron(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1],
                                       xyz + 3 * (size_t)v[2], xyz + 3 * (size_t)v[3]);
    if (q.min_dihedral < s.min_dihedral) {
      s.min_dihedral = q.min_dihedral;
      s.worst_dihedral = (long)t;
    }
    if (q.max_dihedral > s.max_dihedral) s.max_dihedral = q.max_dihedral;
    if (q.radius_edge > s.max_radius_edge) {
      s.max_radius_edge = q.radius_edge;
      s.worst_radius_edge = (long)t;
    }
    if (q.radius_ratio < s.min_radius_ratio) s.min_radius_ratio = q.radius_ratio;
    if (q.circumradius > s.max_circumradius) s.max_circumradius = q.circumradius;
    ratio_sum += q.radius_ratio;
    for (int k = 0; k < QUALITY_DIHEDRAL_THRESHOLDS; k++)
      s.dihedral_below[k] += q.min_dihedral < quality_dihedral_thresholds[k];
    int bin = (int)(q.radius_ratio * QUALITY_HISTOGRAM_BINS);
    if (bin < 0) bin = 0;
    if (bin >= QUALITY_HISTOGRAM_BINS) bin = QUALITY_HISTOGRAM_BINS - 1;
    s.radius_ratio_histogram[bin]++;
  }
  s.mean_radius_ratio = ratio_sum / (double)count;
  return s;
}

double quality_triangle_min_angle(const double a[3], const double b[3], const double c[3]) {
  const double *p[3] = {a, b, c};
  double smallest = INFINITY;
  for (int k = 0; k < 3; k++) {
    double u[3], v[3];
    sub(p[(k + 1) % 3], p[k], u);
    sub(p[(k + 2) % 3], p[k], v);
    if (dot(u, u) == 0.0 || dot(v, v) == 0.0) return 0.0;
    double angle = angle_between(u, v) * DEGREES;
    if (angle < smallest) smallest = angle;
  }
  return smallest;
}

double quality_triangles_min_angle(const double *xyz, const uint32_t *triangles, size_t count) {
  double smallest = count ? INFINITY : NAN;
  for (size_t t = 0; t < count; t++) {
    const uint32_t *v = triangles + 3 * t;
    double angle = quality_triangle_min_angle(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1],
                                              xyz + 3 * (size_t)v[2]);
    if (angle < smallest) smallest = angle;
  }
  return smallest;
}

void quality_print(const QualitySummary *q, const char *indent) {
  printf("%sdihedral angles:   min %.2f, max %.2f degrees\n", indent, q->min_dihedral,
         q->max_dihedral);
  printf("%sradius-edge ratio: max %.4f\n", indent, q->max_radius_edge);
  printf("%sradius ratio:      min %.4f, mean %.4f (3 r_in / r_circ, 1 = regular)\n", indent,
         q->min_radius_ratio, q->mean_radius_ratio);
  printf("%sdihedral below", indent);
  for (int k = 0; k < QUALITY_DIHEDRAL_THRESHOLDS; k++)
    printf("%s %g deg: %zu (%.3f%%)", k ? "," : "", quality_dihedral_thresholds[k],
           q->dihedral_below[k],
           q->tetrahedra ? 100.0 * (double)q->dihedral_below[k] / (double)q->tetrahedra : 0.0);
  printf("\n%sradius ratio histogram (bins of 0.1 from 0 to 1):", indent);
  for (int k = 0; k < QUALITY_HISTOGRAM_BINS; k++) printf(" %zu", q->radius_ratio_histogram[k]);
  printf("\n");
}
