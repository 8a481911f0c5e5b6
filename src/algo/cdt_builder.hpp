// Segment insertion into a closed triangulation (ghost triangles): the
// shared front end (tracing a segment, splitting it at vertices on it and at
// crossings with earlier segments) and the seed's recovery methods.
#pragma once
#include <algorithm>
#include <cstdint>
#include <deque>
#include <unordered_set>
#include <vector>

#include "algo/cdt_lifting.hpp"
#include "algo/insertion.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/cdt.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"
#include "mesh/legalize.hpp"

namespace deltamesh::detail {

// While segments are inserted, the builder's own per-half-edge array holds,
// for a constrained half-edge, the index of the input segment it belongs to.
// It is carried through every split and flip exactly as the mesh's markers
// are (the same carry kernels, mesh/flip.hpp and mesh/split.hpp), so the
// mapping edge -> segment costs nothing to maintain, and the mesh's marker
// array only ever holds markers: finish() writes them from the indices.
class CdtBuilder {
 public:
  // segment_ids: when not empty, one per half-edge of the mesh, the index of
  // the segment of each constrained edge; the builder then keeps indices
  // even when no segment has a marker (insert_segments reads them before
  // finish(), through segment_of()).
  CdtBuilder(Mesh& mesh, const Pslg& pslg, const CdtOptions& options, CdtStats& stats,
             std::vector<int> segment_ids = {});

  // Inserts input segment `index` between (already merged) vertices a != b.
  void insert_segment(VertexId a, VertexId b, std::uint32_t index);
  // Indices -> the mesh's markers (none when every marker is 0); the
  // indices are gone afterwards.
  void finish();
  // The segment of constrained half-edge e (0 when indices are not kept).
  std::uint32_t segment_of(HalfEdgeId e) const { return seg_id(e); }

  // Inserts vertex v (in the mesh's points, in no triangle) by Delaunay
  // insertion that keeps constrained edges, locating it by a walk from the
  // triangle of half-edge `near`. Returns v, or the vertex it coincides with.
  VertexId insert_vertex(VertexId v, HalfEdgeId near);
  std::size_t vertex_flips() const { return inserter_.flips() + lean_flips_; }
  // Triangle slots for insert_vertex to split into without Mesh::add_triangle
  // (dead until used); release_slots() drops the unused ones at the end and
  // recounts the mesh's live triangles.
  void reserve_slots(std::size_t slots);
  void release_slots();
  std::size_t walk_steps() const { return walk_steps_; }

 private:
  struct Piece {
    VertexId a, b;
    std::uint32_t seg;
  };
  enum class TraceKind : std::uint8_t {
    Present,      // edge a->b exists: `edge` is it
    OnVertex,     // vertex `vertex` lies on the open segment; crossings_ holds the edges crossed before it
                  // (when empty, `edge` is the edge a->vertex)
    Constrained,  // `edge` is a constrained edge crossing the open segment (origin right, dest left)
    Clean,        // crossings_ holds every edge crossing ab, in order from a
  };
  struct Trace {
    TraceKind kind;
    HalfEdgeId edge = kNone;
    VertexId vertex = kNone;
  };

  void process(const Piece& piece, bool whole);
  Trace trace(VertexId a, VertexId b);
  void mark(HalfEdgeId e, std::uint32_t seg);
  void resolve_crossing(const Piece& piece, HalfEdgeId cd);
  bool split_fits(HalfEdgeId cd, const Point& p) const;
  void release(HalfEdgeId cd);

  // Recovery of a clean piece (crossings_ filled by trace, all unconstrained).
  void recover(VertexId a, VertexId b, std::uint32_t seg);
  void recover_fast(VertexId a, VertexId b, std::uint32_t seg);
  // Cuts the excursions to enclosed vertices out of a cavity side's chain;
  // false if the chain is not a walk out and back (a cavity with a hole).
  bool cut_excursions(std::vector<VertexId>& chain, std::vector<HalfEdgeId>& out);
  // Ct (§1.2.2); with `lawson`, then constrained Lawson flips (§2.2).
  void recover_flips(VertexId a, VertexId b, std::uint32_t seg, bool lawson);
  void recover_lifting(VertexId a, VertexId b, std::uint32_t seg);
  // A flip method gave up (degenerate input): retrace and finish with Fast.
  void fallback_fast(VertexId a, VertexId b, std::uint32_t seg);
  // Fast met a cavity that encloses triangles: Lifting instead.
  void fast_gave_up(VertexId a, VertexId b, std::uint32_t seg);
  bool in_fallback_ = false;
  // constrained_lawson() (mesh/legalize.hpp) from `stack`, flips counted in the stats.
  void lawson_flips(std::vector<HalfEdgeId>& stack);
  // Trace events (trace_hooks.hpp): a segment that was an edge already; the
  // Fast method's retriangulated cavity (slots_).
  void trace_present(VertexId a, VertexId b);
  void trace_cavity(VertexId a, VertexId b);
  bool crosses(VertexId a, VertexId b, VertexId c, VertexId d) const;

  HalfEdgeId apex_edge(HalfEdgeId e) const { return prev_edge(e); }
  const Point& pt(VertexId v) const { return pts_[v]; }

  Mesh& mesh_;
  const Pslg& pslg_;
  const CdtOptions& opt_;
  CdtStats& st_;
  std::vector<Point>& pts_;
  std::vector<VertexId>& tv_;
  std::vector<HalfEdgeId>& tw_;
  std::vector<std::uint8_t>& flags_;
  std::vector<int> seg_of_;  // per half-edge: the segment index of a constrained edge (when ids_)
  bool ids_ = false;
  // A recovery flip (Ct, Lawson, Lifting) on the raw arrays, carrying
  // seg_of_ as the markers slot. Both triangles are real (the recovery
  // methods flip only inside a segment's cavity), so the mesh's live
  // triangle count stays as it is.
  void flip(HalfEdgeId e) {
    MeshArrays arrays = MeshArrays::of(mesh_);
    arrays.markers = ids_ ? seg_of_.data() : nullptr;
    flip_arrays<kCarryAll>(arrays, e);
  }
  std::uint32_t seg_id(HalfEdgeId e) const { return ids_ ? static_cast<std::uint32_t>(seg_of_[e]) : 0; }
  std::vector<HalfEdgeId>& ve_;
  DelaunayInserter inserter_;

  std::vector<Piece> pieces_;
  std::vector<HalfEdgeId> crossings_;
  std::size_t steiner_ = 0;
  std::size_t walk_steps_ = 0;
  std::size_t lean_flips_ = 0;
  std::size_t next_slot_ = 0, reserved_slots_ = 0;
  std::vector<HalfEdgeId> legal_;
  void split_and_legalize(TriId t, VertexId v);
  // incircle() with a static filter first: every coordinate difference is
  // at most the input's bounding box extent (rounded up), so the permanent
  // incircle's filter compares with is at most 12 box^4 and its error bound
  // at most static_err_; a determinant beyond that needs no permanent. (The
  // same operations as incircle's, so the same error analysis holds.)
  double static_err_ = 0.0;
  double incircle_fast(const Point& a, const Point& b, const Point& c, const Point& d) const {
    const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
    const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
    const double det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                       (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                       (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
    if (det > static_err_ || -det > static_err_) return det;
    return incircle(a, b, c, d);
  }
  std::uint64_t rng_ = 0x9E3779B97F4A7C15ull;
  std::size_t max_steiner_ = 0;
  std::size_t piece_budget_ = 0;

  // Scratch of the recovery methods, kept to avoid reallocations.
  std::vector<VertexId> left_, right_;
  std::vector<HalfEdgeId> left_out_, right_out_;
  std::vector<TriId> slots_;
  std::vector<VertexId> cut_vertices_;
  std::vector<HalfEdgeId> cut_edges_;
  std::vector<std::uint32_t> vstamp_, vpos_;
  std::uint32_t vstamp_now_ = 0;
  // A fresh stamp for vstamp_ (sized to the vertices; cleared on wrap-around).
  std::uint32_t new_vertex_stamp() {
    if (vstamp_.size() < pts_.size()) {
      vstamp_.resize(pts_.size(), 0);
      vpos_.resize(pts_.size(), 0);
    }
    if (++vstamp_now_ == 0) {
      std::fill(vstamp_.begin(), vstamp_.end(), 0);
      vstamp_now_ = 1;
    }
    return vstamp_now_;
  }
  struct Job {
    std::uint32_t lo, hi;
    HalfEdgeId parent;
  };
  std::vector<Job> jobs_;
  std::vector<HalfEdgeId> lawson_stack_;
  std::deque<std::pair<VertexId, VertexId>> queue_;
  std::unordered_set<std::uint64_t> flipped_;
  struct Event {
    EventTime time;
    Quad quad;
    VertexId x, y, p, q;  // edge x->y, apex p on its left, q on its right
  };
  std::vector<Event> events_;  // every event of the current piece
  struct HeapEntry {
    EventTime time;
    std::uint32_t index;  // into events_
  };
  std::vector<HeapEntry> heap_;
  std::vector<std::uint32_t> cavity_stamp_;  // per triangle slot: == stamp_ when in the current cavity
  std::uint32_t stamp_ = 0;
  // A fresh stamp_ for cavity_stamp_ (sized to the slots; cleared on wrap-around).
  void new_cavity_stamp() {
    if (cavity_stamp_.size() < mesh_.num_triangle_slots()) cavity_stamp_.resize(mesh_.num_triangle_slots(), 0);
    if (++stamp_ == 0) {
      std::fill(cavity_stamp_.begin(), cavity_stamp_.end(), 0);
      stamp_ = 1;
    }
  }
};

// The Fast method's first attempt (cdt_chain.cpp): vertices inserted along
// the segment chains, segments as soon as their endpoints are in. Fills
// `mesh` and returns true, or returns false when the flip or walk budget is
// exceeded (the caller starts over). first_copy[v] is the vertex that input
// vertex v became (itself, or an earlier copy of its point).
bool chain_order_cdt(Mesh& mesh, const Pslg& pslg, const CdtOptions& options, CdtStats& stats,
                     std::vector<VertexId>& first_copy);

}  // namespace deltamesh::detail
