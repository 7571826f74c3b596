#include "mesh_run.h"

DelmeshStatus mesh_run(const Shape *s, const RefMeshCriteria *c, double relative_error, MeshRunMode mode,
                       DelmeshMesh **out) {
  DelmeshDomain *domain = NULL;
  DelmeshMesher *mesher = NULL;
  DelmeshStatus st = s->implicit ? delmesh_domain_new_implicit(s->implicit, NULL, s->bbox, relative_error, &domain)
                                 : delmesh_domain_new_labeled(s->label, NULL, s->bbox, relative_error, &domain);
  if (st == DELMESH_OK) st = delmesh_mesher_new(&mesher);
  if (st == DELMESH_OK && c->facet_angle > 0) st = delmesh_mesher_set_facet_angle(mesher, c->facet_angle);
  if (st == DELMESH_OK && c->facet_size > 0) st = delmesh_mesher_set_facet_size(mesher, c->facet_size);
  if (st == DELMESH_OK && c->facet_distance > 0) st = delmesh_mesher_set_facet_distance(mesher, c->facet_distance);
  if (st == DELMESH_OK && c->cell_radius_edge_ratio > 0)
    st = delmesh_mesher_set_cell_radius_edge_ratio(mesher, c->cell_radius_edge_ratio);
  if (st == DELMESH_OK && c->cell_size > 0) st = delmesh_mesher_set_cell_size(mesher, c->cell_size);
  if (st == DELMESH_OK && mode != MESH_RUN_DEFAULT) st = delmesh_mesher_set_optimization(mesher, 0, 0);
  if (st == DELMESH_OK && mode == MESH_RUN_AS_CGAL) st = delmesh_mesher_set_surface_sliver_angle(mesher, 0);
  if (st == DELMESH_OK) st = delmesh_mesher_run(mesher, domain, out);
  delmesh_mesher_free(mesher);
  delmesh_domain_free(domain);
  return st;
}
