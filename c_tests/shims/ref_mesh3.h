/* CGAL 5.5 Mesh_3 behind a C interface (ref_mesh3.cpp), in the conventions of ref.h: 0 on
 * success, -1 and ref_last_error() on failure, malloc'd results, no C++ exception crosses.
 *
 * The domains are CGAL::Labeled_mesh_domain_3<Epick> with the bounding box `bbox`
 * (xmin ymin zmin xmax ymax zmax) and the given relative error bound (of surface points,
 * relative to the box diagonal). The mesh is that of CGAL::make_mesh_3, sequential, seeded with
 * surface points where random segments across the box change label (ref_mesh3.cpp says why).
 * ref_cgal_mesh_implicit / _labeled run it with no_perturb() and no_exude() (refinement only);
 * the _optimized variants can add CGAL's optimizers (RefMeshOptions). */
#ifndef DELMESH_C_TESTS_REF_MESH3_H
#define DELMESH_C_TESTS_REF_MESH3_H

#include "ref.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The callback types of delmesh's domains (same signatures). */
typedef double (*RefImplicitFn)(const double p[3], void *user_data); /* < 0 inside */
typedef int32_t (*RefLabelFn)(const double p[3], void *user_data);   /* 0 outside, > 0 subdomain */

/* Mesh_criteria_3 named parameters; a value <= 0 means "not set" (CGAL's 0). */
typedef struct RefMeshCriteria {
  double facet_angle;            /* degrees */
  double facet_size;             /* surface Delaunay ball radius */
  double facet_distance;         /* facet circumcenter to surface */
  double cell_radius_edge_ratio; /* circumradius / shortest edge */
  double cell_size;              /* circumradius */
} RefMeshCriteria;

/* The cells of the complex. Vertices: only those used by its cells, compactly numbered.
 * Tetrahedra are positively oriented in delmesh's convention (ref_orient3d_exact > 0). */
typedef struct RefMesh {
  double *xyz;         /* 3 * vertex_count */
  int8_t *dimensions;  /* vertex_count: CGAL's in_dimension (2 surface, 3 volume, ...) */
  size_t vertex_count;
  uint32_t *tets;      /* 4 * tet_count */
  int32_t *labels;     /* tet_count: subdomain index (> 0) */
  size_t tet_count;
} RefMesh;

/* Implicit domain: inside where f < 0 (label 1). */
int ref_cgal_mesh_implicit(RefImplicitFn f, void *user_data, const double bbox[6],
                           double relative_error, const RefMeshCriteria *criteria, RefMesh *out,
                           RefTiming *timing);

/* Labeling-function domain: label 0 outside, > 0 subdomain. */
int ref_cgal_mesh_labeled(RefLabelFn f, void *user_data, const double bbox[6],
                          double relative_error, const RefMeshCriteria *criteria, RefMesh *out,
                          RefTiming *timing);

/* ---- Optimization (perturbation and exudation) ------------------------------------------------ */

typedef enum RefOptimization {
  /* make_mesh_3 with no_perturb(), no_exude(): refinement only, as ref_cgal_mesh_implicit. */
  REF_OPTIMIZE_NONE = 0,
  /* make_mesh_3 with perturb() and exude() (CGAL's default optimizers, default sliver bounds),
   * time limits from RefMeshOptions. */
  REF_OPTIMIZE_MESH_3 = 1,
  /* make_mesh_3 with no_perturb(), no_exude(), then CGAL::perturb_mesh_3 and CGAL::exude_mesh_3
   * on its result, the same calls make_mesh_3 makes, each timed alone (RefMeshTiming). */
  REF_OPTIMIZE_SEPARATE = 2
} RefOptimization;

typedef struct RefMeshOptions {
  int optimization; /* a RefOptimization */
  /* Time limit of each optimizer, in seconds. 0: none (the default of perturb_mesh_3 and
   * exude_mesh_3; the result does not depend on the machine's speed). Negative: make_mesh_3's
   * default, the refinement's own time (machine-dependent). */
  double time_limit;
  /* REF_OPTIMIZE_SEPARATE only: if not NULL, receives the refined mesh before optimization
   * (exported between the timed calls, outside refine_seconds and the optimizers' times). */
  RefMesh *refined;
} RefMeshOptions;

/* CGAL::Mesh_optimization_return_code of an optimizer, or REF_OPTIMIZER_NOT_RUN /
 * REF_OPTIMIZER_NOT_REPORTED (make_mesh_3 does not return its optimizers' codes). */
enum { REF_OPTIMIZER_NOT_RUN = -2, REF_OPTIMIZER_NOT_REPORTED = -3 };

typedef struct RefMeshTiming {
  double seconds;         /* the whole call, as RefTiming (includes exporting `refined`) */
  double refine_seconds;  /* REF_OPTIMIZE_SEPARATE: refinement from the initial points */
  double perturb_seconds; /* REF_OPTIMIZE_SEPARATE: CGAL::perturb_mesh_3 alone */
  double exude_seconds;   /* REF_OPTIMIZE_SEPARATE: CGAL::exude_mesh_3 alone */
  int perturb_code, exude_code; /* return codes, see above */
} RefMeshTiming;

/* "bound reached", "time limit reached", "can't improve anymore", ..., "not run". */
const char *ref_optimizer_code_name(int code);

/* As ref_cgal_mesh_implicit / _labeled, with the optimization of `options` (NULL: none).
 * `timing` may be NULL. */
int ref_cgal_mesh_implicit_optimized(RefImplicitFn f, void *user_data, const double bbox[6],
                                     double relative_error, const RefMeshCriteria *criteria,
                                     const RefMeshOptions *options, RefMesh *out,
                                     RefMeshTiming *timing);
int ref_cgal_mesh_labeled_optimized(RefLabelFn f, void *user_data, const double bbox[6],
                                    double relative_error, const RefMeshCriteria *criteria,
                                    const RefMeshOptions *options, RefMesh *out,
                                    RefMeshTiming *timing);

/* Frees the arrays of a RefMesh and zeroes it (NULL accepted). */
void ref_mesh_free(RefMesh *mesh);

#ifdef __cplusplus
}
#endif

#endif
