#include "deltamesh/validate.hpp"
#include "core/plural.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <unordered_map>

#include "algo/normalize.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "mesh/edge_rules.hpp"
#include "validate_overlap.hpp"

namespace deltamesh {

std::string CheckReport::summary() const {
  std::ostringstream out;
  if (ok()) {
    out << "mesh is valid: " << count_of(triangles, "triangle", "triangles") << ", " << count_of(edges, "edge", "edges")
        << ", " << count_of(vertices_used, "vertex", "vertices");
    if (segments_checked > 0) out << ", " << count_of(segments_checked, "segment", "segments") << " present";
    if (!delaunay_checked) out << "; the Delaunay property was not checked";
  } else {
    out << problems.size() << " problem(s):";
    for (const std::string& p : problems) out << "\n  " << p;
  }
  return out.str();
}

namespace {

class Checker {
 public:
  Checker(const Mesh& m, const CheckOptions& o, CheckReport& r) : mesh_(m), opt_(o), rep_(r) {}

  void run() {
    if (!check_indices()) return;
    check_twins();
    if (!rep_.ok()) return;  // later checks assume a consistent topology
    check_orientation();
    // The overlap test counts triangles by the boundary's winding number,
    // which needs consistent twins and counter-clockwise triangles.
    if (rep_.ok()) check_overlap();
    check_vertex_edges();
    if (opt_.delaunay) check_delaunay();
    check_boundary_and_euler();
    if (opt_.pslg) check_segments(*opt_.pslg);
  }

 private:
  template <class... A>
  void problem(const A&... parts) {
    if (rep_.problems.size() >= opt_.max_problems) return;
    std::ostringstream out;
    (out << ... << parts);
    rep_.problems.push_back(out.str());
  }

  // A real half-edge whose twin is missing or a ghost lies on the boundary.
  bool on_boundary(HalfEdgeId e) const {
    const HalfEdgeId t = mesh_.twin(e);
    return t == kNone || mesh_.is_ghost(tri_of(t));
  }

  bool check_indices() {
    const std::size_t nv = mesh_.num_vertices();
    for (TriId t = 0; t < mesh_.num_triangle_slots(); ++t) {
      if (mesh_.is_dead(t)) continue;
      for (VertexId v : mesh_.triangle(t))
        if (v != kInfinite && v >= nv) problem("triangle ", t, " refers to vertex ", v, " of ", nv);
    }
    return rep_.ok();
  }

  void check_twins() {
    const std::size_t slots = mesh_.num_triangle_slots();
    bool closed = false;  // ghost triangles close the mesh: every edge has a twin
    for (TriId t = 0; t < slots && !closed; ++t) closed = !mesh_.is_dead(t) && mesh_.is_ghost(t);
    for (TriId t = 0; t < slots; ++t) {
      if (mesh_.is_dead(t)) continue;
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId e = 3 * t + i;
        const HalfEdgeId f = mesh_.twin(e);
        if (f == kNone) {
          if (closed)
            problem("half-edge ", e, " of triangle ", t, " has no twin in a closed triangulation");
          continue;
        }
        if (f >= 3 * slots || mesh_.is_dead(tri_of(f))) {
          problem("half-edge ", e, " has twin ", f, " that is not a live half-edge");
        } else if (mesh_.twin(f) != e) {
          problem("twin of twin of half-edge ", e, " is ", mesh_.twin(f), ", not itself");
        } else if (mesh_.origin(f) != mesh_.dest(e) || mesh_.dest(f) != mesh_.origin(e)) {
          problem("half-edge ", e, " (", mesh_.origin(e), "->", mesh_.dest(e), ") and its twin (",
                  mesh_.origin(f), "->", mesh_.dest(f), ") disagree");
        }
        if (mesh_.is_constrained(e) != mesh_.is_constrained(f) && f < 3 * slots)
          problem("edge ", mesh_.origin(e), "-", mesh_.dest(e), " is constrained on one side only");
      }
    }
  }

  void check_orientation() {
    for (TriId t : mesh_.triangles()) {
      ++rep_.triangles;
      const auto v = mesh_.triangle(t);
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
        problem("triangle ", t, " repeats a vertex");
        continue;
      }
      if (!(orient2d(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2])) > 0))
        problem("triangle ", t, " (", v[0], ", ", v[1], ", ", v[2], ") is not counter-clockwise");
    }
  }

  void check_overlap() {
    if (auto found = detail::find_overlap(mesh_)) {
      rep_.conflicts.push_back(found->conflict);
      problem(found->message);
    }
  }

  // Real triangles met rotating counter-clockwise from e until a boundary
  // (or back at e); `closed` tells which.
  std::uint32_t fan_size(HalfEdgeId e, std::uint32_t limit, bool& closed) const {
    std::uint32_t seen = 0;
    closed = true;
    HalfEdgeId g = e;
    do {
      if (mesh_.is_real(tri_of(g))) ++seen;
      else closed = false;
      g = mesh_.rotate_ccw(g);
    } while (g != kNone && g != e && seen <= limit);
    if (g == kNone) closed = false;
    return seen;
  }

  // Each fan at a pinch vertex starts along a boundary edge; the direction
  // just counter-clockwise of it must lie in exactly one triangle around v
  // (half-open angular cones, decided by exact orientations).
  bool pinch_fans_disjoint(VertexId v, HalfEdgeId first, const std::vector<HalfEdgeId>& next_out) const {
    std::vector<HalfEdgeId> around;  // one half-edge out of v per triangle
    for (HalfEdgeId b = first; b != kNone; b = next_out[b]) {
      HalfEdgeId g = b;
      do {
        if (mesh_.is_real(tri_of(g))) around.push_back(g);
        g = mesh_.rotate_ccw(g);
      } while (g != kNone && g != b && around.size() <= mesh_.num_triangle_slots());
    }
    const Point& pv = mesh_.point(v);
    for (HalfEdgeId b = first; b != kNone; b = next_out[b]) {
      const Point& d = mesh_.point(mesh_.dest(b));
      int cover = 0;
      for (const HalfEdgeId g : around) {
        const Point& x = mesh_.point(mesh_.dest(g));
        const Point& y = mesh_.point(mesh_.origin(prev_edge(g)));
        if (orient2d(pv, x, d) >= 0 && orient2d(pv, d, y) > 0) ++cover;
      }
      if (cover != 1) return false;
    }
    return true;
  }

  void check_vertex_edges() {
    const std::size_t nv = mesh_.num_vertices();
    std::vector<std::uint32_t> incident(nv, 0);
    for (TriId t : mesh_.triangles()) {
      for (VertexId v : mesh_.triangle(t)) ++incident[v];
    }
    // Boundary out-edges per vertex: a carved mesh may pinch at a vertex
    // (two holes touching there), which then has one fan per boundary edge.
    std::vector<HalfEdgeId> first_boundary(nv, kNone), next_boundary_out;
    next_boundary_out.assign(mesh_.triangle_vertices().size(), kNone);
    for (TriId t : mesh_.triangles()) {
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId e = 3 * t + i;
        if (!on_boundary(e)) continue;
        const VertexId v = mesh_.origin(e);
        next_boundary_out[e] = first_boundary[v];
        first_boundary[v] = e;
      }
    }
    for (VertexId v = 0; v < nv; ++v) {
      const HalfEdgeId e = mesh_.out_edge(v);
      if (incident[v] == 0) {
        if (e != kNone && e < mesh_.triangle_vertices().size() && !mesh_.is_dead(tri_of(e)) &&
            mesh_.is_real(tri_of(e)))
          problem("vertex ", v, " is in no triangle but has out-edge ", e);
        continue;
      }
      ++rep_.vertices_used;
      if (e == kNone || e >= mesh_.triangle_vertices().size() || mesh_.is_dead(tri_of(e))) {
        problem("vertex ", v, " is in ", incident[v], " triangles but has no valid out-edge");
        continue;
      }
      if (mesh_.origin(e) != v) {
        problem("out-edge ", e, " of vertex ", v, " starts at ", mesh_.origin(e));
        continue;
      }
      // Rotary traversal from the out-edge must meet every real triangle
      // around v once, or, at a pinch vertex, the fans from each of its
      // boundary out-edges together must.
      bool closed_fan;
      const std::uint32_t seen = fan_size(e, incident[v], closed_fan);
      if (seen != incident[v]) {
        std::uint32_t fans = 0, total = 0;
        for (HalfEdgeId b = first_boundary[v]; b != kNone; b = next_boundary_out[b]) {
          bool closed;
          ++fans;
          total += fan_size(b, incident[v], closed);
        }
        if (fans < 2 || total != incident[v]) {
          problem("rotation around vertex ", v, " meets ", seen, " of its ", incident[v], " triangles");
        } else if (!pinch_fans_disjoint(v, first_boundary[v], next_boundary_out)) {
          problem("the fans of triangles at vertex ", v, " overlap");
        } else {
          extra_fans_ += fans - 1;
        }
        continue;
      }
      if (!closed_fan) continue;
      // The triangles of a closed fan cover the direction +x exactly once
      // around an interior vertex; y comparisons decide it exactly.
      const Point& pv = mesh_.point(v);
      std::uint32_t wraps = 0;
      HalfEdgeId g = e;
      do {
        const Point& a = mesh_.point(mesh_.dest(g));
        const Point& b = mesh_.point(mesh_.origin(prev_edge(g)));
        if (a.y <= pv.y && b.y > pv.y) ++wraps;
        g = mesh_.rotate_ccw(g);
      } while (g != e);
      if (wraps != 1) problem("the triangles around vertex ", v, " wind ", wraps, " times around it (overlap)");
    }
  }

  void check_delaunay() {
    for (TriId t : mesh_.triangles()) {
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId e = 3 * t + i;
        const HalfEdgeId f = real_twin(mesh_, e);
        if (f == kNone || f < e || mesh_.is_constrained(e)) continue;
        const Point& a = mesh_.point(mesh_.origin(e));
        const Point& b = mesh_.point(mesh_.dest(e));
        const Point& c = mesh_.point(mesh_.origin(prev_edge(e)));
        const Point& d = mesh_.point(mesh_.origin(prev_edge(f)));
        if (incircle(a, b, c, d) > 0)
          problem("edge ", mesh_.origin(e), "-", mesh_.dest(e), " is not locally Delaunay (vertex ",
                  mesh_.origin(prev_edge(f)), " lies inside the circumcircle of triangle ", t, ")");
      }
    }
  }

  // The boundary half-edge that follows boundary half-edge e (they share dest(e)).
  HalfEdgeId next_boundary(HalfEdgeId e) const {
    HalfEdgeId g = next_edge(e);  // out of dest(e), inside the mesh
    for (std::size_t guard = 0; guard < 3 * mesh_.num_triangle_slots(); ++guard) {
      if (on_boundary(g)) return g;
      g = next_edge(mesh_.twin(g));  // clockwise around dest(e)
    }
    return kNone;
  }

  void check_boundary_and_euler() {
    std::size_t edges = 0, boundary = 0;
    for (TriId t : mesh_.triangles()) {
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId e = 3 * t + i;
        if (on_boundary(e)) {
          ++edges;
          ++boundary;
        } else if (mesh_.twin(e) > e) {
          ++edges;
        }
      }
    }
    rep_.edges = edges;
    // Walk boundary loops; check convexity where asked.
    std::vector<char> done(3 * mesh_.num_triangle_slots(), 0);
    std::size_t loops = 0;
    for (TriId t : mesh_.triangles()) {
      for (int i = 0; i < 3; ++i) {
        const HalfEdgeId start = 3 * t + i;
        if (done[start] || !on_boundary(start)) continue;
        ++loops;
        HalfEdgeId e = start;
        std::size_t steps = 0;
        do {
          done[e] = 1;
          const HalfEdgeId n = next_boundary(e);
          if (n == kNone) {
            problem("boundary walk from half-edge ", e, " is broken");
            return;
          }
          if (opt_.convex_hull &&
              orient2d(mesh_.point(mesh_.origin(e)), mesh_.point(mesh_.dest(e)), mesh_.point(mesh_.dest(n))) < 0)
            problem("boundary turns right at vertex ", mesh_.dest(e), ": the hull is not convex");
          e = n;
        } while (e != start && ++steps <= boundary);
        if (e != start) problem("boundary loop from half-edge ", start, " does not close");
      }
    }
    if (opt_.convex_hull && loops > 1) problem("the mesh has ", loops, " boundary loops, not one convex hull");
    // Components by flood fill over twins; Euler: V - E + F = 2C - loops.
    std::vector<char> seen(mesh_.num_triangle_slots(), 0);
    std::size_t components = 0;
    std::vector<TriId> stack;
    for (TriId t = 0; t < mesh_.num_triangle_slots(); ++t) {
      if (!mesh_.is_real(t) || seen[t]) continue;
      ++components;
      stack.push_back(t);
      seen[t] = 1;
      while (!stack.empty()) {
        const TriId u = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
          const HalfEdgeId f = mesh_.twin(3 * u + i);
          if (f == kNone) continue;
          const TriId w = tri_of(f);
          if (!seen[w] && mesh_.is_real(w)) {
            seen[w] = 1;
            stack.push_back(w);
          }
        }
      }
    }
    // A pinch vertex counts once per fan: the surface is a disc per fan there.
    const long long chi = static_cast<long long>(rep_.vertices_used + extra_fans_) - static_cast<long long>(edges) +
                          static_cast<long long>(rep_.triangles);
    const long long expected = 2 * static_cast<long long>(components) - static_cast<long long>(loops);
    if (chi != expected)
      problem("Euler count V - E + F = ", chi, " but ", components, " component(s) with ", loops,
              " boundary loop(s) need ", expected, " (a vertex is shared by separate fans, or the mesh overlaps)");
  }

  // ---- segments of a PSLG as chains of constrained edges ------------------

  void check_segments(const Pslg& g) {
    const std::size_t nv = mesh_.num_vertices();
    const std::size_t slots = mesh_.num_triangle_slots();
    std::vector<char> used(nv, 0);
    for (TriId t = 0; t < slots; ++t)
      if (mesh_.is_real(t))
        for (VertexId v : mesh_.triangle(t)) used[v] = 1;
    // Constrained edges as adjacency lists (CSR), each edge once per end.
    std::vector<std::uint32_t> start(nv + 1, 0);
    auto for_each_constrained = [&](auto&& emit) {
      for (TriId t : mesh_.triangles()) {
        for (int i = 0; i < 3; ++i) {
          const HalfEdgeId e = 3 * t + i;
          if (!mesh_.is_constrained(e)) continue;
          const HalfEdgeId f = real_twin(mesh_, e);
          if (f != kNone && f < e) continue;  // counted from the other half
          emit(mesh_.origin(e), mesh_.dest(e));
        }
      }
    };
    for_each_constrained([&](VertexId u, VertexId v) {
      ++start[u + 1];
      ++start[v + 1];
    });
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<VertexId> adj(start[nv]);
    {
      std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
      for_each_constrained([&](VertexId u, VertexId v) {
        adj[fill[u]++] = v;
        adj[fill[v]++] = u;
      });
    }
    // Duplicate endpoints stand for the used vertex at the same point.
    std::unordered_map<std::uint64_t, std::vector<VertexId>> by_point;
    auto point_key = [](const Point& p) {
      std::uint64_t x, y;
      std::memcpy(&x, &p.x, 8);
      std::memcpy(&y, &p.y, 8);
      return x * 0x9E3779B97F4A7C15ull ^ (y + 0x632BE59BD9B4E019ull + (x << 6) + (x >> 2));
    };
    auto canonical = [&](VertexId v) -> VertexId {
      if (used[v]) return v;
      if (by_point.empty())
        for (VertexId w = 0; w < nv; ++w)
          if (used[w]) by_point[point_key(mesh_.point(w))].push_back(w);
      const auto it = by_point.find(point_key(mesh_.point(v)));
      if (it != by_point.end())
        for (VertexId w : it->second)
          if (mesh_.point(w) == mesh_.point(v)) return w;
      return kNone;
    };
    std::vector<std::uint32_t> seen(nv, 0);
    std::uint32_t stamp = 0;
    std::vector<VertexId> stack;
    for (std::size_t i = 0; i < g.segments.size(); ++i) {
      const Segment& s = g.segments[i];
      if (s.a >= nv || s.b >= nv) {
        problem("segment ", i, " refers to vertex ", std::max(s.a, s.b), " of ", nv);
        continue;
      }
      const VertexId a = canonical(s.a), b = canonical(s.b);
      if (a == kNone || b == kNone || a == b) continue;  // carved away, or zero length
      ++rep_.segments_checked;
      ++stamp;
      if (!chain_exists(a, b, start, adj, seen, stamp, stack))
        problem("segment ", i, " (", s.a, "-", s.b, ") is not a chain of constrained edges");
    }
  }

  // Depth-first search from a over constrained edges whose far vertex lies
  // on segment ab (exactly), or within rounding distance of it and of its
  // extent (vertices added where rounded crossings bend the chain slightly,
  // even back and forth), until b is reached.
  bool chain_exists(VertexId a, VertexId b, const std::vector<std::uint32_t>& start, const std::vector<VertexId>& adj,
                    std::vector<std::uint32_t>& seen, std::uint32_t stamp, std::vector<VertexId>& stack) const {
    const Point pa = mesh_.point(a), pb = mesh_.point(b);
    const bool use_x = std::fabs(pb.x - pa.x) >= std::fabs(pb.y - pa.y);
    const double dir = use_x ? (pb.x > pa.x ? 1.0 : -1.0) : (pb.y > pa.y ? 1.0 : -1.0);
    auto key = [&](const Point& p) { return dir * (use_x ? p.x : p.y); };
    const double len = std::hypot(pb.x - pa.x, pb.y - pa.y);
    const double scale = std::max({std::fabs(pa.x), std::fabs(pa.y), std::fabs(pb.x), std::fabs(pb.y), len});
    const double tol = 1e-9 * scale;
    const double ka = key(pa), kb = key(pb);
    stack.clear();
    stack.push_back(a);
    seen[a] = stamp;
    while (!stack.empty()) {
      const VertexId u = stack.back();
      stack.pop_back();
      for (std::uint32_t k = start[u]; k < start[u + 1]; ++k)
        if (adj[k] == b) return true;
      for (std::uint32_t k = start[u]; k < start[u + 1]; ++k) {
        const VertexId w = adj[k];
        if (seen[w] == stamp) continue;
        const Point& pw = mesh_.point(w);
        const double kw = key(pw);
        const double o = orient2d(pa, pb, pw);
        const bool on_segment = o == 0.0 && kw > ka && kw < kb;
        const bool near = std::fabs(o) <= tol * len && kw > ka - tol && kw < kb + tol;
        if (!on_segment && !near) continue;
        seen[w] = stamp;
        stack.push_back(w);
      }
    }
    return false;
  }

  std::size_t extra_fans_ = 0;  // fans beyond the first at pinch vertices
  const Mesh& mesh_;
  const CheckOptions& opt_;
  CheckReport& rep_;
};

}  // namespace

CheckReport check(const Mesh& mesh, const CheckOptions& options) {
  CheckReport report;
  report.delaunay_checked = options.delaunay;
  if (detail::needs_frame(mesh.points())) {
    // Beyond the predicates' range (subnormal coordinates underflow: a
    // counter-clockwise triangle would look flat): the same checks on an
    // exact power-of-two copy, as triangulate() meshes it. Ids are unchanged;
    // coordinates in problem texts are the frame's.
    const detail::Frame f = detail::frame_for(mesh.points());
    Mesh framed = mesh;
    Pslg pslg;
    CheckOptions o = options;
    try {
      detail::scale_mesh(f, framed);
      if (options.pslg) pslg = detail::scaled_pslg(f, *options.pslg);
    } catch (const InputError&) {  // a spread no frame holds: checked as it is
      Checker(mesh, options, report).run();
      return report;
    }
    if (options.pslg) o.pslg = &pslg;
    Checker(framed, o, report).run();
    return report;
  }
  Checker(mesh, options, report).run();
  return report;
}

}  // namespace deltamesh
