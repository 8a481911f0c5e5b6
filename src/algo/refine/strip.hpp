// Pieces of refine_in_parts (refine_parallel.cpp) shared with its last pass
// on a strip (strip.cpp): a part cut out of the whole mesh with its outer
// edges frozen, and the flips that note the slots they rewrite.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "algo/refine_parallel.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/refine.hpp"
#include "mesh/editor.hpp"
#include "mesh/legalize.hpp"

namespace deltamesh::detail {

inline std::uint64_t directed_key(VertexId a, VertexId b) { return (std::uint64_t{a} << 32) | b; }

// A part of the whole mesh: its own mesh, and its first vertices' ids in the whole.
struct Part {
  Mesh mesh;
  std::vector<VertexId> global;     // part vertex (those it started with) -> whole-mesh vertex
  std::vector<std::uint64_t> cuts;  // the temporary segments (whole-mesh ids, one direction each)
  std::vector<HalfEdgeId> outer;    // the whole's half-edges across the part's frozen edges
  RefineStats stats;
  RefineStage stage;  // keeps the final verdict per slot: the last pass's first look
};

// The triangles `tris` of `whole` (local(t): t's index in the part, kNone
// for a triangle outside it) as a mesh of their own: vertex, edge and
// triangle data copied, the edges to triangles outside frozen (temporary
// segments, marker 0; a segment there is frozen too).
template <class Local>
void cut_part(const Mesh& whole, const std::vector<TriId>& tris, Local local_index, Part& part) {
  const std::size_t n = whole.num_vertices();
  std::vector<VertexId> local(n, kNone);
  for (TriId t : tris)
    for (VertexId v : whole.triangle(t))
      if (local[v] == kNone) {
        local[v] = static_cast<VertexId>(part.global.size());
        part.global.push_back(v);
      }
  Mesh& m = part.mesh;
  const std::size_t nv = part.global.size(), na = whole.num_vertex_attributes();
  MeshEditor(m).points().resize(nv);
  for (std::size_t v = 0; v < nv; ++v) MeshEditor(m).points()[v] = whole.point(part.global[v]);
  if (!whole.vertex_markers().empty()) {
    m.vertex_markers().resize(nv);
    for (std::size_t v = 0; v < nv; ++v) m.vertex_markers()[v] = whole.vertex_markers()[part.global[v]];
  }
  m.set_num_vertex_attributes(na);
  m.vertex_attributes().resize(nv * na);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t k = 0; k < na; ++k)
      m.vertex_attributes()[v * na + k] = whole.vertex_attributes()[std::size_t{part.global[v]} * na + k];
  MeshEditor(m).out_edges().assign(nv, kNone);

  const std::size_t nt = tris.size(), ta = whole.num_triangle_attributes();
  std::vector<VertexId>& tv = MeshEditor(m).triangle_vertices();
  std::vector<HalfEdgeId>& tw = MeshEditor(m).twins();
  std::vector<std::uint8_t>& fl = MeshEditor(m).edge_flags();
  std::vector<int>& mk = MeshEditor(m).edge_markers();
  tv.resize(3 * nt);
  tw.resize(3 * nt);
  fl.assign(3 * nt, 0);
  // Edge markers only when the whole has them: all-zero markers are the
  // same to every reader, but cost 4 bytes per half-edge, their copies, and
  // passes that skip meshes without them (finish_vertex_markers).
  const bool edge_markers = whole.has_edge_markers();
  if (edge_markers) mk.assign(3 * nt, 0);
  m.set_num_triangle_attributes(ta);
  m.triangle_attributes().resize(nt * ta);
  for (std::size_t i = 0; i < nt; ++i) {
    const TriId t = tris[i];
    for (int c = 0; c < 3; ++c) {
      const HalfEdgeId e = 3 * t + c, f = static_cast<HalfEdgeId>(3 * i + c), o = whole.twin(e);
      tv[f] = local[whole.origin(e)];
      fl[f] = whole.edge_flags(e);
      if (edge_markers) mk[f] = whole.edge_marker(e);
      const TriId across = o == kNone ? kNone : local_index(tri_of(o));
      if (o == kNone) {
        tw[f] = kNone;
      } else if (across != kNone) {
        tw[f] = static_cast<HalfEdgeId>(3 * std::size_t{across} + o % 3);
      } else {
        tw[f] = kNone;
        part.outer.push_back(o);
        if (!(fl[f] & kConstrained)) {
          fl[f] = static_cast<std::uint8_t>(fl[f] | kConstrained | kFrozenEdge);
          part.cuts.push_back(directed_key(whole.origin(e), whole.dest(e)));
        } else {
          fl[f] = static_cast<std::uint8_t>(fl[f] | kFrozenEdge);  // a segment along the cut: split on neither side
        }
      }
    }
    for (std::size_t k = 0; k < ta; ++k)
      m.triangle_attributes()[i * ta + k] = whole.triangle_attributes()[std::size_t{t} * ta + k];
  }
  if (whole.has_triangle_area_bounds())
    for (std::size_t i = 0; i < nt; ++i)
      m.set_triangle_area_bound(static_cast<TriId>(i), whole.triangle_area_bound(tris[i]));
  m.compact();  // out-edges, counts
}

// Adds the counts of a refinement (its Steiner points by kind, rejections
// and skips; the largest queue) to another's.
inline void add_counts(RefineStats& to, const RefineStats& from) {
  to.segment_splits += from.segment_splits;
  to.interior_points += from.interior_points;
  to.offcenters += from.offcenters;
  to.rejected_points += from.rejected_points;
  to.small_angle_skips += from.small_angle_skips;
  to.failed_splits += from.failed_splits;
  to.peak_queue = std::max(to.peak_queue, from.peak_queue);
}

// The mesh's own flips, noting the slots they rewrite (the parts' verdicts
// on those no longer hold).
class NotingTopology : public MeshTopology {
 public:
  NotingTopology(Mesh& m, std::vector<TriId>& rewritten) : MeshTopology(m), rewritten_(rewritten) {}
  void flip(const FlipQuad& q, TraceReason why) {
    MeshTopology::flip(q, why);
    rewritten_.push_back(tri_of(q.e));
    rewritten_.push_back(tri_of(q.f));
  }

 private:
  std::vector<TriId>& rewritten_;
};

// refine_in_parts' last pass on a strip: the triangles within a few rings
// of `seeds` (the cuts' triangles, the slots the stitch's flips rewrote,
// the parts' final bad triangles and those of segments along a cut) are
// cut out with their outer edges frozen, refined on one thread, written
// back into their own slots (new ones appended), and the outer edges
// flipped to the constrained Delaunay triangulation; what that leaves bad
// (next to the frozen edges) seeds the next round, a few at most. True,
// with the strips' statistics in `stats`, when no triangle of the whole
// mesh is bad and no subsegment the strips or the flips touched is
// encroached: the mesh is finished. False: the whole-mesh pass must run,
// on the mesh unchanged when nothing was written back (`stats` empty:
// a first strip left triangles at small input angles, or was stopped),
// else on a valid constrained Delaunay triangulation with every slot
// rewritten marked kLookAgain in `first_look` (`stats`: the strips' counts).
// `strip_triangles`: the strips' sizes before refinement, summed.
// `refuse` (tests): false after writing back, as if a check had failed.
bool refine_strip(Mesh& whole, const RefineOptions& options, const std::vector<TriId>& seeds,
                  std::vector<std::uint8_t>& first_look, RefineStats& stats, std::size_t& strip_triangles,
                  bool refuse = false);

}  // namespace deltamesh::detail
