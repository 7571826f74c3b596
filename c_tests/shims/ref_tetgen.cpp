// TetGen reference for the C tests (interface and conventions in ref.h).
#include "ref.h"
#include "ref_internal.hpp"

#define TETLIBRARY
#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <set>
#include <string>
#include <vector>

extern "C" int ref_tetgen_delaunay(const double *xyz, size_t n, uint32_t **tets, size_t *tet_count,
                                   RefTiming *timing) {
  if (!xyz || !tets || !tet_count) return ref::fail("ref_tetgen_delaunay: NULL argument");
  if (n > 0x7fffffff) return ref::fail("ref_tetgen_delaunay: too many points for TetGen");
  try {
    ref::Stopwatch clock;
    tetgenio in, out;  // their destructors release the lists with delete[]
    in.firstnumber = 0;
    in.numberofpoints = int(n);
    in.pointlist = new REAL[3 * (n ? n : 1)];
    for (std::size_t i = 0; i < 3 * n; ++i) in.pointlist[i] = xyz[i];
    // Q: quiet; z: 0-based output; J: keep unused (duplicate) points so that indices stay the
    // input indices. No p: the input is a bare point set, the output its Delaunay tetrahedralization.
    char switches[] = "QzJ";
    tetrahedralize(switches, &in, &out);
    if (out.numberofpoints != int(n))
      return ref::fail("ref_tetgen_delaunay: TetGen renumbered the points");
    if (out.numberofcorners != 4) return ref::fail("ref_tetgen_delaunay: unexpected element order");
    std::size_t count = std::size_t(out.numberoftetrahedra);
    uint32_t *result = static_cast<uint32_t *>(std::malloc((count ? count : 1) * 4 * sizeof(uint32_t)));
    if (!result) return ref::fail("out of memory");
    for (std::size_t k = 0; k < 4 * count; ++k) {
      int v = out.tetrahedronlist[k];
      if (v < 0 || std::size_t(v) >= n) {
        std::free(result);
        return ref::fail("ref_tetgen_delaunay: TetGen returned an index out of range");
      }
      result[k] = uint32_t(v);
    }
    *tets = result;
    *tet_count = count;
    if (timing) timing->seconds = clock.seconds();
    return 0;  // in/out are released after the clock stopped
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (int code) {
    // TetGen reports errors by throwing an int (terminatetetgen).
    char message[64];
    std::snprintf(message, sizeof message, "ref_tetgen_delaunay: TetGen failed with code %d", code);
    return ref::fail(message);
  } catch (...) {
    return ref::fail("ref_tetgen_delaunay: unknown exception");
  }
}

// ---- Surfaces ---------------------------------------------------------------------------------

extern "C" void ref_surface_mesh_free(RefSurfaceMesh *m) {
  if (!m) return;
  std::free(m->xyz);
  std::free(m->tets);
  std::free(m->labels);
  *m = RefSurfaceMesh{};
}

namespace {

// Facet f is the polygon corners[begin(f) .. begin(f+1)): offsets when given, else triangles.
struct Facets {
  const uint32_t *corners;
  const size_t *offsets;  // NULL: every facet a triangle
  size_t count;
  size_t begin(size_t f) const { return offsets ? offsets[f] : 3 * f; }
};

// TetGen 1.5.0 leaves attribute 0 on the tetrahedra it creates when it suppresses boundary
// Steiner points (-Y), which happens after it spread the region attributes. Each such
// tetrahedron gets the attribute of its region instead: the one found across faces that are not
// TetGen's boundary faces (its trifacelist, the triangulated facets). A region with no
// attributed tetrahedron keeps 0.
void repair_labels(const tetgenio &result, const uint32_t *tets, int32_t *labels, std::size_t count,
                   const std::vector<uint32_t> &renumber) {
  bool any = false;
  for (std::size_t t = 0; t < count && !any; ++t) any = labels[t] == 0;
  if (!any) return;
  using Key = std::array<uint32_t, 3>;
  auto key = [](uint32_t a, uint32_t b, uint32_t c) {
    Key k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::set<Key> boundary;
  for (int f = 0; f < result.numberoftrifaces; ++f) {
    const int *v = result.trifacelist + 3 * f;
    boundary.insert(key(renumber[std::size_t(v[0])], renumber[std::size_t(v[1])], renumber[std::size_t(v[2])]));
  }
  std::map<Key, std::vector<std::size_t>> faces;
  for (std::size_t t = 0; t < count; ++t) {
    const uint32_t *q = tets + 4 * t;
    for (int k = 0; k < 4; ++k) {
      Key f = key(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]);
      if (!boundary.count(f)) faces[f].push_back(t);
    }
  }
  std::vector<std::size_t> queue;
  for (std::size_t t = 0; t < count; ++t)
    if (labels[t] != 0) queue.push_back(t);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    std::size_t t = queue[head];
    const uint32_t *q = tets + 4 * t;
    for (int k = 0; k < 4; ++k) {
      auto it = faces.find(key(q[(k + 1) % 4], q[(k + 2) % 4], q[(k + 3) % 4]));
      if (it == faces.end()) continue;
      for (std::size_t u : it->second)
        if (labels[u] == 0) {
          labels[u] = labels[t];
          queue.push_back(u);
        }
    }
  }
}

int tetgen_plc(const char *who, const double *xyz, size_t n, const Facets &facets,
               const double *regions, size_t n_regions, const double *holes, size_t n_holes,
               const char *switches, RefSurfaceMesh *out, RefTiming *timing) {
  char message[160];
  if (!xyz || !facets.corners || !switches || !out || (n_regions && !regions) || (n_holes && !holes)) {
    std::snprintf(message, sizeof message, "%s: NULL argument", who);
    return ref::fail(message);
  }
  if (n > 0x7fffffff || facets.count > 0x7fffffff || n_regions > 0x7fffffff || n_holes > 0x7fffffff) {
    std::snprintf(message, sizeof message, "%s: input too large for TetGen", who);
    return ref::fail(message);
  }
  for (size_t f = 0; f < facets.count; ++f) {
    if (facets.begin(f + 1) < facets.begin(f) + 3) {
      std::snprintf(message, sizeof message, "%s: facet %zu has fewer than 3 corners", who, f);
      return ref::fail(message);
    }
    for (size_t k = facets.begin(f); k < facets.begin(f + 1); ++k)
      if (facets.corners[k] >= n) {
        std::snprintf(message, sizeof message, "%s: facet %zu names point %u of %zu", who, f,
                      unsigned(facets.corners[k]), n);
        return ref::fail(message);
      }
  }
  // z: 0-based output; J: no point is jettisoned, so output point i < n is input point i; A:
  // region attributes. a (no number) when a region carries a volume bound.
  std::string all = "zJA";
  for (size_t r = 0; r < n_regions; ++r)
    if (regions[5 * r + 4] > 0) {
      all += 'a';
      break;
    }
  all += switches;
  std::vector<char> sw(all.begin(), all.end());
  sw.push_back('\0');
  try {
    ref::Stopwatch clock;
    tetgenio in, result;  // their destructors release the lists with delete[]
    in.firstnumber = 0;
    in.numberofpoints = int(n);
    in.pointlist = new REAL[3 * (n ? n : 1)];
    for (std::size_t i = 0; i < 3 * n; ++i) in.pointlist[i] = xyz[i];
    in.numberoffacets = int(facets.count);
    in.facetlist = new tetgenio::facet[facets.count ? facets.count : 1];
    for (std::size_t f = 0; f < facets.count; ++f) {  // initialized first: the destructor walks them
      tetgenio::init(&in.facetlist[f]);
    }
    for (std::size_t f = 0; f < facets.count; ++f) {
      tetgenio::facet &facet = in.facetlist[f];
      facet.polygonlist = new tetgenio::polygon[1];
      facet.numberofpolygons = 1;
      tetgenio::polygon &p = facet.polygonlist[0];
      tetgenio::init(&p);
      std::size_t b = facets.begin(f), e = facets.begin(f + 1);
      p.numberofvertices = int(e - b);
      p.vertexlist = new int[e - b];
      for (std::size_t k = b; k < e; ++k) p.vertexlist[k - b] = int(facets.corners[k]);
    }
    if (n_regions) {
      in.numberofregions = int(n_regions);
      in.regionlist = new REAL[5 * n_regions];
      for (std::size_t k = 0; k < 5 * n_regions; ++k) in.regionlist[k] = regions[k];
    }
    if (n_holes) {
      in.numberofholes = int(n_holes);
      in.holelist = new REAL[3 * n_holes];
      for (std::size_t k = 0; k < 3 * n_holes; ++k) in.holelist[k] = holes[k];
    }
    tetrahedralize(sw.data(), &in, &result);

    if (result.numberofpoints < int(n)) {
      std::snprintf(message, sizeof message, "%s: TetGen returned %d points for %zu input points", who,
                    result.numberofpoints, n);
      return ref::fail(message);
    }
    for (std::size_t k = 0; k < 3 * n; ++k)
      if (result.pointlist[k] != xyz[k]) {
        std::snprintf(message, sizeof message, "%s: TetGen's point %zu is not input point %zu", who, k / 3, k / 3);
        return ref::fail(message);
      }
    if (result.numberofcorners != 4) {
      std::snprintf(message, sizeof message, "%s: unexpected element order %d", who, result.numberofcorners);
      return ref::fail(message);
    }
    // Output points past the input's that no tetrahedron uses (Steiner points TetGen inserted,
    // then suppressed: J keeps them in the list) are dropped; the others are renumbered from n
    // on, in TetGen's order.
    std::size_t points = std::size_t(result.numberofpoints);
    std::size_t count = std::size_t(result.numberoftetrahedra);
    std::vector<uint32_t> renumber(points, UINT32_MAX);
    for (std::size_t i = 0; i < n; ++i) renumber[i] = uint32_t(i);
    for (std::size_t k = 0; k < 4 * count; ++k) {
      int v = result.tetrahedronlist[k];
      if (v < 0 || std::size_t(v) >= points) {
        std::snprintf(message, sizeof message, "%s: TetGen returned an index out of range", who);
        return ref::fail(message);
      }
      if (std::size_t(v) >= n) renumber[std::size_t(v)] = 0;  // a used Steiner point: numbered below
    }
    std::size_t vertex_count = n;
    for (std::size_t i = n; i < points; ++i)
      if (renumber[i] != UINT32_MAX) renumber[i] = uint32_t(vertex_count++);
    RefSurfaceMesh mesh{};
    mesh.xyz = static_cast<double *>(std::malloc(3 * (vertex_count ? vertex_count : 1) * sizeof(double)));
    mesh.tets = static_cast<uint32_t *>(std::malloc(4 * (count ? count : 1) * sizeof(uint32_t)));
    mesh.labels = static_cast<int32_t *>(std::malloc((count ? count : 1) * sizeof(int32_t)));
    if (!mesh.xyz || !mesh.tets || !mesh.labels) {
      ref_surface_mesh_free(&mesh);
      return ref::fail("out of memory");
    }
    for (std::size_t i = 0; i < points; ++i)
      if (renumber[i] != UINT32_MAX)
        for (int k = 0; k < 3; ++k) mesh.xyz[3 * std::size_t(renumber[i]) + k] = result.pointlist[3 * i + k];
    for (std::size_t k = 0; k < 4 * count; ++k) mesh.tets[k] = renumber[std::size_t(result.tetrahedronlist[k])];
    int attributes = result.numberoftetrahedronattributes;
    for (std::size_t t = 0; t < count; ++t)
      mesh.labels[t] = attributes > 0 ? int32_t(std::lround(result.tetrahedronattributelist[t * attributes])) : 1;
    double seconds = clock.seconds();  // what follows is the shim's, not TetGen's work
    // Steiner points on TetGen's own boundary faces (its triangulated facets): -Y did not hold.
    std::vector<bool> on_boundary(vertex_count, false);
    for (int k = 0; k < 3 * result.numberoftrifaces; ++k) {
      int v = result.trifacelist[k];
      if (v >= 0 && std::size_t(v) < points && renumber[std::size_t(v)] != UINT32_MAX)
        on_boundary[renumber[std::size_t(v)]] = true;
    }
    for (std::size_t i = n; i < vertex_count; ++i) mesh.boundary_steiner += on_boundary[i];
    repair_labels(result, mesh.tets, mesh.labels, count, renumber);
    mesh.vertex_count = vertex_count;
    mesh.steiner_count = vertex_count - n;
    mesh.tet_count = count;
    *out = mesh;
    if (timing) timing->seconds = seconds;
    return 0;  // in/result are released after the clock stopped
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (int code) {
    // TetGen reports errors by throwing an int (terminatetetgen): 1 out of memory, 2
    // an internal error, 3 a self-intersection, 4 a very small input feature, 5 two very close
    // input facets, 10 an input error.
    std::snprintf(message, sizeof message, "%s: TetGen failed with code %d", who, code);
    return ref::fail(message);
  } catch (...) {
    std::snprintf(message, sizeof message, "%s: unknown exception", who);
    return ref::fail(message);
  }
}

}  // namespace

extern "C" int ref_tetgen_surface(const double *xyz, size_t n, const uint32_t *tris, size_t m,
                                  const double *regions, size_t n_regions, const double *holes,
                                  size_t n_holes, const char *switches, RefSurfaceMesh *out,
                                  RefTiming *timing) {
  return tetgen_plc("ref_tetgen_surface", xyz, n, Facets{tris, nullptr, m}, regions, n_regions, holes,
                    n_holes, switches, out, timing);
}

extern "C" int ref_tetgen_polygons(const double *xyz, size_t n, const uint32_t *corners,
                                   const size_t *offsets, size_t m, const double *regions,
                                   size_t n_regions, const double *holes, size_t n_holes,
                                   const char *switches, RefSurfaceMesh *out, RefTiming *timing) {
  if (!offsets) return ref::fail("ref_tetgen_polygons: NULL argument");
  return tetgen_plc("ref_tetgen_polygons", xyz, n, Facets{corners, offsets, m}, regions, n_regions, holes,
                    n_holes, switches, out, timing);
}

extern "C" int ref_tetgen_intersections(const double *xyz, size_t n, const uint32_t *tris, size_t m,
                                        uint32_t **culprits, size_t *count) {
  if (!xyz || !tris || !culprits || !count) return ref::fail("ref_tetgen_intersections: NULL argument");
  if (n > 0x7fffffff || m > 0x7fffffff) return ref::fail("ref_tetgen_intersections: input too large for TetGen");
  for (std::size_t k = 0; k < 3 * m; ++k)
    if (tris[k] >= n) return ref::fail("ref_tetgen_intersections: index out of range");
  try {
    tetgenio in, result;
    in.firstnumber = 0;
    in.numberofpoints = int(n);
    in.pointlist = new REAL[3 * (n ? n : 1)];
    for (std::size_t i = 0; i < 3 * n; ++i) in.pointlist[i] = xyz[i];
    in.numberoffacets = int(m);
    in.facetlist = new tetgenio::facet[m ? m : 1];
    for (std::size_t f = 0; f < m; ++f) tetgenio::init(&in.facetlist[f]);
    for (std::size_t f = 0; f < m; ++f) {
      tetgenio::facet &facet = in.facetlist[f];
      facet.polygonlist = new tetgenio::polygon[1];
      facet.numberofpolygons = 1;
      tetgenio::init(&facet.polygonlist[0]);
      facet.polygonlist[0].numberofvertices = 3;
      facet.polygonlist[0].vertexlist = new int[3];
      for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = int(tris[3 * f + std::size_t(k)]);
    }
    // d: detect self-intersections only; the faces involved come back in trifacelist.
    char switches[] = "pdzQ";
    tetrahedralize(switches, &in, &result);
    using Key = std::array<uint32_t, 3>;
    auto key = [](uint32_t a, uint32_t b, uint32_t c) {
      Key k{a, b, c};
      std::sort(k.begin(), k.end());
      return k;
    };
    std::map<Key, std::vector<uint32_t>> index;
    for (std::size_t f = 0; f < m; ++f) index[key(tris[3 * f], tris[3 * f + 1], tris[3 * f + 2])].push_back(uint32_t(f));
    std::set<uint32_t> found;
    for (int f = 0; f < result.numberoftrifaces; ++f) {
      const int *v = result.trifacelist + 3 * f;
      auto it = index.find(key(uint32_t(v[0]), uint32_t(v[1]), uint32_t(v[2])));
      if (it != index.end()) found.insert(it->second.begin(), it->second.end());
    }
    uint32_t *list = static_cast<uint32_t *>(std::malloc((found.size() ? found.size() : 1) * sizeof(uint32_t)));
    if (!list) return ref::fail("out of memory");
    std::size_t k = 0;
    for (uint32_t f : found) list[k++] = f;
    *culprits = list;
    *count = k;
    return 0;
  } catch (const std::exception &e) {
    return ref::fail(e.what());
  } catch (int code) {
    char message[96];
    std::snprintf(message, sizeof message, "ref_tetgen_intersections: TetGen failed with code %d", code);
    return ref::fail(message);
  } catch (...) {
    return ref::fail("ref_tetgen_intersections: unknown exception");
  }
}
