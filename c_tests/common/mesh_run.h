/* One delmesh meshing run of a test shape through the C API, with the criteria the CGAL shim
 * takes (ref_mesh3.h), shared by the tests and benchmarks that compare with CGAL Mesh_3. */
#ifndef DELMESH_C_TESTS_MESH_RUN_H
#define DELMESH_C_TESTS_MESH_RUN_H

#include "ref_mesh3.h"
#include "shapes.h"

#include <delmesh.h>

typedef enum MeshRunMode {
  MESH_RUN_AS_CGAL, /* refinement with CGAL's criteria only: no optimization, no surface sliver bound */
  MESH_RUN_REFINE,  /* delmesh's refinement (with its surface sliver bound), no optimization */
  MESH_RUN_DEFAULT  /* delmesh's defaults: refinement, then perturbation and exudation */
} MeshRunMode;

/* Meshes `s` (its implicit function, else its labeling function) with the criteria `c` (a value
 * <= 0 is not set) and the domain's `relative_error`; *out receives the mesh on success. */
DelmeshStatus mesh_run(const Shape *s, const RefMeshCriteria *c, double relative_error, MeshRunMode mode,
                       DelmeshMesh **out);

#endif
