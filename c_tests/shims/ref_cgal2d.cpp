// CGAL planar references for the C tests (interface in ref_cgal2d.h). One translation unit:
// CGAL headers are slow to compile.
//
// Kernel: Epick (exact predicates, inexact constructions), as for the 3D references; the
// points CGAL adds on constrained edges are rounded, as delmesh's are.
#include "ref_cgal2d.h"
#include "ref_internal.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_conformer_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <utility>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_2<K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
// Crossing constraints allowed: their intersection points become vertices.
using CrossingCdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Every finite edge is locally Delaunay: the vertex opposite across it is not strictly inside
// the circumcircle of the face (constrained edges included, which is what conforming means).
template <class T>
bool is_delaunay(const T &cdt) {
  for (auto f : cdt.finite_face_handles()) {
    for (int i = 0; i < 3; ++i) {
      auto g = f->neighbor(i);
      if (cdt.is_infinite(g)) continue;
      auto v = g->vertex(g->index(f));
      if (cdt.side_of_oriented_circle(f, v->point()) == CGAL::ON_POSITIVE_SIDE) return false;
    }
  }
  return true;
}

// Pebay's degradation alpha h / r of the triangle abc.
double degradation(const K::Point_2 &a, const K::Point_2 &b, const K::Point_2 &c) {
  double x = std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b)));
  double y = std::sqrt(CGAL::to_double(CGAL::squared_distance(b, c)));
  double z = std::sqrt(CGAL::to_double(CGAL::squared_distance(c, a)));
  double area = std::abs(CGAL::to_double(CGAL::area(a, b, c)));
  return std::sqrt(3.0) / 6.0 * std::max(x, std::max(y, z)) * (x + y + z) / (2.0 * area);
}

// The conforming Delaunay triangulation of the points and segments in a T (Cdt or
// CrossingCdt), its figures written to *out.
template <class T>
int conforming_2d(const double *xy, size_t n, const uint32_t *segments, size_t n_segments,
                  RefConforming2d *out, RefTiming *timing) {
  try {
    ref::Stopwatch clock;
    T cdt;
    std::vector<typename T::Vertex_handle> handles;
    handles.reserve(n);
    for (size_t i = 0; i < n; ++i) handles.push_back(cdt.insert(K::Point_2(xy[2 * i], xy[2 * i + 1])));
    size_t points = cdt.number_of_vertices();
    for (size_t k = 0; k < n_segments; ++k) {
      uint32_t a = segments[2 * k], b = segments[2 * k + 1];
      if (a >= n || b >= n) return ref::fail("segment index out of range");
      if (handles[a] != handles[b]) cdt.insert_constraint(handles[a], handles[b]);
    }
    out->intersection_count = cdt.number_of_vertices() - points;
    CGAL::make_conforming_Delaunay_2(cdt);
    size_t constrained = 0;
    for (auto e : cdt.finite_edges()) {
      if (cdt.is_constrained(e)) ++constrained;
    }
    if (timing) timing->seconds = clock.seconds();
    out->vertex_count = cdt.number_of_vertices();
    out->constrained_edge_count = constrained;
    out->valid = cdt.is_valid() && is_delaunay(cdt);
    out->worst_degradation = out->mean_degradation = 0;
    size_t faces = 0;
    for (auto f : cdt.finite_face_handles()) {
      double d = degradation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
      out->worst_degradation = std::max(out->worst_degradation, d);
      out->mean_degradation += d;
      ++faces;
    }
    if (faces) out->mean_degradation /= static_cast<double>(faces);
    return 0;
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("unknown C++ exception");
  }
}

}  // namespace

extern "C" int ref_cgal_conforming_2d(const double *xy, size_t n, const uint32_t *segments,
                                      size_t n_segments, RefConforming2d *out,
                                      RefTiming *timing) {
  return conforming_2d<Cdt>(xy, n, segments, n_segments, out, timing);
}

extern "C" int ref_cgal_conforming_2d_crossing(const double *xy, size_t n, const uint32_t *segments,
                                               size_t n_segments, RefConforming2d *out) {
  return conforming_2d<CrossingCdt>(xy, n, segments, n_segments, out, NULL);
}

namespace {

K::Point_2 point2(const double p[2]) { return K::Point_2(p[0], p[1]); }

using MeshVb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using MeshFb = CGAL::Delaunay_mesh_face_base_2<K>;
using MeshTds = CGAL::Triangulation_data_structure_2<MeshVb, MeshFb>;
using MeshCdt = CGAL::Constrained_Delaunay_triangulation_2<K, MeshTds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<MeshCdt>;

// The smallest angle of a triangle, in degrees (law of cosines at the shortest edge).
double smallest_angle(const K::Point_2 &a, const K::Point_2 &b, const K::Point_2 &c) {
  double l[3] = {CGAL::to_double(CGAL::squared_distance(b, c)),
                 CGAL::to_double(CGAL::squared_distance(c, a)),
                 CGAL::to_double(CGAL::squared_distance(a, b))};
  int k = static_cast<int>(std::min_element(l, l + 3) - l);
  double x = l[(k + 1) % 3], y = l[(k + 2) % 3];
  double cosine = std::max(-1.0, std::min(1.0, (x + y - l[k]) / (2.0 * std::sqrt(x * y))));
  return std::acos(cosine) * 180.0 / 3.14159265358979323846;
}

}  // namespace

extern "C" int ref_cgal_mesh_2d(const double *xy, size_t n, const uint32_t *segments,
                                size_t n_segments, const double *holes, size_t n_holes,
                                double min_angle_degrees, RefMesh2d *out, RefTiming *timing) {
  try {
    ref::Stopwatch clock;
    MeshCdt cdt;
    std::vector<MeshCdt::Vertex_handle> handles;
    handles.reserve(n);
    for (size_t i = 0; i < n; ++i) handles.push_back(cdt.insert(point2(&xy[2 * i])));
    for (size_t k = 0; k < n_segments; ++k) {
      uint32_t a = segments[2 * k], b = segments[2 * k + 1];
      if (a >= n || b >= n) return ref::fail("segment index out of range");
      if (handles[a] != handles[b]) cdt.insert_constraint(handles[a], handles[b]);
    }
    std::vector<K::Point_2> seeds;
    for (size_t h = 0; h < n_holes; ++h) seeds.push_back(point2(&holes[2 * h]));
    double s = std::sin(min_angle_degrees * 3.14159265358979323846 / 180.0);
    CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(s * s, 0.0), false);
    if (timing) timing->seconds = clock.seconds();
    out->vertex_count = cdt.number_of_vertices();
    out->triangle_count = 0;
    out->min_angle_degrees = 180.0;
    out->below_bound = 0;
    for (auto f : cdt.finite_face_handles()) {
      if (!f->is_in_domain()) continue;
      double angle = smallest_angle(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
      out->triangle_count++;
      out->min_angle_degrees = std::min(out->min_angle_degrees, angle);
      if (angle < min_angle_degrees) out->below_bound++;
    }
    return 0;
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("unknown C++ exception");
  }
}

extern "C" int ref_small_disk_side(const double a[2], const double b[2], const double q[2]) {
  switch (CGAL::side_of_bounded_circle(point2(a), point2(b), point2(q))) {
    case CGAL::ON_BOUNDED_SIDE: return 1;
    case CGAL::ON_BOUNDARY: return 0;
    default: return -1;
  }
}

extern "C" int ref_incircle_2(const double a[2], const double b[2], const double c[2],
                              const double d[2]) {
  return static_cast<int>(
      CGAL::side_of_oriented_circle(point2(a), point2(b), point2(c), point2(d)));
}

extern "C" int ref_orient_2(const double a[2], const double b[2], const double c[2]) {
  return static_cast<int>(CGAL::orientation(point2(a), point2(b), point2(c)));
}

namespace {

using InfoVb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using InfoTds = CGAL::Triangulation_data_structure_2<InfoVb>;
using Delaunay2 = CGAL::Delaunay_triangulation_2<K, InfoTds>;

}  // namespace

extern "C" int ref_cgal_delaunay_2d(const double *xy, size_t n, uint32_t **triangles,
                                    size_t *triangle_count, RefTiming *timing) {
  if (!xy || !triangles || !triangle_count) return ref::fail("ref_cgal_delaunay_2d: NULL argument");
  if (!ref::fits_u32(n)) return ref::fail("ref_cgal_delaunay_2d: too many points");
  try {
    ref::Stopwatch clock;
    std::vector<std::pair<K::Point_2, std::uint32_t>> input;
    input.reserve(n);
    for (size_t i = 0; i < n; ++i) input.emplace_back(point2(&xy[2 * i]), std::uint32_t(i));
    Delaunay2 dt(input.begin(), input.end());
    size_t count = dt.number_of_faces();
    uint32_t *out = static_cast<uint32_t *>(std::malloc(3 * (count ? count : 1) * sizeof(uint32_t)));
    if (!out) return ref::fail("out of memory");
    size_t k = 0;
    for (auto f : dt.finite_face_handles())
      for (int i = 0; i < 3; ++i) out[k++] = f->vertex(i)->info();
    if (timing) timing->seconds = clock.seconds();
    *triangles = out;
    *triangle_count = k / 3;
    return 0;  // dt is destroyed after the clock stopped
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_delaunay_2d: unknown exception");
  }
}
