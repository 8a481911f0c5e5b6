// libFuzzer target: random bytes -> a small PSLG -> carved CDT -> maybe a
// quality refinement -> coarsen() and/or adapt() to a size field chosen from
// the bytes (none, constant huge or tiny, a linear ramp, a wavy field, a
// field with zero/NaN/negative/infinite "no target" regions, or
// size_field_from_vertices over the mesh or over a point set) -> check.
//
// A bug is: a crash or sanitizer report; an exception other than InputError
// (InternalError among them; size_field_from_vertices must
// throw InputError on bad sizes, and only then); after each step, a mesh the
// validator rejects (constrained Delaunay; the input segments as chains when
// nothing was carved and the input vertices are protected; every chain of
// constrained edges between vertices that must stay still a chain); a vertex
// that must stay gone or moved (protected ids, vertices where constrained
// chains end, branch, bend, change marker, or where the boundary touches
// itself); a vertex removed where the field gives no target; stats that do
// not add up; triangle or constrained-edge counts that do not match the
// removals; the domain's area or the constrained length per marker changed;
// vertices removed when none was removable; more Steiner points than the
// budget. With f3's bit 6, an anisotropic step follows (fuzz_adapt_metric.hpp:
// metrics of aspect ratio up to 1:10^4, rotating directions, tensors that
// are not metrics rejected with an InputError).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "deltamesh/adapt.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "fuzz_adapt_metric.hpp"
#include "fuzz_util.hpp"
#include "pslg_bytes.hpp"

namespace dm = deltamesh;
namespace fz = deltamesh::fuzz;

namespace {

constexpr std::size_t kMaxPoints = 20;
constexpr std::size_t kMaxSegments = 14;
constexpr dm::VertexId kNone = dm::kNone;

bool verbose() {
  static const bool v = std::getenv("DELTAMESH_FUZZ_VERBOSE") != nullptr;
  return v;
}

// Constrained edges as coarsen() sees them: boundary edges count (it
// constrains them first), a half-edge's marker is read from v's side.
struct Link {
  dm::VertexId w;
  int marker;
};

// What a step must keep, taken before it.
struct Before {
  std::vector<dm::Point> points;
  std::vector<std::uint8_t> used;
  std::size_t used_count = 0;
  std::size_t triangles = 0;
  std::size_t constrained = 0;  // undirected constrained edges, boundary included
  std::vector<std::uint8_t> must_stay;
  std::vector<std::uint8_t> free;  // interior, no constrained edge, no vertex marker: smooth() may move it
  dm::Pslg chains;  // constrained chains between anchors (old ids)
  std::vector<std::uint8_t> soft;  // anchors that may still go (see anchors())
  double area = 0, area_terms = 0;
  std::map<int, double> length;  // constrained length per marker
  double min_altitude = INFINITY;
  double diag = 0;
  double max_abs = 0;  // largest coordinate magnitude
};

dm::Point ref_point(const dm::Mesh& m) {
  for (dm::VertexId v = 0; v < m.num_vertices(); ++v)
    if (m.out_edge(v) != kNone) return m.point(v);
  return {0, 0};
}

// Sum of triangle areas relative to one vertex (differences of nearby
// coordinates are exact, so far offsets do not swamp small triangles), and
// the sum of the magnitudes of the products (a bound on the rounding).
void area_of(const dm::Mesh& m, double& area, double& terms) {
  const dm::Point o = ref_point(m);
  area = terms = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point& a = m.point(v[0]);
    const dm::Point& b = m.point(v[1]);
    const dm::Point& c = m.point(v[2]);
    const double ax = a.x - o.x, ay = a.y - o.y, bx = b.x - o.x, by = b.y - o.y, cx = c.x - o.x, cy = c.y - o.y;
    const double p1 = (bx - ax) * (cy - ay), p2 = (by - ay) * (cx - ax);
    area += 0.5 * (p1 - p2);
    terms += std::fabs(p1) + std::fabs(p2);
  }
}

std::map<int, double> constrained_length(const dm::Mesh& m, std::size_t* count) {
  std::map<int, double> len;
  std::size_t n = 0;
  for (dm::HalfEdgeId e = 0; e < 3 * m.num_triangle_slots(); ++e) {
    if (!m.is_real(e / 3)) continue;
    const dm::HalfEdgeId f = m.twin(e);
    if (f != kNone && !(m.origin(e) < m.dest(e))) continue;
    if (f != kNone && !m.is_constrained(e)) continue;
    const dm::Point& a = m.point(m.origin(e));
    const dm::Point& b = m.point(m.dest(e));
    len[m.edge_marker(e)] += std::hypot(a.x - b.x, a.y - b.y);
    ++n;
  }
  if (count) *count = n;
  return len;
}

// Anchors: vertices coarsen() must keep (CoarsenOptions and adapt.hpp:
// protected ids, where segments end or branch, where markers change, where
// the boundary touches itself, where they bend). coarsen() calls a vertex
// straight when it is within 1e-11 of the line through its constrained
// neighbours relative to their distance, so beside a very short edge a
// sharp corner counts as straight, and once a neighbour goes the next one
// may lie in another direction. So a bend makes a vertex stay only when
// both its constrained edges are long (1e-4 of the mesh's extent: removals
// then turn them by at most ~1e-7) and it turns by more than 1e-5 (or
// 90 degrees); other bends of more than 1e-11 are "soft" anchors: chains
// end there (the validator allows chain vertices 1e-9 off the segment),
// but they may go.
Before snapshot(const dm::Mesh& m, std::size_t protect_first) {
  Before b;
  const std::size_t n = m.num_vertices();
  b.points.assign(m.points().begin(), m.points().end());
  b.used.assign(n, 0);
  b.triangles = m.num_triangles();
  std::vector<std::vector<Link>> adj(n);
  std::vector<int> fans(n, 0);
  double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    for (dm::HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const dm::VertexId v = m.origin(e), w = m.dest(e);
      b.used[v] = 1;
      const dm::Point& p = m.point(v);
      lox = std::min(lox, p.x), hix = std::max(hix, p.x), loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
      if (m.twin(e) == kNone) {
        ++fans[v];
        adj[v].push_back({w, m.edge_marker(e)});
        adj[w].push_back({v, m.edge_marker(e)});
      } else if (m.is_constrained(e)) {
        adj[v].push_back({w, m.edge_marker(e)});
      }
      // altitude onto e
      const dm::Point& q = m.point(w);
      const dm::Point& r = m.point(m.origin(dm::prev_edge(e)));
      const double len = std::hypot(q.x - p.x, q.y - p.y);
      const double cr = std::fabs((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
      if (len > 0) b.min_altitude = std::min(b.min_altitude, cr / len);
    }
  }
  b.diag = std::hypot(hix - lox, hiy - loy);
  b.max_abs = std::max({std::fabs(lox), std::fabs(hix), std::fabs(loy), std::fabs(hiy)});
  for (std::size_t v = 0; v < n; ++v) b.used_count += b.used[v];
  area_of(m, b.area, b.area_terms);
  b.length = constrained_length(m, &b.constrained);

  b.must_stay.assign(n, 0);
  b.soft.assign(n, 0);
  b.free.assign(n, 0);
  for (dm::VertexId v = 0; v < n; ++v)
    b.free[v] = b.used[v] && adj[v].empty() && v >= protect_first &&
                (v >= m.vertex_markers().size() || m.vertex_markers()[v] == 0);
  std::vector<std::uint8_t> anchor(n, 0);
  for (dm::VertexId v = 0; v < n; ++v) {
    if (!b.used[v]) continue;
    auto& a = adj[v];
    bool hard = v < protect_first || fans[v] > 1 || (a.size() != 0 && a.size() != 2);
    bool is_anchor = hard;
    if (!hard && a.size() == 2) {
      const dm::Point &pa = m.point(a[0].w), &pv = m.point(v), &pb = m.point(a[1].w);
      const double dot = (pa.x - pv.x) * (pb.x - pv.x) + (pa.y - pv.y) * (pb.y - pv.y);
      const double o = std::fabs((pa.x - pv.x) * (pb.y - pv.y) - (pa.y - pv.y) * (pb.x - pv.x));
      const double la = std::hypot(pa.x - pv.x, pa.y - pv.y), lb = std::hypot(pb.x - pv.x, pb.y - pv.y);
      const bool robust = std::min(la, lb) >= 1e-4 * b.diag;
      if (a[0].marker != a[1].marker) {
        hard = is_anchor = true;
      } else if (!(dot < 0) || o > 1e-11 * la * lb) {
        is_anchor = true;
        hard = robust && (!(dot < 0) || o > 1e-5 * la * lb);
      }
    }
    b.must_stay[v] = hard;
    anchor[v] = is_anchor;
    b.soft[v] = is_anchor && !hard;
  }
  if (verbose())
    for (dm::VertexId v = 0; v < n; ++v) {
      if (adj[v].empty()) continue;
      std::fprintf(stderr, "  before %u (%.17g, %.17g)%s%s:", static_cast<unsigned>(v), m.point(v).x, m.point(v).y,
                   b.must_stay[v] ? " must stay" : "", b.soft[v] ? " soft" : "");
      for (const Link& l : adj[v]) std::fprintf(stderr, " %u/%d", static_cast<unsigned>(l.w), l.marker);
      std::fprintf(stderr, "\n");
    }
  // Chains from each anchor through non-anchors with two constrained
  // neighbours, to the next anchor (each once: from its smaller end).
  for (dm::VertexId s = 0; s < n; ++s) {
    if (!anchor[s]) continue;
    for (const Link& first : adj[s]) {
      dm::VertexId prev = s, cur = first.w;
      std::size_t steps = 0;
      while (!anchor[cur] && adj[cur].size() == 2 && steps++ <= n) {
        const dm::VertexId next = adj[cur][0].w == prev ? adj[cur][1].w : adj[cur][0].w;
        prev = cur;
        cur = next;
      }
      if (!anchor[cur] || cur == s) continue;
      if (s < cur || (s == cur)) b.chains.segments.push_back({s, cur, first.marker});
    }
  }
  return b;
}

struct CoarsenSetup {
  dm::CoarsenOptions opt;
  bool none_removable = false;  // by the options alone
};

// Old id -> id after the step (kNone: gone from the vertex list).
std::vector<dm::VertexId> id_map(const Before& b, const dm::CoarsenStats& st, bool renumber) {
  if (!renumber) {
    std::vector<dm::VertexId> id(b.points.size());
    for (std::size_t v = 0; v < id.size(); ++v) id[v] = static_cast<dm::VertexId>(v);
    return id;
  }
  DELTAMESH_FUZZ_CHECK(st.new_id.size() == b.points.size(), "new_id has one entry per old vertex");
  return st.new_id;
}

std::vector<std::uint8_t> used_of(const dm::Mesh& m) {
  std::vector<std::uint8_t> used(m.num_vertices(), 0);
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t)
    if (m.is_real(t))
      for (const dm::VertexId v : m.triangle(t)) used[v] = 1;
  return used;
}

void validate(const dm::Mesh& m, const dm::Pslg* pslg, const std::string& stage) {
  dm::CheckOptions co;
  co.delaunay = true;
  co.convex_hull = false;  // carved, and split points on hull edges are rounded
  co.pslg = pslg;
  const dm::CheckReport rep = dm::check(m, co);
  if (!rep.ok()) fz::fail(stage + ": the validator rejects the mesh: " + rep.summary());
}

// Checks shared by coarsen() and adapt(): `added` vertices were appended
// after the coarsening (refinement).
// smoothed: smooth() ran, which moves free vertices (adapt.hpp: "vertices
// on segments, the boundary and protected ones keep their exact coordinates").
void check_step(const dm::Mesh& m, const Before& b, const dm::CoarsenStats& st, const CoarsenSetup& cs,
                const dm::SizeField& h, std::size_t added, const dm::Pslg* input, const std::string& stage,
                bool smoothed = false) {
  const std::string what = stage + ": " + st.summary();
  const bool renumber = cs.opt.renumber;
  DELTAMESH_FUZZ_CHECK(st.vertices_before == b.used_count, what);
  DELTAMESH_FUZZ_CHECK(st.vertices_after + st.removed == st.vertices_before, what);
  DELTAMESH_FUZZ_CHECK(st.removed_on_segments <= st.removed, what);
  DELTAMESH_FUZZ_CHECK(st.removed + st.refused <= st.vertices_before, what);
  DELTAMESH_FUZZ_CHECK(cs.opt.max_removals == 0 || st.removed <= cs.opt.max_removals, what);
  if (cs.none_removable) DELTAMESH_FUZZ_CHECK(st.removed == 0, what + " (nothing was removable)");

  const std::vector<dm::VertexId> id = id_map(b, st, renumber);
  const std::vector<std::uint8_t> used = used_of(m);
  const std::size_t kept_ids = renumber ? st.vertices_after : b.points.size();
  DELTAMESH_FUZZ_CHECK(m.num_vertices() == kept_ids + added, what + ": vertex count " + std::to_string(m.num_vertices()));
  std::size_t gone = 0, last = 0;
  bool first = true;
  for (dm::VertexId v = 0; v < b.points.size(); ++v) {
    const dm::VertexId w = id[v];
    if (w != kNone) {
      DELTAMESH_FUZZ_CHECK(w < kept_ids, what);
      DELTAMESH_FUZZ_CHECK(first || w > last, what + ": renumbering out of order");
      first = false, last = w;
      if (!(smoothed && b.free[v]))
        DELTAMESH_FUZZ_CHECK(m.point(w) == b.points[v], what + ": vertex " + std::to_string(v) + " moved");
    }
    const bool here = w != kNone && used[w];
    if (!b.used[v]) {
      DELTAMESH_FUZZ_CHECK(!here && (!renumber || w == kNone), what + ": an unused vertex came back or stayed listed");
      continue;
    }
    if (here) continue;
    ++gone;
    DELTAMESH_FUZZ_CHECK(!renumber || w == kNone, what + ": a removed vertex kept an id");
    if (b.must_stay[v])
      fz::fail(what + ": vertex " + std::to_string(v) + " (" + std::to_string(b.points[v].x) + ", " +
               std::to_string(b.points[v].y) + ") must stay (protected, chain end, bend, marker change) but went");
    const double hv = h ? h(b.points[v].x, b.points[v].y) : NAN;
    DELTAMESH_FUZZ_CHECK(hv > 0 && std::isfinite(hv),
                         what + ": vertex " + std::to_string(v) + " removed where the field gives no target");
  }
  DELTAMESH_FUZZ_CHECK(gone == st.removed, what + ": " + std::to_string(gone) + " vertices gone");
  for (dm::VertexId v = 0; v < added; ++v) DELTAMESH_FUZZ_CHECK(used[kept_ids + v], what + ": Steiner point unused");

  // Segments: every chain between anchors still (soft anchors that went:
  // their chains are not checked), and the input's when asked.
  dm::Pslg chains;
  chains.points.assign(m.points().begin(), m.points().end());
  for (const dm::Segment& s : b.chains.segments) {
    const dm::VertexId a = id[s.a], c = id[s.b];
    if (a == kNone || c == kNone || !used[a] || !used[c]) {
      DELTAMESH_FUZZ_CHECK(b.soft[s.a] || b.soft[s.b], what + ": a chain end went");
      continue;
    }
    chains.segments.push_back({a, c, s.marker});
  }
  if (verbose()) {  // the chains and, after the step, the constrained edges at their vertices
    for (const dm::Segment& s : chains.segments)
      std::fprintf(stderr, "  chain %u (%.17g, %.17g) - %u (%.17g, %.17g) marker %d\n", static_cast<unsigned>(s.a),
                   m.point(s.a).x, m.point(s.a).y, static_cast<unsigned>(s.b), m.point(s.b).x, m.point(s.b).y, s.marker);
    for (dm::HalfEdgeId e = 0; e < 3 * m.num_triangle_slots(); ++e)
      if (m.is_real(e / 3) && (m.twin(e) == dm::kNone || (m.is_constrained(e) && m.origin(e) < m.dest(e))))
        std::fprintf(stderr, "  constrained %u (%.17g, %.17g) - %u (%.17g, %.17g) marker %d%s\n",
                     static_cast<unsigned>(m.origin(e)), m.point(m.origin(e)).x, m.point(m.origin(e)).y,
                     static_cast<unsigned>(m.dest(e)), m.point(m.dest(e)).x, m.point(m.dest(e)).y, m.edge_marker(e),
                     m.twin(e) == dm::kNone ? " boundary" : "");
  }
  validate(m, &chains, stage);
  if (input) {
    dm::Pslg g = *input;
    g.points.assign(m.points().begin(), m.points().end());
    g.point_markers.clear();
    bool ok = true;
    // A duplicate input vertex (in no triangle) stands for its used copy.
    auto map = [&](dm::VertexId v) {
      if (v >= id.size()) return kNone;
      if (!b.used[v])
        for (dm::VertexId u = 0; u < b.points.size(); ++u)
          if (b.used[u] && b.points[u] == b.points[v]) return id[u];
      return id[v];
    };
    for (dm::Segment& s : g.segments) {
      s.a = map(s.a), s.b = map(s.b);
      if (s.a == kNone || s.b == kNone) ok = false;
    }
    if (ok) validate(m, &g, stage + " (input segments)");
  }

  // Same domain: area, constrained length per marker.
  double area, terms;
  area_of(m, area, terms);
  const double d2 = b.diag * b.diag;
  // Rounding of the sums; coarsen's 1e-11 collinearity tolerance per merged
  // subsegment; a split point on a slanted segment is rounded off it by up
  // to an ulp of the coordinates.
  const double tol = 1e-9 * std::fabs(b.area) + 1e-14 * (terms + b.area_terms) +
                     double(st.removed_on_segments) * 1e-11 * d2 + double(added) * 1e-15 * b.max_abs * b.diag;
  if (!(std::fabs(area - b.area) <= tol))
    fz::fail(what + ": domain area " + std::to_string(b.area) + " -> " + std::to_string(area));
  std::size_t constrained = 0;
  const std::map<int, double> len = constrained_length(m, &constrained);
  DELTAMESH_FUZZ_CHECK(len.size() == b.length.size(), what + ": a segment marker vanished or appeared");
  for (const auto& [marker, l] : b.length) {
    const auto it = len.find(marker);
    DELTAMESH_FUZZ_CHECK(it != len.end(), what + ": marker gone");
    // A split point rounded off a slanted segment by up to an ulp lengthens
    // it by up to two: relative to the length of a segment a few ulps long,
    // far more than 1e-9.
    const double len_tol = 1e-9 * l + double(added) * 1e-15 * b.max_abs;
    char got[96];
    std::snprintf(got, sizeof got, " %.17g -> %.17g", l, it->second);
    DELTAMESH_FUZZ_CHECK(std::fabs(it->second - l) <= len_tol,
                         what + ": constrained length of marker " + std::to_string(marker) + got);
  }
  if (added == 0) {
    // Each removal on a segment merges two constrained edges; an interior
    // removal takes 2 triangles, one on the boundary 1.
    DELTAMESH_FUZZ_CHECK(constrained + st.removed_on_segments == b.constrained, what + ": constrained edge count");
    DELTAMESH_FUZZ_CHECK(m.num_triangles() + st.removed <= b.triangles && b.triangles <= m.num_triangles() + 2 * st.removed,
                         what + ": " + std::to_string(b.triangles) + " -> " + std::to_string(m.num_triangles()) +
                             " triangles");
  }
}

// The largest target at the used vertices (positive, finite ones).
double max_h(const Before& b, const dm::SizeField& h) {
  double hi = 0;
  if (!h) return hi;
  for (std::size_t v = 0; v < b.points.size(); ++v) {
    if (!b.used[v]) continue;
    const double x = h(b.points[v].x, b.points[v].y);
    if (x > 0 && std::isfinite(x)) hi = std::max(hi, x);
  }
  return hi;
}

CoarsenSetup coarsen_setup(FuzzedDataProvider& in, const dm::Mesh& m, std::size_t input_points) {
  CoarsenSetup cs;
  static constexpr double kRatio[] = {0.7, 0.3, 1.0, 2.0, 0.0, -1.0, NAN, INFINITY};
  static constexpr double kSpoke[] = {1.5, 0.5, 4.0, 1e300};
  const std::uint8_t b = in.ConsumeIntegral<std::uint8_t>();
  cs.opt.ratio = kRatio[b & 7];
  cs.opt.max_spoke = kSpoke[(b >> 3) & 3];
  cs.opt.renumber = (b & 32) == 0;
  switch ((b >> 6) & 3) {
    case 0: cs.opt.protect_first = 0; break;
    case 1: cs.opt.protect_first = input_points; break;
    case 2: cs.opt.protect_first = in.ConsumeIntegralInRange<std::size_t>(0, m.num_vertices()); break;
    default: cs.opt.protect_first = m.num_vertices(); break;
  }
  const int r = in.ConsumeIntegralInRange<int>(0, 3);
  cs.opt.max_removals = r == 0 ? 0 : r == 1 ? 1 : r == 2 ? 3 : in.ConsumeIntegralInRange<std::size_t>(0, 40);
  cs.none_removable = !(cs.opt.ratio > 0) || !(cs.opt.max_spoke > 0) || cs.opt.protect_first >= m.num_vertices();
  return cs;
}

// A size field from the bytes, in units of the mesh's extent. `expect_error`:
// size_field_from_vertices was given bad sizes on purpose.
dm::SizeField make_field(FuzzedDataProvider& in, const dm::Mesh& m, const Before& b, const fz::Coords& cm,
                         int kind, bool& skip) {
  skip = false;
  const double L = b.diag > 0 ? b.diag : 1.0;
  double lox = INFINITY, loy = INFINITY, hix = -INFINITY;
  for (std::size_t v = 0; v < b.points.size(); ++v)
    if (b.used[v]) lox = std::min(lox, b.points[v].x), loy = std::min(loy, b.points[v].y), hix = std::max(hix, b.points[v].x);
  const double W = hix > lox ? hix - lox : L;
  switch (kind) {
    case 0:
      return {};
    case 1: {  // huge
      const int k = in.ConsumeIntegralInRange<int>(0, 22);
      const double c = k == 21 ? 1e308 : k == 22 ? INFINITY : std::ldexp(L, k);
      return [c](double, double) { return c; };
    }
    case 2: {  // tiny
      const int k = in.ConsumeIntegralInRange<int>(3, 61);
      const double c = k == 61 ? std::numeric_limits<double>::denorm_min() : std::ldexp(L, -k);
      return [c](double, double) { return c; };
    }
    case 3: {  // ramp, negative ("no target") on one side sometimes
      const double a = L * (in.ConsumeIntegralInRange<int>(-4, 8) / 16.0);
      const double s = L * (in.ConsumeIntegralInRange<int>(-8, 8) / 8.0);
      return [a, s, lox, W](double x, double) { return a + s * (x - lox) / W; };
    }
    case 4: {  // wavy
      const double amp = std::ldexp(L, -in.ConsumeIntegralInRange<int>(1, 8));
      const double kx = in.ConsumeIntegralInRange<int>(1, 8) * 6.283185307179586 / L;
      const double ky = in.ConsumeIntegralInRange<int>(0, 8) * 6.283185307179586 / L;
      return [amp, kx, ky, lox, loy](double x, double y) {
        return amp * (1.1 + std::sin(kx * (x - lox)) * std::cos(ky * (y - loy)));
      };
    }
    case 5: {  // "no target" (0, NaN, negative, +-inf) in a disk, a size elsewhere
      static constexpr double kBad[] = {0.0, NAN, -1.0, -INFINITY, INFINITY, -0.0};
      const double bad = kBad[in.ConsumeIntegralInRange<int>(0, 5)];
      const double c = std::ldexp(L, -in.ConsumeIntegralInRange<int>(0, 6));
      const dm::Point ctr = cm.point(in);
      const double r = L * in.ConsumeIntegralInRange<int>(0, 8) / 8.0;
      return [bad, c, ctr, r](double x, double y) { return std::hypot(x - ctr.x, y - ctr.y) <= r ? bad : c; };
    }
    default: {  // sizes at the vertices of the mesh (6) or of a point set (7)
      dm::Mesh bg;
      if (kind == 6) {
        bg = m;
      } else {
        dm::Pslg ps;
        const std::size_t np = in.ConsumeIntegralInRange<std::size_t>(3, 8);
        for (std::size_t i = 0; i < np; ++i) ps.points.push_back(cm.point(in));
        try {
          bg = dm::triangulate(ps);
        } catch (const dm::InputError& e) {
          skip = true;
          return {};
        } catch (...) {
          fz::unexpected_exception("background triangulate");
        }
      }
      std::vector<double> sizes(bg.num_vertices());
      for (double& s : sizes) s = std::ldexp(L, in.ConsumeIntegralInRange<int>(-10, 3));
      const int broken = in.ConsumeIntegralInRange<int>(0, 15);
      if (broken == 1 && !sizes.empty()) sizes.back() = 0.0;
      if (broken == 2 && !sizes.empty()) sizes.front() = NAN;
      if (broken == 3) sizes.push_back(L);
      if (broken == 4 && !sizes.empty()) sizes[sizes.size() / 2] = -INFINITY;
      const bool bad = broken >= 1 && broken <= 4;
      try {
        dm::SizeField f = dm::size_field_from_vertices(bg, sizes);
        if (bad) fz::fail("size_field_from_vertices accepted bad sizes (case " + std::to_string(broken) + ")");
        return f;
      } catch (const dm::InputError& e) {
        if (!bad) fz::fail(std::string("size_field_from_vertices threw on good sizes: ") + e.what());
        skip = true;
        return {};
      } catch (...) {
        fz::unexpected_exception("size_field_from_vertices");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  // Integers are read from the end: options first, then the geometry.
  const std::uint8_t f1 = in.ConsumeIntegral<std::uint8_t>();
  const std::uint8_t f2 = in.ConsumeIntegral<std::uint8_t>();
  const std::uint8_t f3 = in.ConsumeIntegral<std::uint8_t>();
  fz::Coords cm;
  cm.init(in);
  dm::Pslg g;
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(3, kMaxPoints);
  const std::size_t ns = in.ConsumeIntegralInRange<std::size_t>(0, kMaxSegments);
  fz::read_pslg(in, cm, n, ns, (f1 & 1) != 0, (f1 & 2) != 0, g);

  dm::TriangulateOptions topt;
  topt.domain.keep_convex_hull = (f1 & 4) != 0;
  static constexpr dm::CdtMethod kMethods[] = {dm::CdtMethod::Fast, dm::CdtMethod::Lawson, dm::CdtMethod::Lifting,
                                               dm::CdtMethod::Fast};
  topt.method = kMethods[(f1 >> 3) & 3];
  if (verbose())
    std::fprintf(stderr, "--- input.poly (method %s, keep_convex_hull %d):\n%s--- end\n",
                 std::string(dm::to_string(topt.method)).c_str(), topt.domain.keep_convex_hull,
                 fz::to_poly(g).c_str());
  dm::Mesh mesh;
  if (!fz::triangulate_or_stop(g, topt, mesh)) return 0;
  const bool nothing_carved = topt.domain.keep_convex_hull && g.holes.empty();
  validate(mesh, nothing_carved ? &g : nullptr, "triangulate");

  if (f1 & 32) {  // a quality mesh first (finer than most fields)
    dm::RefineOptions ro;
    static constexpr double kAngles[] = {0.0, 20.0, 30.0, 20.0};
    ro.min_angle_deg = kAngles[(f1 >> 6) & 3];
    if (f2 & 3) {
      double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
      for (const dm::Point& p : g.points)
        lox = std::min(lox, p.x), hix = std::max(hix, p.x), loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
      ro.max_area = (hix - lox) * (hiy - loy) / (4 << (2 * (f2 & 3)));
    }
    static constexpr std::size_t kBudget[] = {20, 100, 400, 400};
    ro.max_steiner = kBudget[(f2 >> 2) & 3];
    ro.time_limit_seconds = 1.0;
    try {
      dm::refine(mesh, ro);
    } catch (...) {
      fz::unexpected_exception("refine");
    }
    validate(mesh, nothing_carved ? &g : nullptr, "refine");
  }

  // The operations: 0 coarsen, 1 adapt, 2 coarsen then adapt, 3 coarsen twice.
  const int op = f3 & 3;
  const int steps = op >= 2 ? 2 : 1;
  std::size_t input_points = g.points.size();  // ids of the input vertices (while not renumbered)
  for (int step = 0; step < steps; ++step) {
    const bool do_adapt = op == 1 || (op == 2 && step == 1);
    const CoarsenSetup cs = coarsen_setup(in, mesh, input_points);
    const Before b = snapshot(mesh, cs.opt.protect_first);
    const int kind = step == 0 ? (f3 >> 2) & 7 : in.ConsumeIntegralInRange<int>(0, 7);
    bool skip = false;
    const dm::SizeField h = make_field(in, mesh, b, cm, kind, skip);
    if (skip) return 0;
    CoarsenSetup cs2 = cs;
    if (!h || cs.opt.ratio * max_h(b, h) < 0.5 * b.min_altitude) cs2.none_removable = true;
    // The input segments, when nothing was carved and the input vertices are
    // kept by protection (ids mapped by check_step).
    const dm::Pslg* input = nothing_carved && cs.opt.protect_first >= input_points && input_points == g.points.size()
                                ? &g
                                : nullptr;
    const std::string stage = std::string(do_adapt ? "adapt" : "coarsen") + " step " + std::to_string(step) +
                              " (field " + std::to_string(kind) + ")";
    if (verbose())
      std::fprintf(stderr,
                   "--- %s: %zu vertices, %zu triangles; ratio %g max_spoke %g protect_first %zu max_removals %zu "
                   "renumber %d\n",
                   stage.c_str(), mesh.num_vertices(), mesh.num_triangles(), cs.opt.ratio, cs.opt.max_spoke,
                   cs.opt.protect_first, cs.opt.max_removals, cs.opt.renumber);
    if (!do_adapt) {
      dm::CoarsenStats st;
      try {
        st = dm::coarsen(mesh, h, cs.opt);
      } catch (const dm::InputError& e) {
        return 0;
      } catch (...) {
        fz::unexpected_exception("coarsen");
      }
      if (verbose()) std::fprintf(stderr, "--- %s\n", st.summary().c_str());
      check_step(mesh, b, st, cs2, h, 0, input, stage);
      if (cs.opt.renumber) input_points = 0;  // ids changed: no longer comparable to the input
    } else {
      dm::AdaptOptions ao;
      ao.coarsen = cs.opt;
      ao.refine.min_angle_deg = (f2 & 16) ? 25.0 : 0.0;
      static constexpr std::size_t kBudget[] = {10, 60, 200, 200};
      ao.refine.max_steiner = kBudget[(f2 >> 5) & 3];
      ao.refine.time_limit_seconds = 1.0;
      static constexpr int kSmooth[] = {2, 0, 1, 3};
      ao.smooth_passes = kSmooth[(f2 >> 7) | ((f3 >> 4) & 2)];
      dm::AdaptStats st;
      try {
        st = dm::adapt(mesh, h, ao);
      } catch (const dm::InputError& e) {
        return 0;
      } catch (...) {
        fz::unexpected_exception("adapt");
      }
      if (verbose())
        std::fprintf(stderr, "--- smooth_passes %d: %s; %s; %s\n", ao.smooth_passes, st.summary().c_str(),
                     st.refine.summary().c_str(), st.smooth.summary().c_str());
      const std::string what = stage + ": " + st.summary();
      DELTAMESH_FUZZ_CHECK(st.removed == st.coarsen.removed, what);
      DELTAMESH_FUZZ_CHECK(st.inserted == st.refine.steiner_points, what);
      DELTAMESH_FUZZ_CHECK(st.inserted <= ao.refine.max_steiner, what);
      DELTAMESH_FUZZ_CHECK(st.triangles == mesh.num_triangles(), what);
      DELTAMESH_FUZZ_CHECK(st.complete == st.refine.complete, what);
      DELTAMESH_FUZZ_CHECK(st.refine.input_vertices == (cs.opt.renumber ? st.coarsen.vertices_after : b.points.size()),
                           what);
      DELTAMESH_FUZZ_CHECK(!(st.refine.budget_exhausted || st.refine.time_exhausted) || !st.complete, what);
      DELTAMESH_FUZZ_CHECK(st.resplit <= st.inserted, what);
      check_step(mesh, b, st.coarsen, cs2, h, st.inserted, input, stage, st.smooth.passes > 0);
      if (cs.opt.renumber) input_points = 0;
    }
  }
  // Then, with f3's bit 6, adaptation to an anisotropic metric
  // (fuzz_adapt_metric.hpp), the input vertices protected while their ids hold.
  if (f3 & 64) {
    const bool ids_hold = input_points == g.points.size();
    fz::metric_step(in, mesh, nothing_carved && ids_hold ? &g : nullptr, ids_hold ? input_points : 0, verbose());
  }
  return 0;
}
