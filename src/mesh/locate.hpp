// Point location and segment walks, written once.
//   visibility_walk - from a triangle towards a point: leave each triangle
//     through an edge that has the point strictly on its far side
//     (Devillers, Pion, Teillaud 2002, "Walking in a triangulation"); the
//     order the edges are tried in is a policy (fixed, or random, which rules
//     out cycles on any triangulation);
//   walk_line - the straight walk along a line pa -> pb, through each edge
//     it crosses, up to its target (Target: a vertex, or a point anywhere)
//     or an edge the caller stops at (a constraint). Two ways in:
//     segment_exit + walk_segment - along a segment a -> b from vertex a:
//       the triangle around a it leaves through (or the edge it runs
//       along), then every edge it crosses up to b or a vertex on it;
//     line_exit + walk_line<PointTarget> - from a point strictly inside a
//       triangle towards any point c (refinement's Steiner points).
// Every decision is an exact orientation. Header-only: the hot insertion
// loops inline them.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "deltamesh/errors.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/flip.hpp"

namespace deltamesh::detail {

// Small deterministic generator for the walks' random edge orders.
inline std::uint32_t walk_random(std::uint64_t& s) {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return static_cast<std::uint32_t>(s >> 32);
}

// t itself, or (for a ghost) the real triangle across its hull edge.
inline TriId real_triangle_near(const VertexId* tv, const HalfEdgeId* tw, TriId t) {
  for (unsigned i = 0; i < 3; ++i)
    if (tv[3 * t + i] == kInfinite) return tri_of(tw[3 * t + kNextIndex[i]]);
  return t;
}

// Edge orders: fill cand with the local indices (0..2) of the triangle's
// edges to try, given the local index `from` of the edge the walk entered
// by (kNoEntry at the start; p is strictly beyond it, so it is never an
// exit). Return how many.
inline constexpr unsigned kNoEntry = 3;

// The fixed order: 0, 1, 2, then the two edges after the entry edge. Cannot
// cycle in a Delaunay triangulation (Edelsbrunner 1990).
struct FixedEdgeOrder {
  int operator()(unsigned from, unsigned* cand) const {
    if (from == kNoEntry) {
      cand[0] = 0;
      cand[1] = 1;
      cand[2] = 2;
      return 3;
    }
    cand[0] = kNextIndex[from];
    cand[1] = kPrevIndex[from];
    return 2;
  }
};

// A random rotation of the three edges per triangle (the entry edge skipped).
struct RandomRotationOrder {
  std::uint64_t state;
  int operator()(unsigned from, unsigned* cand) {
    const std::uint32_t r = walk_random(state) % 3;
    int n = 0;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const unsigned i = (r + k) % 3;
      if (i != from) cand[n++] = i;
    }
    return n;
  }
};

// A random rotation at the start, then a coin toss between the two edges
// after the entry edge; the generator's state lives with the caller.
struct RandomPairOrder {
  std::uint64_t& state;
  int operator()(unsigned from, unsigned* cand) {
    const std::uint32_t r = walk_random(state);
    if (from == kNoEntry) {
      for (std::uint32_t i = 0; i < 3; ++i) cand[i] = static_cast<std::uint32_t>(r + i) % 3;
      return 3;
    }
    const unsigned e1 = kNextIndex[from], e2 = kPrevIndex[from];
    cand[0] = (r & 1) ? e1 : e2;
    cand[1] = (r & 1) ? e2 : e1;
    return 2;
  }
};

struct WalkResult {
  Location loc;           // tri == kNone (kind Outside) when the step bound ran out
  std::size_t steps = 0;  // triangles visited
};

// Visibility walk from real triangle t to p, at most max_steps + 1 triangles.
// Ends InTriangle / OnEdge / OnVertex in the triangle holding p, or Outside:
// at the ghost beyond the hull edge p sees from outside (tri = the ghost,
// edge = its hull half-edge), or, in a compacted mesh, at the boundary edge
// with no twin (tri = the last triangle, edge = that half-edge).
template <class Order>
inline WalkResult visibility_walk(const VertexId* tv, const HalfEdgeId* tw, const Point* pts, const Point& p, TriId t,
                                  Order&& order, std::size_t max_steps = std::numeric_limits<std::size_t>::max() - 1) {
  WalkResult r;
  Location& loc = r.loc;
  unsigned from = kNoEntry;
  for (std::size_t steps = 0; steps <= max_steps; ++steps) {
    ++r.steps;
    const HalfEdgeId base = 3 * t;
    const VertexId v[3] = {tv[base], tv[base + 1], tv[base + 2]};
    unsigned cand[3];
    const int nc = order(from, cand);
    unsigned exit = kNoEntry, zero = kNoEntry;
    int zeros = 0;
    for (int k = 0; k < nc; ++k) {
      const unsigned i = cand[k];
      const double o = orient2d(pts[v[i]], pts[v[kNextIndex[i]]], p);
      if (o < 0) {
        exit = i;
        break;
      }
      if (o == 0) {
        ++zeros;
        zero = i;
      }
    }
    if (exit == kNoEntry) {
      loc.tri = t;
      if (zeros == 0) {
        loc.kind = Location::Kind::InTriangle;
      } else if (zeros == 1) {
        loc.kind = Location::Kind::OnEdge;
        loc.edge = base + zero;
      } else {  // two zero orientations: p is the vertex the two edges share
        loc.kind = Location::Kind::OnVertex;
        for (unsigned i = 0; i < 3 && loc.vertex == kNone; ++i)
          if (pts[v[i]] == p) {
            loc.vertex = v[i];
            loc.edge = base + i;
          }
        if (loc.vertex == kNone)
          throw InternalError("visibility_walk", "point location met a degenerate triangle " + std::to_string(t));
      }
      return r;
    }
    const HalfEdgeId across = tw[base + exit];
    if (across == kNone) {  // compacted mesh: p is outside the domain here
      loc.kind = Location::Kind::Outside;
      loc.tri = t;
      loc.edge = base + exit;
      return r;
    }
    t = tri_of(across);
    from = across - 3 * t;
    if (tv[3 * t + kPrevIndex[from]] == kInfinite) {  // entered by a real edge: a ghost's apex is at infinity
      loc.kind = Location::Kind::Outside;
      loc.tri = t;
      loc.edge = across;
      return r;
    }
  }
  loc.kind = Location::Kind::Outside;
  loc.tri = kNone;
  return r;
}

// u is collinear with a and b (exactly): is it on the ray from a towards b?
// Differences of doubles have exact signs, so this is exact.
inline bool same_direction(const Point& a, const Point& u, const Point& b) {
  auto sgn = [](double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); };
  return sgn(u.x - a.x) == sgn(b.x - a.x) && sgn(u.y - a.y) == sgn(b.y - a.y);
}

// How a segment on line (pa, pb) leaves vertex v (on that line, before pb).
struct SegmentExit {
  enum class Kind : std::uint8_t {
    Along,   // `edge` = v -> `vertex` runs along the segment
    Enters,  // the segment enters the triangle of `edge` = u -> w, u right of it, w left
    None,    // no triangle around v meets it (a broken triangulation)
  };
  Kind kind = Kind::None;
  HalfEdgeId edge = kNone;
  VertexId vertex = kNone;
};

// Rotary traversal around v (from its out-edge, counter-clockwise) for the
// triangle the segment towards pb leaves v through, or a neighbour exactly on
// it. Orientations are exact, so exactly one exists in a valid closed
// triangulation. At most `limit` triangles are looked at.
inline SegmentExit segment_exit(const VertexId* tv, const HalfEdgeId* tw, const Point* pts, HalfEdgeId start,
                                const Point& pv, const Point& pa, const Point& pb, std::size_t limit) {
  SegmentExit out;
  HalfEdgeId e = start;
  VertexId u = tv[next_edge(e)];
  double ou = u == kInfinite ? 0.0 : orient2d(pa, pb, pts[u]);
  std::size_t guard = 0;
  do {
    const VertexId w = tv[prev_edge(e)];
    const double ow = w == kInfinite ? 0.0 : orient2d(pa, pb, pts[w]);
    if (u != kInfinite) {
      if (ou == 0.0 && same_direction(pv, pts[u], pb)) {
        out.kind = SegmentExit::Kind::Along;
        out.edge = e;
        out.vertex = u;
        return out;
      }
      if (ou < 0.0 && w != kInfinite && ow > 0.0) {
        out.kind = SegmentExit::Kind::Enters;
        out.edge = next_edge(e);  // u -> w
        return out;
      }
    }
    e = tw[prev_edge(e)];
    u = w;
    ou = ow;
  } while (e != start && ++guard < limit);
  return out;
}

struct SegmentWalk {
  enum class Kind : std::uint8_t {
    Reached,    // the walk reached its target (PointTarget: `edge` = the
                // exit edge of the triangle holding it)
    OnVertex,   // `vertex` lies exactly on the open segment (VertexTarget)
    Stopped,    // the caller's visit refused crossed half-edge `edge`
    LeftHull,   // the line left the triangulation (a broken invariant)
    Overrun,    // more than `limit` steps (a broken invariant)
  };
  Kind kind = Kind::Overrun;
  HalfEdgeId edge = kNone;
  VertexId vertex = kNone;
};

// What walk_line walks to. A target says whether apex z of the triangle just
// entered is the end (at), whether the line ends before leaving that
// triangle through half-edge h (before), and whether a vertex exactly on the
// line ends the walk (kStopOnLine) or counts as left of it.

// Vertex b, the end of a segment: a vertex on the open segment stops the walk.
struct VertexTarget {
  static constexpr bool kStopOnLine = true;
  VertexId b;
  bool at(VertexId z) const { return z == b; }
  bool before(const VertexId*, const Point*, HalfEdgeId) const { return false; }
};

// Point c anywhere: the walk ends in the triangle whose exit edge does not
// have c strictly beyond it. A vertex exactly on the line counts as left of
// it (a symbolic perturbation), so each step is one exact orientation.
struct PointTarget {
  static constexpr bool kStopOnLine = false;
  Point c;
  double side = 0.0;  // at the end: orient2d of the exit edge and c (0: c on it)
  bool at(VertexId) const { return false; }
  bool before(const VertexId* tv, const Point* pts, HalfEdgeId h) {
    side = orient2d(pts[tv[h]], pts[tv[next_edge(h)]], c);
    return side >= 0;
  }
};

// The straight walk along the line from pa towards pb from half-edge
// h = u -> w that it crosses (u right, w left of it), through each triangle
// it crosses, up to the target. visit(h) is called on each crossed half-edge
// before the walk goes through it; returning false stops the walk there.
template <class Target, class Visit>
inline SegmentWalk walk_line(const VertexId* tv, const HalfEdgeId* tw, const Point* pts, const Point& pa,
                             const Point& pb, Target& target, HalfEdgeId h, Visit&& visit, std::size_t limit) {
  SegmentWalk out;
  for (std::size_t guard = 0; guard < limit; ++guard) {
    if (!visit(h)) {
      out.kind = SegmentWalk::Kind::Stopped;
      out.edge = h;
      return out;
    }
    const HalfEdgeId g = tw[h];  // w -> u in the next triangle (w, u, z)
    const VertexId z = tv[prev_edge(g)];
    if (target.at(z)) {
      out.kind = SegmentWalk::Kind::Reached;
      return out;
    }
    if (z == kInfinite) {
      out.kind = SegmentWalk::Kind::LeftHull;
      return out;
    }
    const double oz = orient2d(pa, pb, pts[z]);
    if constexpr (Target::kStopOnLine) {
      if (oz == 0.0) {
        out.kind = SegmentWalk::Kind::OnVertex;
        out.vertex = z;
        return out;
      }
    }
    h = oz < 0.0 ? prev_edge(g) : next_edge(g);
    if (target.before(tv, pts, h)) {
      out.kind = SegmentWalk::Kind::Reached;
      out.edge = h;
      return out;
    }
  }
  return out;
}

// The walk along the segment from pa to vertex b (point pb), from half-edge
// h that segment_exit found.
template <class Visit>
inline SegmentWalk walk_segment(const VertexId* tv, const HalfEdgeId* tw, const Point* pts, const Point& pa,
                                const Point& pb, VertexId b, HalfEdgeId h, Visit&& visit, std::size_t limit) {
  VertexTarget target{b};
  return walk_line(tv, tw, pts, pa, pb, target, h, visit, limit);
}

// The half-edge u -> w of triangle t that the line from pa (strictly inside
// t) towards pb leaves t through: u right of the line, w left, a vertex on
// it counting as left (PointTarget's rule). kNone when pa == pb.
inline HalfEdgeId line_exit(const VertexId* tv, const Point* pts, TriId t, const Point& pa, const Point& pb) {
  const HalfEdgeId base = 3 * t;
  const bool left[3] = {orient2d(pa, pb, pts[tv[base]]) >= 0, orient2d(pa, pb, pts[tv[base + 1]]) >= 0,
                        orient2d(pa, pb, pts[tv[base + 2]]) >= 0};
  HalfEdgeId exit = kNone;
  for (unsigned i = 0; i < 3; ++i)
    if (!left[i] && left[kNextIndex[i]]) exit = base + i;
  return exit;
}

}  // namespace deltamesh::detail
