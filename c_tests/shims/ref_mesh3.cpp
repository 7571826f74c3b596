// CGAL Mesh_3 reference for the C tests (interface and conventions in ref_mesh3.h).
//
// One domain type, CGAL::Labeled_mesh_domain_3<Epick>, serves both entry points (implicit
// functions go through CGAL's create_implicit_mesh_domain, which labels f < 0 as 1), so the
// mesher is instantiated once: Mesh_3 is slow to compile.
//
// Initial points. make_mesh_3 seeds the triangulation with the domain's Construct_initial_points:
// segments from the box center (or, after a miss, a random point) to the bounding sphere, kept
// when the labels at their two ends differ. A segment whose ends are both outside misses every
// surface it crosses twice, so CGAL 5.5 meshes one of two disjoint spheres only, and one of two
// nested spheres. The shim therefore does what make_mesh_3 does (init_c3t3, then refine_mesh_3)
// with segments between two random points of the box instead, each crossing found by the
// domain's own Do_intersect_surface / Construct_intersection.
//
// Optimization (ref_cgal_mesh_*_optimized): refine_mesh_3's perturb()/exude() options, or the same
// two calls refine_mesh_3 makes (perturb_mesh_3, then exude_mesh_3) made here one by one, timed.
#include "ref_mesh3.h"
#include "ref_internal.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_optimization_return_code.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <unordered_map>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

// The C callbacks as CGAL functions of a point.
struct Implicit {
  RefImplicitFn f;
  void *user_data;
  K::FT operator()(const Point &p) const {
    const double q[3] = {p.x(), p.y(), p.z()};
    return f(q, user_data);
  }
};

struct Labeling {
  RefLabelFn f;
  void *user_data;
  int operator()(const Point &p) const {
    const double q[3] = {p.x(), p.y(), p.z()};
    return static_cast<int>(f(q, user_data));
  }
};

double criterion(double value) { return value > 0 ? value : 0.0; }  // CGAL: 0 = not set

// The cells of the complex, their used vertices compactly numbered.
int export_complex(const C3t3 &c3t3, RefMesh *out) {
  const Tr &tr = c3t3.triangulation();
  auto bare = tr.geom_traits().construct_point_3_object();
  std::size_t cell_count = c3t3.number_of_cells_in_complex();
  if (!ref::fits_u32(4 * cell_count)) return ref::fail("ref_mesh3: too many cells");
  std::unordered_map<Tr::Vertex_handle, std::uint32_t> index_of;
  std::vector<Tr::Vertex_handle> vertices;
  std::vector<std::uint32_t> tets;
  std::vector<std::int32_t> labels;
  tets.reserve(4 * cell_count);
  labels.reserve(cell_count);
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    std::uint32_t q[4];
    for (int i = 0; i < 4; ++i) {
      auto v = c->vertex(i);
      auto it = index_of.emplace(v, static_cast<std::uint32_t>(vertices.size())).first;
      if (it->second == vertices.size()) vertices.push_back(v);
      q[i] = it->second;
    }
    // CGAL's cells are positively oriented in the sense of CGAL::orientation, which is
    // delmesh's convention; checked, and swapped if ever not.
    if (CGAL::orientation(bare(tr.point(c, 0)), bare(tr.point(c, 1)), bare(tr.point(c, 2)),
                          bare(tr.point(c, 3))) == CGAL::NEGATIVE)
      std::swap(q[2], q[3]);
    tets.insert(tets.end(), q, q + 4);
    labels.push_back(static_cast<std::int32_t>(c3t3.subdomain_index(c)));
  }

  std::size_t n = vertices.size(), m = labels.size();
  RefMesh r{};
  r.xyz = static_cast<double *>(std::malloc((n ? n : 1) * 3 * sizeof(double)));
  r.dimensions = static_cast<std::int8_t *>(std::malloc(n ? n : 1));
  r.tets = static_cast<std::uint32_t *>(std::malloc((m ? m : 1) * 4 * sizeof(std::uint32_t)));
  r.labels = static_cast<std::int32_t *>(std::malloc((m ? m : 1) * sizeof(std::int32_t)));
  if (!r.xyz || !r.dimensions || !r.tets || !r.labels) {
    ref_mesh_free(&r);
    return ref::fail("out of memory");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = bare(tr.point(vertices[i]));
    r.xyz[3 * i] = p.x();
    r.xyz[3 * i + 1] = p.y();
    r.xyz[3 * i + 2] = p.z();
    r.dimensions[i] = static_cast<std::int8_t>(c3t3.in_dimension(vertices[i]));
  }
  std::copy(tets.begin(), tets.end(), r.tets);
  std::copy(labels.begin(), labels.end(), r.labels);
  r.vertex_count = n;
  r.tet_count = m;
  *out = r;
  return 0;
}

// Surface points where random segments across the box cross a label change (the first crossing
// from the segment's source); inserted with dimension 2 and their surface index, as init_c3t3 does.
void insert_initial_points(const Domain &domain, C3t3 &c3t3) {
  const int wanted = 24, tries = 100000;
  CGAL::Random rng(0);
  const CGAL::Bbox_3 b = domain.bbox();
  auto random_point = [&]() {
    return Point(rng.get_double(b.xmin(), b.xmax()), rng.get_double(b.ymin(), b.ymax()),
                 rng.get_double(b.zmin(), b.zmax()));
  };
  auto do_intersect = domain.do_intersect_surface_object();
  auto intersection = domain.construct_intersection_object();
  auto weighted = c3t3.triangulation().geom_traits().construct_weighted_point_3_object();
  int found = 0;
  for (int i = 0; i < tries && found < wanted; ++i) {
    K::Segment_3 segment(random_point(), random_point());
    if (!do_intersect(segment)) continue;
    const auto crossing = intersection(segment);  // (point, index of its patch, dimension 2)
    if (std::get<2>(crossing) != 2) continue;
    Tr::Vertex_handle v = c3t3.triangulation().insert(weighted(std::get<0>(crossing)));
    if (v == Tr::Vertex_handle()) continue;
    c3t3.set_dimension(v, 2);
    c3t3.set_index(v, std::get<1>(crossing));
    ++found;
  }
}

// make_mesh_3 (init_c3t3 replaced, see above), optimized as `o` says.
int mesh(const Domain &domain, const RefMeshCriteria &c, const RefMeshOptions &o, RefMesh *out,
         const ref::Stopwatch &clock, RefMeshTiming *timing) {
  namespace params = CGAL::parameters;
  Criteria criteria(params::facet_angle = criterion(c.facet_angle),
                    params::facet_size = criterion(c.facet_size),
                    params::facet_distance = criterion(c.facet_distance),
                    params::cell_radius_edge_ratio = criterion(c.cell_radius_edge_ratio),
                    params::cell_size = criterion(c.cell_size));
  RefMeshTiming t{};
  t.perturb_code = t.exude_code = REF_OPTIMIZER_NOT_RUN;
  C3t3 c3t3;
  insert_initial_points(domain, c3t3);
  if (c3t3.triangulation().number_of_vertices() == 0)
    return ref::fail("ref_mesh3: no random segment across the box crosses the surface");
  RefMesh refined{};
  if (o.optimization == REF_OPTIMIZE_MESH_3) {
    // CGAL's defaults: no time_limit argument = the refinement's time (make_mesh_3's default).
    if (o.time_limit < 0)
      CGAL::refine_mesh_3(c3t3, domain, criteria, params::perturb(), params::exude());
    else
      CGAL::refine_mesh_3(c3t3, domain, criteria, params::perturb(params::time_limit = o.time_limit),
                          params::exude(params::time_limit = o.time_limit));
    t.perturb_code = t.exude_code = REF_OPTIMIZER_NOT_REPORTED;
  } else if (o.optimization == REF_OPTIMIZE_SEPARATE) {
    ref::Stopwatch refine_clock;
    CGAL::refine_mesh_3(c3t3, domain, criteria, params::no_perturb(), params::no_exude());
    t.refine_seconds = refine_clock.seconds();
    if (o.refined && export_complex(c3t3, &refined) != 0) return -1;
    // As refine_mesh_3_impl: perturb_mesh_3 then exude_mesh_3, sliver bounds at their defaults.
    double limit = o.time_limit < 0 ? t.refine_seconds : o.time_limit;
    ref::Stopwatch perturb_clock;
    t.perturb_code = static_cast<int>(CGAL::perturb_mesh_3(c3t3, domain, params::time_limit = limit));
    t.perturb_seconds = perturb_clock.seconds();
    ref::Stopwatch exude_clock;
    t.exude_code = static_cast<int>(CGAL::exude_mesh_3(c3t3, params::time_limit = limit));
    t.exude_seconds = exude_clock.seconds();
  } else {
    CGAL::refine_mesh_3(c3t3, domain, criteria, params::no_perturb(), params::no_exude());
  }
  int rc = export_complex(c3t3, out);
  t.seconds = clock.seconds();
  if (rc != 0) {
    ref_mesh_free(&refined);
    return rc;
  }
  if (o.refined) *o.refined = refined;
  if (timing) *timing = t;
  return 0;  // c3t3 is destroyed after the clock stopped
}

int check_options(const RefMeshOptions &o, const char *caller) {
  if (o.optimization < REF_OPTIMIZE_NONE || o.optimization > REF_OPTIMIZE_SEPARATE ||
      !(o.time_limit == o.time_limit))
    return ref::fail(caller);
  return 0;
}

CGAL::Bbox_3 box(const double b[6]) { return CGAL::Bbox_3(b[0], b[1], b[2], b[3], b[4], b[5]); }

}  // namespace

extern "C" int ref_cgal_mesh_implicit_optimized(RefImplicitFn f, void *user_data, const double bbox[6],
                                                double relative_error, const RefMeshCriteria *criteria,
                                                const RefMeshOptions *options, RefMesh *out,
                                                RefMeshTiming *timing) {
  if (!f || !bbox || !criteria || !out) return ref::fail("ref_cgal_mesh_implicit: NULL argument");
  const RefMeshOptions o = options ? *options : RefMeshOptions{};
  if (check_options(o, "ref_cgal_mesh_implicit: unknown optimization or NaN time limit") != 0) return -1;
  try {
    ref::Stopwatch clock;
    Domain domain = Domain::create_implicit_mesh_domain(
        Implicit{f, user_data}, box(bbox), CGAL::parameters::relative_error_bound = relative_error);
    return mesh(domain, *criteria, o, out, clock, timing);
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_mesh_implicit: unknown exception");
  }
}

extern "C" int ref_cgal_mesh_labeled_optimized(RefLabelFn f, void *user_data, const double bbox[6],
                                               double relative_error, const RefMeshCriteria *criteria,
                                               const RefMeshOptions *options, RefMesh *out,
                                               RefMeshTiming *timing) {
  if (!f || !bbox || !criteria || !out) return ref::fail("ref_cgal_mesh_labeled: NULL argument");
  const RefMeshOptions o = options ? *options : RefMeshOptions{};
  if (check_options(o, "ref_cgal_mesh_labeled: unknown optimization or NaN time limit") != 0) return -1;
  try {
    ref::Stopwatch clock;
    Domain domain(CGAL::parameters::function = Domain::Fct(Labeling{f, user_data}),
                  CGAL::parameters::bounding_object = box(bbox),
                  CGAL::parameters::relative_error_bound = relative_error);
    return mesh(domain, *criteria, o, out, clock, timing);
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (...) {
    return ref::fail("ref_cgal_mesh_labeled: unknown exception");
  }
}

extern "C" int ref_cgal_mesh_implicit(RefImplicitFn f, void *user_data, const double bbox[6],
                                      double relative_error, const RefMeshCriteria *criteria,
                                      RefMesh *out, RefTiming *timing) {
  RefMeshTiming t{};
  int rc = ref_cgal_mesh_implicit_optimized(f, user_data, bbox, relative_error, criteria, nullptr, out, &t);
  if (rc == 0 && timing) timing->seconds = t.seconds;
  return rc;
}

extern "C" int ref_cgal_mesh_labeled(RefLabelFn f, void *user_data, const double bbox[6],
                                     double relative_error, const RefMeshCriteria *criteria,
                                     RefMesh *out, RefTiming *timing) {
  RefMeshTiming t{};
  int rc = ref_cgal_mesh_labeled_optimized(f, user_data, bbox, relative_error, criteria, nullptr, out, &t);
  if (rc == 0 && timing) timing->seconds = t.seconds;
  return rc;
}

extern "C" const char *ref_optimizer_code_name(int code) {
  switch (code) {
    case REF_OPTIMIZER_NOT_RUN: return "not run";
    case REF_OPTIMIZER_NOT_REPORTED: return "not reported by make_mesh_3";
    case CGAL::BOUND_REACHED: return "bound reached";
    case CGAL::TIME_LIMIT_REACHED: return "time limit reached";
    case CGAL::CANT_IMPROVE_ANYMORE: return "can't improve anymore";
    case CGAL::CONVERGENCE_REACHED: return "convergence reached";
    case CGAL::MAX_ITERATION_NUMBER_REACHED: return "max iteration number reached";
    case CGAL::ALL_VERTICES_FROZEN: return "all vertices frozen";
    default: return "unknown error";
  }
}

extern "C" void ref_mesh_free(RefMesh *mesh) {
  if (!mesh) return;
  std::free(mesh->xyz);
  std::free(mesh->dimensions);
  std::free(mesh->tets);
  std::free(mesh->labels);
  *mesh = RefMesh{};
}
