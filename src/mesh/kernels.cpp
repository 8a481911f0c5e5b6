// Out-of-line mesh kernels: whole-mesh constrained Lawson flips and the
// first triangle of a closed triangulation.
#include "mesh/legalize.hpp"
#include "mesh/split.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh::detail {

std::size_t constrained_lawson_flips(Mesh& mesh) {
  std::vector<HalfEdgeId> stack;
  const std::size_t halves = mesh.triangle_vertices().size();
  for (HalfEdgeId e = 0; e < halves; ++e)
    if (mesh.is_real(tri_of(e)) && mesh.twin(e) != kNone && e < mesh.twin(e)) stack.push_back(e);
  auto topo = lawson_topology(mesh);
  return constrained_lawson(topo, stack);
}

void make_first_triangle(Mesh& mesh, VertexId a, VertexId b, VertexId c) {
  const TriId t = mesh.add_triangle(a, b, c);
  const VertexId v[3] = {a, b, c};
  TriId g[3];
  for (int i = 0; i < 3; ++i) g[i] = mesh.add_triangle(v[(i + 1) % 3], v[i], kInfinite);
  for (int i = 0; i < 3; ++i) {
    mesh.link(3 * t + i, 3 * g[i]);
    // Ghost g[i] = (v[i+1], v[i], inf): its edge v[i] -> inf meets ghost
    // g[i-1] = (v[i], v[i-1], inf) at its edge inf -> v[i].
    mesh.link(3 * g[i] + 1, 3 * g[(i + 2) % 3] + 2);
    mesh.set_out_edge(v[i], 3 * t + i);
  }
  if (TraceObserver* o = mesh.trace())
    TraceAccess::slots(*o, trace_insert(c, mesh.point(c)), mesh.triangle_vertices().data(), {t, g[0], g[1], g[2]});
}

}  // namespace deltamesh::detail
