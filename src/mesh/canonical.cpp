// Canonical triangle numbering (see canonical.hpp).
#include "mesh/canonical.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mesh/editor.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh::detail {

namespace {

// v permuted so that slot s of the result holds what slot src[s] held, with
// `width` entries per slot.
template <class T>
void gather(std::vector<T>& v, const std::vector<std::uint32_t>& src, std::size_t width) {
  if (v.empty()) return;
  std::vector<T> out(v.size());
  for (std::size_t s = 0; s < src.size(); ++s)
    for (std::size_t i = 0; i < width; ++i) out[width * s + i] = v[width * src[s] + i];
  v.swap(out);
}

}  // namespace

void canonical_triangle_order(Mesh& mesh) {
  MeshEditor ed(mesh);
  std::vector<VertexId>& tv = ed.triangle_vertices();
  const std::size_t nt = tv.size() / 3, nv = ed.points().size();
  if (nt == 0) return;
  // Per triangle: the rotation that puts its smallest vertex first.
  std::vector<std::uint8_t> rot(nt);
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const VertexId* v = &tv[3 * t];
    const int r = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
    rot[t] = static_cast<std::uint8_t>(r);
    ++start[v[r] + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  // src[s]: the old slot of new slot s (by smallest vertex, then the next).
  std::vector<std::uint32_t> src(nt);
  for (std::size_t t = 0; t < nt; ++t) src[start[tv[3 * t + rot[t]]]++] = static_cast<std::uint32_t>(t);
  const auto second = [&](std::uint32_t t) { return tv[3 * t + (rot[t] + 1) % 3]; };
  for (std::size_t lo = 0; lo < nt;) {  // groups are small (a vertex's fan): insertion sort
    std::size_t hi = lo + 1;
    const VertexId first = tv[3 * src[lo] + rot[src[lo]]];
    while (hi < nt && tv[3 * src[hi] + rot[src[hi]]] == first) ++hi;
    for (std::size_t i = lo + 1; i < hi; ++i)
      for (std::size_t j = i; j > lo && second(src[j]) < second(src[j - 1]); --j) std::swap(src[j], src[j - 1]);
    lo = hi;
  }
  // Rotate each triangle in place (with its half-edge data), then move slots.
  std::vector<HalfEdgeId>& tw = ed.twins();
  std::vector<std::uint8_t>& fl = ed.edge_flags();
  std::vector<int>& mk = ed.edge_markers();
  std::vector<std::uint32_t> slot_of(nt);
  for (std::size_t s = 0; s < nt; ++s) slot_of[src[s]] = static_cast<std::uint32_t>(s);
  // Old half-edge 3t + i goes to 3 slot_of[t] + (i - rot[t]) mod 3.
  const auto moved = [&](HalfEdgeId e) -> HalfEdgeId {
    const std::size_t t = e / 3, i = e % 3;
    return static_cast<HalfEdgeId>(3 * slot_of[t] + (i + 3 - rot[t]) % 3);
  };
  for (HalfEdgeId& f : tw)
    if (f != kNone) f = moved(f);
  const auto rotate = [&](auto& v) {
    if (v.empty()) return;
    for (std::size_t t = 0; t < nt; ++t)
      if (rot[t] != 0) std::rotate(v.begin() + 3 * t, v.begin() + 3 * t + rot[t], v.begin() + 3 * t + 3);
  };
  rotate(tv);
  rotate(tw);
  rotate(fl);
  rotate(mk);
  gather(tv, src, 3);
  gather(tw, src, 3);
  gather(fl, src, 3);
  gather(mk, src, 3);
  gather(mesh.triangle_attributes(), src, mesh.num_triangle_attributes());
  if (mesh.has_triangle_area_bounds()) {
    std::vector<double> bounds(nt);
    for (std::size_t s = 0; s < nt; ++s) bounds[s] = mesh.triangle_area_bound(src[s]);
    for (std::size_t s = 0; s < nt; ++s) mesh.set_triangle_area_bound(static_cast<TriId>(s), bounds[s]);
  }
  // Out-edges as compact() sets them: any, then a boundary vertex's boundary edge.
  std::vector<HalfEdgeId>& ve = ed.out_edges();
  std::fill(ve.begin(), ve.end(), kNone);
  for (HalfEdgeId e = 0; e < tv.size(); ++e) ve[tv[e]] = e;
  for (HalfEdgeId e = 0; e < tw.size(); ++e)
    if (tw[e] == kNone) ve[tv[e]] = e;
  if (mesh.trace()) TraceAccess::resync(*mesh.trace(), tv, "canonical_triangle_order");
}

}  // namespace deltamesh::detail
