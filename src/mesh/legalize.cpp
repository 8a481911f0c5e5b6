#include "mesh/legalize.hpp"

namespace deltamesh::detail {

std::size_t constrained_lawson_flips(Mesh& mesh) {
  std::vector<HalfEdgeId> stack;
  const std::size_t halves = mesh.triangle_vertices().size();
  for (HalfEdgeId e = 0; e < halves; ++e)
    if (mesh.is_real(tri_of(e)) && mesh.twin(e) != kNone && e < mesh.twin(e)) stack.push_back(e);
  auto topo = lawson_topology(mesh);
  return constrained_lawson(topo, stack);
}

}  // namespace deltamesh::detail
