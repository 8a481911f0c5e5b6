// Global overlap test of the validator.
//
// Why looking at the boundary edges is enough: the half-edges of the
// counter-clockwise triangles, added up as a 1-chain, cancel in twin pairs
// and leave the boundary half-edges. So for a point p on no edge, the number
// of triangles containing p equals the winding number W(p) of the boundary
// half-edges around p (winding numbers add up over chains; a
// counter-clockwise triangle winds once around its interior points). The
// interiors are pairwise disjoint exactly when W <= 1 everywhere.
//
// One plane sweep over the boundary edges (Shamos and Hoey, "Geometric
// intersection problems", FOCS 1976) finds the leftmost place where two
// boundary edges meet other than at a common endpoint (a crossing, a vertex
// on another edge, edges along each other), and, where there is none, the
// boundary edges split every vertical line into intervals whose winding
// number follows from the edge below: crossing a boundary edge changes W by
// one, up when the mesh lies above it. Every face of the boundary edges'
// arrangement is seen just right of its leftmost point, when its lower and
// upper edges are inserted, so W is checked on every face. O(B log B) for B
// boundary edges, every decision by exact orientation tests; the triangles
// themselves are visited once to collect the boundary, and once more only
// when an overlap was found, to name the second triangle.
#include "validate_overlap.hpp"

#include <algorithm>
#include <numeric>
#include <set>
#include <sstream>
#include <vector>

#include "deltamesh/predicates.hpp"

namespace deltamesh::detail {
namespace {

bool lex_less(const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Closed segments: true when p lies strictly between a and b, given that it
// is on their line (then (x, y) order is the order along the line).
bool strictly_between(const Point& a, const Point& b, const Point& p) { return lex_less(a, p) && lex_less(p, b); }

struct BoundaryEdge {
  Point l, r;       // endpoints, l before r in (x, y) order
  HalfEdgeId half;  // the boundary half-edge (the mesh lies on its left)
  int up;           // +1: the half-edge runs from l to r, so the mesh lies above it; -1: below
};

enum class Contact : std::uint8_t { None, Cross, Touch, Along };

struct ContactInfo {
  Contact kind = Contact::None;
  int touching = -1;  // Touch: 0/1 = l/r of the second edge lies on the first, 2/3 = l/r of the first on the second
};

// How two boundary edges meet, beyond sharing an endpoint (exactly).
ContactInfo contact(const BoundaryEdge& s, const BoundaryEdge& t) {
  const double o1 = orient2d(s.l, s.r, t.l), o2 = orient2d(s.l, s.r, t.r);
  if (o1 == 0 && o2 == 0) {  // on one line: overlap of positive length?
    const Point& lo = lex_less(s.l, t.l) ? t.l : s.l;
    const Point& hi = lex_less(s.r, t.r) ? s.r : t.r;
    return {lex_less(lo, hi) ? Contact::Along : Contact::None, -1};
  }
  const double o3 = orient2d(t.l, t.r, s.l), o4 = orient2d(t.l, t.r, s.r);
  if (((o1 < 0 && o2 > 0) || (o1 > 0 && o2 < 0)) && ((o3 < 0 && o4 > 0) || (o3 > 0 && o4 < 0)))
    return {Contact::Cross, -1};
  if (o1 == 0 && strictly_between(s.l, s.r, t.l)) return {Contact::Touch, 0};
  if (o2 == 0 && strictly_between(s.l, s.r, t.r)) return {Contact::Touch, 1};
  if (o3 == 0 && strictly_between(t.l, t.r, s.l)) return {Contact::Touch, 2};
  if (o4 == 0 && strictly_between(t.l, t.r, s.r)) return {Contact::Touch, 3};
  return {};
}

using Tri = std::array<Point, 3>;

// Interiors of two counter-clockwise triangles intersect (positive area):
// convex polygons with disjoint interiors are separated by the line of an
// edge of one of them (the edges of their Minkowski difference are theirs).
bool interiors_overlap(const Tri& a, const Tri& b) {
  auto separated_by_edges_of = [](const Tri& p, const Tri& q) {
    for (int i = 0; i < 3; ++i) {
      const Point& u = p[i];
      const Point& v = p[(i + 1) % 3];
      if (orient2d(u, v, q[0]) <= 0 && orient2d(u, v, q[1]) <= 0 && orient2d(u, v, q[2]) <= 0) return true;
    }
    return false;
  };
  return !separated_by_edges_of(a, b) && !separated_by_edges_of(b, a);
}

bool inside_or_on(const Tri& t, const Point& p) {
  return orient2d(t[0], t[1], p) >= 0 && orient2d(t[1], t[2], p) >= 0 && orient2d(t[2], t[0], p) >= 0;
}

bool strictly_inside(const Tri& t, const Point& p) {
  return orient2d(t[0], t[1], p) > 0 && orient2d(t[1], t[2], p) > 0 && orient2d(t[2], t[0], p) > 0;
}

class Sweep {
 public:
  explicit Sweep(const Mesh& m) : mesh_(m), status_(Below{this}) {}

  std::optional<OverlapFinding> run() {
    collect();
    const std::size_t n = edges_.size();
    std::vector<std::uint32_t> by_l(n), by_r(n);
    std::iota(by_l.begin(), by_l.end(), 0u);
    std::iota(by_r.begin(), by_r.end(), 0u);
    std::sort(by_l.begin(), by_l.end(), [&](auto a, auto b) { return lex_less(edges_[a].l, edges_[b].l); });
    std::sort(by_r.begin(), by_r.end(), [&](auto a, auto b) { return lex_less(edges_[a].r, edges_[b].r); });
    where_.resize(n);
    w_below_.assign(n, 0);
    std::size_t i = 0, j = 0;
    while (j < n) {
      Point p = edges_[by_r[j]].r;
      if (i < n && lex_less(edges_[by_l[i]].l, p)) p = edges_[by_l[i]].l;
      const std::size_t j0 = j, i0 = i;
      while (j < n && edges_[by_r[j]].r == p) ++j;
      while (i < n && edges_[by_l[i]].l == p) ++i;
      // Edges ending at p leave; with none starting there, their neighbours
      // below and above become adjacent.
      std::uint32_t below = kNone, above = kNone;
      for (std::size_t k = j0; k < j; ++k) removed_mark(by_r[k], true);
      for (std::size_t k = j0; k < j; ++k) {
        const auto it = where_[by_r[k]];
        if (it != status_.begin() && !removing(*std::prev(it))) below = *std::prev(it);
        if (std::next(it) != status_.end() && !removing(*std::next(it))) above = *std::next(it);
      }
      for (std::size_t k = j0; k < j; ++k) {
        status_.erase(where_[by_r[k]]);
        removed_mark(by_r[k], false);
      }
      if (i0 == i) {
        if (below != kNone && above != kNone)
          if (auto f = check_pair(below, above)) return f;
        continue;
      }
      // Edges starting at p enter from the bottom up, so each one's lower
      // neighbour is final when its winding numbers are computed.
      std::sort(by_l.begin() + i0, by_l.begin() + i, [&](auto a, auto b) {
        return orient2d(p, edges_[a].r, edges_[b].r) > 0;
      });
      for (std::size_t k = i0 + 1; k < i; ++k)
        if (orient2d(p, edges_[by_l[k - 1]].r, edges_[by_l[k]].r) == 0) return report_contact(by_l[k - 1], by_l[k]);
      for (std::size_t k = i0; k < i; ++k)
        if (auto f = insert(by_l[k])) return f;
    }
    return std::nullopt;
  }

 private:
  struct Below {
    const Sweep* sweep;
    bool operator()(std::uint32_t a, std::uint32_t b) const { return sweep->below(a, b); }
  };
  using Status = std::set<std::uint32_t, Below>;

  // Boundary half-edges: real ones without a twin, and the twins of ghost
  // triangles' finite edges (reached from the few ghosts, so the pass over
  // the triangles reads memory in order).
  void collect() {
    auto add = [&](HalfEdgeId e) {
      const Point& a = mesh_.point(mesh_.origin(e));
      const Point& b = mesh_.point(mesh_.dest(e));
      if (lex_less(a, b)) edges_.push_back({a, b, e, +1});
      else edges_.push_back({b, a, e, -1});
    };
    for (TriId t = 0; t < mesh_.num_triangle_slots(); ++t) {
      if (mesh_.is_dead(t)) continue;
      const bool ghost = mesh_.is_ghost(t);
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId e = 3 * t + i;
        const HalfEdgeId f = mesh_.twin(e);
        if (!ghost) {
          if (f == kNone) add(e);
        } else if (mesh_.origin(e) != kInfinite && mesh_.dest(e) != kInfinite && f != kNone &&
                   mesh_.is_real(tri_of(f))) {
          add(f);
        }
      }
    }
    removing_.assign(edges_.size(), 0);
  }

  bool removing(std::uint32_t s) const { return removing_[s] != 0; }
  void removed_mark(std::uint32_t s, bool on) { removing_[s] = on ? 1 : 0; }

  // Status order: is edge a below edge b where both cross the sweep line?
  // Decided at the left endpoint of the one that starts later (the order of
  // two edges that do not meet is the same all along). A tie is a contact,
  // kept for the caller; ids then keep the order strict.
  bool below(std::uint32_t a, std::uint32_t b) const {
    if (a == b) return false;
    const BoundaryEdge& s = edges_[a];
    const BoundaryEdge& t = edges_[b];
    const bool t_later = !lex_less(t.l, s.l);
    const BoundaryEdge& first = t_later ? s : t;
    const BoundaryEdge& second = t_later ? t : s;
    double o = first.l == second.l ? orient2d(first.l, first.r, second.r) : orient2d(first.l, first.r, second.l);
    if (o == 0) {
      if (!flagged_) flagged_ = {a, b};
      o = orient2d(first.l, first.r, second.r);
    }
    if (o == 0) return a < b;
    // second above first: first is below
    return t_later ? o > 0 : o < 0;
  }

  std::optional<OverlapFinding> insert(std::uint32_t e) {
    const auto it = status_.insert(e).first;
    where_[e] = it;
    if (flagged_) return report_contact(flagged_->first, flagged_->second);
    int wb = 0;
    if (it != status_.begin()) {
      const std::uint32_t p = *std::prev(it);
      if (auto f = check_pair(p, e)) return f;
      wb = w_below_[p] + edges_[p].up;
    }
    if (std::next(it) != status_.end())
      if (auto f = check_pair(e, *std::next(it))) return f;
    w_below_[e] = wb;
    const int wa = wb + edges_[e].up;
    if (std::max(wb, wa) >= 2) return report_overlap_at(e);
    if (std::min(wb, wa) < 0) {
      // Cannot happen when twins are consistent: W counts triangles.
      OverlapFinding f;
      f.conflict.first = tri_of(edges_[e].half);
      f.message = "the boundary winds " + std::to_string(std::min(wb, wa)) + " times next to boundary edge " +
                  edge_name(edges_[e].half) + " of triangle " + tri_name(f.conflict.first) +
                  " (the boundary half-edges are inconsistent)";
      return f;
    }
    return std::nullopt;
  }

  std::optional<OverlapFinding> check_pair(std::uint32_t a, std::uint32_t b) const {
    if (contact(edges_[a], edges_[b]).kind == Contact::None) return std::nullopt;
    return report_contact(a, b);
  }

  Tri corners(TriId t) const {
    const auto v = mesh_.triangle(t);
    return {mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2])};
  }

  std::string tri_name(TriId t) const {
    const auto v = mesh_.triangle(t);
    std::ostringstream out;
    out << t << " (" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return out.str();
  }

  std::string edge_name(HalfEdgeId e) const {
    return std::to_string(mesh_.origin(e)) + "-" + std::to_string(mesh_.dest(e));
  }

  // The vertex of boundary edge s at its left (0) or right (1) end.
  VertexId end_vertex(const BoundaryEdge& s, int right) const {
    const bool origin = (s.up > 0) == (right == 0);
    return origin ? mesh_.origin(s.half) : mesh_.dest(s.half);
  }

  OverlapFinding report_contact(std::uint32_t a, std::uint32_t b) const {
    const BoundaryEdge& s = edges_[a];
    const BoundaryEdge& t = edges_[b];
    const TriId ts = tri_of(s.half), tt = tri_of(t.half);
    OverlapFinding f;
    const bool overlap = ts != tt && interiors_overlap(corners(ts), corners(tt));
    f.conflict.kind = overlap ? TriangleConflict::Kind::Overlap : TriangleConflict::Kind::BoundaryContact;
    f.conflict.first = std::min(ts, tt);
    f.conflict.second = std::max(ts, tt);
    std::ostringstream out;
    out << "triangles " << tri_name(f.conflict.first) << " and " << tri_name(f.conflict.second)
        << (overlap ? " overlap: " : " meet where the mesh does not connect them: ");
    const std::string detail = overlap ? overlap_detail(f.conflict.first, f.conflict.second) : std::string();
    if (!detail.empty()) {
      out << detail;
    } else {
      out << contact_detail(s, t, !overlap);
    }
    f.message = out.str();
    return f;
  }

  // Where boundary edges s and t meet; with `junction`, say that a vertex
  // inside an edge means the edge was not split there.
  std::string contact_detail(const BoundaryEdge& s, const BoundaryEdge& t, bool junction) const {
    const ContactInfo c = contact(s, t);
    const std::string es = edge_name(s.half), et = edge_name(t.half);
    const char* note = junction ? " (a T-junction: the edge is not split there)" : "";
    switch (c.kind) {
      case Contact::Cross:
        return "their boundary edges " + es + " and " + et + " cross";
      case Contact::Touch: {
        const BoundaryEdge& on = c.touching < 2 ? s : t;
        const BoundaryEdge& at = c.touching < 2 ? t : s;
        return "vertex " + std::to_string(end_vertex(at, c.touching % 2)) + " of boundary edge " +
               edge_name(at.half) + " lies inside boundary edge " + edge_name(on.half) + note;
      }
      case Contact::Along: {
        std::string text = "their boundary edges " + es + " and " + et + " lie along each other";
        if (s.l == t.l && s.r == t.r)
          return text + " end to end" + (junction ? " (one edge twice, without a twin link)" : "");
        for (int k = 0; k < 4; ++k) {
          const BoundaryEdge& on = k < 2 ? s : t;
          const BoundaryEdge& at = k < 2 ? t : s;
          const Point& p = k % 2 ? at.r : at.l;
          if (strictly_between(on.l, on.r, p))
            return text + "; vertex " + std::to_string(end_vertex(at, k % 2)) + " lies inside " + edge_name(on.half) +
                   note;
        }
        return text;
      }
      case Contact::None:
        break;
    }
    return "boundary edges " + es + " and " + et + " cannot be ordered by the sweep";
  }

  // The boundary winds twice or more just beside edge e, on the mesh's side:
  // the triangle of e overlaps another there; find one to name.
  OverlapFinding report_overlap_at(std::uint32_t e) const {
    const TriId t = tri_of(edges_[e].half);
    const Tri a = corners(t);
    OverlapFinding f;
    f.conflict.first = t;
    for (TriId u = 0; u < mesh_.num_triangle_slots(); ++u) {
      if (u == t || !mesh_.is_real(u)) continue;
      const Tri b = corners(u);
      if (!interiors_overlap(a, b)) continue;
      f.conflict.first = std::min(t, u);
      f.conflict.second = std::max(t, u);
      const std::string detail = overlap_detail(f.conflict.first, f.conflict.second);
      f.message = "triangles " + tri_name(f.conflict.first) + " and " + tri_name(f.conflict.second) +
                  " overlap: " + (detail.empty() ? "their interiors intersect" : detail);
      return f;
    }
    f.message = "triangle " + tri_name(t) + " overlaps another triangle beside its boundary edge " +
                edge_name(edges_[e].half) + " (the boundary winds twice there)";
    return f;
  }

  // How two overlapping triangles lie, when it has a short name.
  std::string overlap_detail(TriId t, TriId u) const {
    const Tri a = corners(t), b = corners(u);
    auto has = [](const Tri& x, const Point& p) { return x[0] == p || x[1] == p || x[2] == p; };
    if (has(a, b[0]) && has(a, b[1]) && has(a, b[2])) return "the same triangle twice";
    if (inside_or_on(a, b[0]) && inside_or_on(a, b[1]) && inside_or_on(a, b[2]))
      return "triangle " + std::to_string(u) + " lies inside triangle " + std::to_string(t);
    if (inside_or_on(b, a[0]) && inside_or_on(b, a[1]) && inside_or_on(b, a[2]))
      return "triangle " + std::to_string(t) + " lies inside triangle " + std::to_string(u);
    for (int k = 0; k < 3; ++k) {
      if (strictly_inside(a, b[k]))
        return "vertex " + std::to_string(mesh_.triangle(u)[k]) + " lies inside triangle " + std::to_string(t);
      if (strictly_inside(b, a[k]))
        return "vertex " + std::to_string(mesh_.triangle(t)[k]) + " lies inside triangle " + std::to_string(u);
    }
    return {};
  }

  const Mesh& mesh_;
  std::vector<BoundaryEdge> edges_;
  std::vector<char> removing_;
  std::vector<int> w_below_;  // winding number just below each edge in the status
  Status status_;
  std::vector<Status::iterator> where_;
  mutable std::optional<std::pair<std::uint32_t, std::uint32_t>> flagged_;  // a tie met by the status order
};

}  // namespace

std::optional<OverlapFinding> find_overlap(const Mesh& mesh) { return Sweep(mesh).run(); }

}  // namespace deltamesh::detail
