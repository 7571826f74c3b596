// CGAL references for the C tests (interface and conventions in ref.h).
//
// Kernel: Epick (exact predicates, inexact constructions): every decision a triangulation takes
// is exact, and degenerate configurations are resolved by CGAL's symbolic perturbation, so the
// triangulation is a function of the point set. Requires -frounding-math.
#include "ref.h"
#include "ref_internal.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <utility>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Weighted_point = K::Weighted_point_3;

// Delaunay: vertex info = input index.
using DVb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
using DTds = CGAL::Triangulation_data_structure_3<DVb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, DTds>;

// Regular: vertex info = input index; hidden points are not stored in cells (we find them as
// the inputs that are not vertices).
using RVb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K,
                                                        CGAL::Regular_triangulation_vertex_base_3<K>>;
using RCb = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>,
                                                    CGAL::Discard_hidden_points>;
using RTds = CGAL::Triangulation_data_structure_3<RVb, RCb>;
using Regular = CGAL::Regular_triangulation_3<K, RTds>;

using Hull_mesh = CGAL::Surface_mesh<Point>;

Point point_at(const double *xyz, std::size_t i) {
  return Point(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

template <class Triangulation>
int export_finite_cells(const Triangulation &tr, uint32_t **tets, std::size_t *tet_count) {
  std::size_t count = tr.dimension() == 3 ? tr.number_of_finite_cells() : 0;
  uint32_t *out = static_cast<uint32_t *>(std::malloc((count ? count : 1) * 4 * sizeof(uint32_t)));
  if (!out) return ref::fail("out of memory");
  std::size_t k = 0;
  if (count) {
    for (auto c : tr.finite_cell_handles()) {
      for (int i = 0; i < 4; ++i) out[4 * k + i] = c->vertex(i)->info();
      ++k;
    }
  }
  *tets = out;
  *tet_count = k;
  return 0;
}

}  // namespace

extern "C" int ref_orient3d_exact(const double a[3], const double b[3], const double c[3],
                                  const double d[3]) {
  // CGAL::orientation(p, q, r, s) is the sign of det[q-p; r-p; s-p] = dot(q-p, cross(r-p, s-p)).
  CGAL::Orientation o = CGAL::orientation(Point(a[0], a[1], a[2]), Point(b[0], b[1], b[2]),
                                          Point(c[0], c[1], c[2]), Point(d[0], d[1], d[2]));
  return o == CGAL::POSITIVE ? 1 : (o == CGAL::NEGATIVE ? -1 : 0);
}

extern "C" int ref_cgal_delaunay(const double *xyz, size_t n, uint32_t **tets, size_t *tet_count,
                                 RefTiming *timing) {
  if (!xyz || !tets || !tet_count) return ref::fail("ref_cgal_delaunay: NULL argument");
  if (!ref::fits_u32(n)) return ref::fail("ref_cgal_delaunay: too many points");
  try {
    ref::Stopwatch clock;
    std::vector<std::pair<Point, std::uint32_t>> input;
    input.reserve(n);
    for (std::size_t i = 0; i < n; ++i) input.emplace_back(point_at(xyz, i), std::uint32_t(i));
    Delaunay dt(input.begin(), input.end());
    int rc = export_finite_cells(dt, tets, tet_count);
    if (timing) timing->seconds = clock.seconds();
    return rc;  // dt is destroyed after the clock stopped
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_delaunay: unknown exception");
  }
}

extern "C" int ref_cgal_regular(const double *xyz, const double *weights, size_t n, uint32_t **tets,
                                size_t *tet_count, unsigned char **hidden, RefTiming *timing) {
  if (!xyz || !weights || !tets || !tet_count || !hidden)
    return ref::fail("ref_cgal_regular: NULL argument");
  if (!ref::fits_u32(n)) return ref::fail("ref_cgal_regular: too many points");
  try {
    ref::Stopwatch clock;
    std::vector<std::pair<Weighted_point, std::uint32_t>> input;
    input.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      input.emplace_back(Weighted_point(point_at(xyz, i), weights[i]), std::uint32_t(i));
    Regular rt;
    rt.insert(input.begin(), input.end());
    unsigned char *flags = static_cast<unsigned char *>(std::malloc(n ? n : 1));
    if (!flags) return ref::fail("out of memory");
    std::memset(flags, 1, n);
    for (auto v : rt.finite_vertex_handles()) flags[v->info()] = 0;
    if (export_finite_cells(rt, tets, tet_count) != 0) {
      std::free(flags);
      return -1;
    }
    *hidden = flags;
    if (timing) timing->seconds = clock.seconds();
    return 0;
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_regular: unknown exception");
  }
}

extern "C" int ref_cgal_convex_hull(const double *xyz, size_t n, uint32_t **triangles,
                                    size_t *triangle_count) {
  if (!xyz || !triangles || !triangle_count) return ref::fail("ref_cgal_convex_hull: NULL argument");
  if (!ref::fits_u32(n)) return ref::fail("ref_cgal_convex_hull: too many points");
  try {
    // The distinct points, each named by its first occurrence.
    std::vector<Point> input;
    input.reserve(n);
    std::map<std::array<double, 3>, std::uint32_t> index_of;
    for (std::size_t i = 0; i < n; ++i) {
      if (index_of.emplace(std::array<double, 3>{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]},
                           std::uint32_t(i)).second)
        input.push_back(point_at(xyz, i));
    }
    // Output into a Surface_mesh: that overload uses CGAL's filtered convex-hull traits (exact
    // plane-side tests). The (points, faces) overload of CGAL 5.5 uses the bare kernel, whose
    // planes are rounded constructions with Epick: on inputs with many coplanar points it was
    // seen to return a wrong hull (fandisk.off: volume off by 5e-4).
    Hull_mesh hull;
    CGAL::convex_hull_3(input.begin(), input.end(), hull);
    std::size_t count = hull.number_of_faces();
    uint32_t *out = static_cast<uint32_t *>(std::malloc((count ? count : 1) * 3 * sizeof(uint32_t)));
    if (!out) return ref::fail("out of memory");
    std::size_t f = 0;
    for (auto face : hull.faces()) {
      int k = 0;
      for (auto v : CGAL::vertices_around_face(hull.halfedge(face), hull)) {
        const Point &p = hull.point(v);
        auto it = index_of.find({p.x(), p.y(), p.z()});
        if (k == 3 || it == index_of.end()) {
          std::free(out);
          return ref::fail(k == 3 ? "ref_cgal_convex_hull: a hull face is not a triangle"
                                  : "ref_cgal_convex_hull: a hull vertex is not an input point");
        }
        out[3 * f + k++] = it->second;
      }
      if (k != 3) {
        std::free(out);
        return ref::fail("ref_cgal_convex_hull: a hull face is not a triangle");
      }
      ++f;
    }
    *triangles = out;
    *triangle_count = f;
    return 0;
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_convex_hull: unknown exception");
  }
}
