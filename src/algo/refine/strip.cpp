// refine_in_parts' last pass on a strip around the cuts (strip.hpp). The
// whole-mesh pass adds a few thousand points to a mesh of millions, but its
// setup visits every half-edge; the strip is refined like a part (its outer
// edges frozen, as PCDM's separators: Chernikov & Chrisochoides 2006), and
// is kept only when the whole mesh is verifiably finished.
#include "algo/refine/strip.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "algo/refine/refiner.hpp"
#include "deltamesh/errors.hpp"
#include "mesh/canonical.hpp"

namespace deltamesh::detail {

namespace {

// Rings of neighbours (across edges) around the seeds. The parts leave bad
// the triangles next to the cuts, whose Steiner points lie a triangle or
// two across; six rings keep the strip's new points away from its frozen
// outer edges (measured: the strip is kept on square-hole and the smooth
// polygon).
constexpr int kStripRings = 6;
// Strips refined, each around what the one before left bad, before the
// whole-mesh pass takes over.
constexpr int kStripRounds = 10;
// A strip larger than this share of the mesh goes to the whole-mesh pass.
constexpr std::size_t kMaxStripShare = 4;

// The last pass's criteria, as Refiner::eval() and encroaches() apply them
// (uniform area bound: refine_in_parts' options; no per-triangle bounds).
struct Criteria {
  double sin2_bound = 0, max_area = 0, lens_cos2 = 0;
  bool lens = false;

  explicit Criteria(const RefineOptions& o) {
    const double theta = std::clamp(o.min_angle_deg, 0.0, 60.0);
    sin2_bound = refinement::angle_bound_sin2(theta);
    max_area = o.max_area;
    lens = o.encroachment == EncroachmentRule::DiametralLens && !o.conforming_delaunay;
    lens_cos2 = refinement::lens_angle_cos2(theta);
  }

  bool bad(const Mesh& m, TriId t) const {
    const refinement::ShortestEdgeShape sh = refinement::shortest_edge_shape(
        m.point(m.origin(3 * t)), m.point(m.origin(3 * t + 1)), m.point(m.origin(3 * t + 2)));
    return sh.cross * sh.cross < sin2_bound * sh.den || (max_area > 0 && 0.5 * sh.cross > max_area);
  }

  bool encroaches(const Point& a, const Point& b, const Point& p) const {
    return refinement::encroaches_upon(a, b, p, lens, lens_cos2);
  }

  // A constrained edge of triangle t whose apex, or the apex across it,
  // encroaches upon it.
  bool encroached_side(const Mesh& m, TriId t) const {
    for (int c = 0; c < 3; ++c) {
      const HalfEdgeId e = 3 * t + c;
      if (!m.is_constrained(e)) continue;
      const Point &a = m.point(m.origin(e)), &b = m.point(m.dest(e));
      if (encroaches(a, b, m.point(m.origin(prev_edge(e))))) return true;
      const HalfEdgeId o = m.twin(e);
      if (o != kNone && encroaches(a, b, m.point(m.origin(prev_edge(o))))) return true;
    }
    return false;
  }
};

// The strip's slots: `tris` grown by the seeds and kStripRings rings of
// neighbours around them (in[t]: t in the strip). False when that is more
// than the mesh's share. Afterwards `tris` is in slot order.
bool grow_strip(const Mesh& m, const std::vector<TriId>& seeds, std::vector<TriId>& tris, std::vector<std::uint8_t>& in) {
  const std::size_t most = m.num_triangle_slots() / kMaxStripShare;
  std::size_t begin = tris.size();
  auto add = [&](TriId t) {
    if (in[t]) return;
    in[t] = 1;
    tris.push_back(t);
  };
  for (TriId t : seeds) add(t);
  for (int ring = 0; ring < kStripRings && tris.size() <= most; ++ring) {
    const std::size_t end = tris.size();
    for (std::size_t i = begin; i < end; ++i)
      for (int c = 0; c < 3; ++c)
        if (const HalfEdgeId o = m.twin(3 * tris[i] + c); o != kNone) add(tri_of(o));
    begin = end;
  }
  if (tris.size() > most) return false;
  std::sort(tris.begin(), tris.end());
  return true;
}

// The refined strip back into the whole mesh: its first slots into the
// strip's own, the rest appended; its new vertices appended; its frozen
// edges paired again with the half-edges outside. Returns the whole's
// half-edges of those edges (strip side) that are not segments, for the
// flips, and sets `slot` (strip slot -> whole slot).
std::vector<HalfEdgeId> write_back(Mesh& whole, const Part& strip, const std::vector<TriId>& tris,
                                   std::vector<TriId>& slot) {
  const Mesh& s = strip.mesh;
  const std::size_t nt = whole.num_triangle_slots(), n = tris.size(), ns = s.num_triangle_slots();
  const std::size_t nv0 = whole.num_vertices(), first_new = strip.global.size();
  const std::size_t nv = nv0 + s.num_vertices() - first_new, nt2 = nt + ns - n;
  if (ns < n) throw InternalError("refine_in_parts", "the strip lost triangles");
  if (nt2 >= kNone / 3 || nv >= kInfinite) throw InputError("too many triangles: at most 1431655764 are supported");
  auto vid = [&](VertexId v) {
    return v < first_new ? strip.global[v] : static_cast<VertexId>(nv0 + (v - first_new));
  };
  slot.resize(ns);
  for (std::size_t i = 0; i < ns; ++i) slot[i] = i < n ? tris[i] : static_cast<TriId>(nt + (i - n));

  MeshEditor ed(whole);
  const std::size_t na = whole.num_vertex_attributes(), ta = whole.num_triangle_attributes();
  ed.points().resize(nv);
  ed.out_edges().resize(nv, kNone);
  const bool markers = !whole.vertex_markers().empty();
  if (markers) whole.vertex_markers().resize(nv, 0);
  whole.vertex_attributes().resize(nv * na, 0.0);
  for (VertexId v = static_cast<VertexId>(first_new); v < s.num_vertices(); ++v) {
    const VertexId g = vid(v);
    ed.points()[g] = s.point(v);
    if (markers && v < s.vertex_markers().size()) whole.vertex_markers()[g] = s.vertex_markers()[v];
    for (std::size_t k = 0; k < na && std::size_t{v} * na + k < s.vertex_attributes().size(); ++k)
      whole.vertex_attributes()[std::size_t{g} * na + k] = s.vertex_attributes()[std::size_t{v} * na + k];
  }

  std::vector<VertexId>& tv = ed.triangle_vertices();
  std::vector<HalfEdgeId>& tw = ed.twins();
  std::vector<std::uint8_t>& fl = ed.edge_flags();
  std::vector<int>& mk = ed.edge_markers();
  const bool edge_markers = whole.has_edge_markers();
  tv.resize(3 * nt2);
  tw.resize(3 * nt2);
  fl.resize(3 * nt2, 0);
  if (edge_markers) mk.resize(3 * nt2, 0);
  whole.triangle_attributes().resize(nt2 * ta);
  std::vector<HalfEdgeId> frozen;
  for (std::size_t i = 0; i < ns; ++i) {
    for (int c = 0; c < 3; ++c) {
      const HalfEdgeId e = static_cast<HalfEdgeId>(3 * i + c), w = 3 * slot[i] + c, o = s.twin(e);
      tv[w] = vid(s.origin(e));
      fl[w] = s.edge_flags(e);
      if (edge_markers) mk[w] = s.edge_marker(e);
      tw[w] = o == kNone ? kNone : 3 * slot[tri_of(o)] + o % 3;
      if (o == kNone && (fl[w] & kFrozenEdge)) frozen.push_back(w);
    }
    for (std::size_t k = 0; k < ta; ++k) whole.triangle_attributes()[slot[i] * ta + k] = s.triangle_attributes()[i * ta + k];
  }
  // The frozen edges meet the half-edges outside again, by their vertices.
  std::unordered_map<std::uint64_t, HalfEdgeId> across;
  across.reserve(strip.outer.size());
  for (HalfEdgeId o : strip.outer) across.emplace(directed_key(tv[next_edge(o)], tv[o]), o);
  std::vector<HalfEdgeId> flips;
  for (HalfEdgeId w : frozen) {
    const auto it = across.find(directed_key(tv[w], tv[next_edge(w)]));
    if (it == across.end()) throw InternalError("refine_in_parts", "a strip edge lost its other side");
    const HalfEdgeId o = it->second;
    tw[w] = o;
    tw[o] = w;
    fl[w] = static_cast<std::uint8_t>(fl[w] & ~kFrozenEdge);
    if (!(fl[o] & kConstrained)) {
      fl[w] = static_cast<std::uint8_t>(fl[w] & ~kConstrained);
      if (edge_markers) mk[w] = mk[o];
      flips.push_back(w);
    }
  }
  if (across.size() != frozen.size()) throw InternalError("refine_in_parts", "a strip edge lost its other side");
  for (VertexId v = 0; v < s.num_vertices(); ++v)
    if (const HalfEdgeId e = s.out_edge(v); e != kNone) ed.out_edges()[vid(v)] = 3 * slot[tri_of(e)] + e % 3;
  ed.set_live_real(nt2);
  return flips;
}

// v's out-edge turned to its most clockwise one (a boundary vertex's
// boundary edge, as compact() leaves it; any edge of an interior vertex).
void most_clockwise_out_edge(Mesh& m, VertexId v) {
  const HalfEdgeId start = m.out_edge(v);
  if (start == kNone) return;
  HalfEdgeId e = start;
  for (HalfEdgeId cw = m.rotate_cw(e); cw != kNone && cw != start; cw = m.rotate_cw(e)) e = cw;
  m.set_out_edge(v, e);
}

}  // namespace

bool refine_strip(Mesh& whole, const RefineOptions& options, const std::vector<TriId>& seeds,
                  std::vector<std::uint8_t>& first_look, RefineStats& stats, std::size_t& strip_triangles,
                  bool refuse) {
  strip_triangles = 0;
  stats = {};
  if (whole.has_triangle_area_bounds() || seeds.empty()) return false;
  const Criteria criteria(options);
  std::vector<TriId> next = seeds, rewritten;
  RefineStats last;
  // A strip that leaves bad triangles (next to its frozen edges) is
  // written back, and the next round refines a strip around them.
  for (int round = 0; round < kStripRounds && !next.empty(); ++round) {
    std::vector<std::uint8_t> in(whole.num_triangle_slots(), 0);
    std::vector<TriId> tris;
    if (!grow_strip(whole, next, tris, in)) break;
    Part strip;
    cut_part(whole, tris, [&](TriId t) {
      return in[t] ? static_cast<TriId>(std::lower_bound(tris.begin(), tris.end(), t) - tris.begin()) : kNone;
    }, strip);
    in = {};
    canonical_triangle_order(strip.mesh);
    last = refine_scanning(strip.mesh, options, 1);
    strip_triangles += tris.size();
    // Triangles at small input angles stay bad, so the whole-mesh pass
    // will run: on the stitched mesh unchanged, when nothing is written yet.
    const bool stopped = last.budget_exhausted || last.time_exhausted || last.stalled;
    if (rewritten.empty() && (stopped || last.below_small_input_angle > 0)) return false;
    add_counts(stats, last);
    std::vector<TriId> slot;
    std::vector<HalfEdgeId> outer = write_back(whole, strip, tris, slot);
    const std::size_t flipped = rewritten.size() + slot.size();
    rewritten.insert(rewritten.end(), slot.begin(), slot.end());
    NotingTopology topo(whole, rewritten);
    constrained_lawson(topo, outer);
    // Every vertex whose out-edge may be a strip edge (or a flipped one)
    // gets the most clockwise one in the whole mesh.
    const std::size_t nv = whole.num_vertices(), ns = strip.mesh.num_vertices();
    for (VertexId v = 0; v < ns; ++v)
      most_clockwise_out_edge(whole, v < strip.global.size() ? strip.global[v] : static_cast<VertexId>(nv - ns + v));
    for (std::size_t i = flipped; i < rewritten.size(); ++i)
      for (VertexId v : whole.triangle(rewritten[i])) most_clockwise_out_edge(whole, v);
    next.clear();
    if (stopped) break;
    for (std::size_t i = flipped - slot.size(); i < rewritten.size(); ++i)
      if (criteria.bad(whole, rewritten[i])) next.push_back(rewritten[i]);
  }
  if (rewritten.empty()) return false;
  // Outside the strips and the flips, each triangle is one of a part's,
  // which the part left good (the seeds hold every one it left bad).
  bool done = !refuse && next.empty() && last.complete;
  for (std::size_t i = 0; i < rewritten.size() && done; ++i)
    done = !criteria.bad(whole, rewritten[i]) && !criteria.encroached_side(whole, rewritten[i]);
  if (done) {
    stats.complete = true;
    stats.min_angle_deg = last.min_angle_deg;
    stats.reached_angle_deg = last.reached_angle_deg;
    return true;
  }
  if (!first_look.empty()) {
    first_look.resize(whole.num_triangle_slots(), kLookAgain);
    for (TriId t : rewritten) first_look[t] = kLookAgain;
  }
  return false;
}

}  // namespace deltamesh::detail
