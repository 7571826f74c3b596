// TetGen reference for the C tests (interface and conventions in ref.h).
#include "ref.h"
#include "ref_internal.hpp"

#define TETLIBRARY
#include <tetgen.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

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
