// Parallel Delaunay triangulation by slabs, merged along the seams.
//
// The points are cut into vertical slabs by x. Each slab is triangulated on
// its own thread by the sequential delaunay(). A triangle whose closed
// circumdisc lies inside its slab has no point of another slab in it, so it
// is a Delaunay triangle of the whole set and is kept as it is. The others
// (their disc crosses a slab boundary, or they are ghosts beyond the slab's
// hull) are dropped, found by a walk from the hull (triangulate_slab); the gap they leave, between the kept regions, is
// triangulated again from their vertices, as a constrained triangulation
// whose segments are the edges between kept and dropped triangles. Its
// triangles outside the kept regions fill the gap. Every edge of the result
// is then locally Delaunay (kept triangles have empty discs; the gap's are
// Delaunay among the gap's vertices, and the rest of the points lie inside
// the kept regions), so the result is Delaunay (the Delaunay lemma), and it
// is the sequential triangulation whenever that one is unique.
#include "algo/delaunay_parallel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/parallel.hpp"
#include "core/prefault.hpp"
#include "mesh/editor.hpp"
#include "deltamesh/cdt.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/pslg.hpp"

namespace deltamesh::detail {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kEps = std::numeric_limits<double>::epsilon();

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::uint64_t directed_key(VertexId a, VertexId b) { return (std::uint64_t{a} << 32) | b; }

// Whether the closed circumdisc of the counterclockwise triangle (a, b, c)
// lies strictly between the lines x = lo and x = hi. Computed in doubles with
// a generous bound on their rounding error (every term below is bounded with
// twice the error it can have, and the sum four times): when the answer is
// not certain it is false. A false only sends the triangle to the gap, which
// is retriangulated with exact predicates, so no triangle is ever kept
// wrongly; nearly flat triangles, whose circumcentres are ill-conditioned,
// simply always go there.
bool disc_inside_slab(const Point& a, const Point& b, const Point& c, double lo, double hi) {
  const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
  const double d = bx * cy - by * cx;
  const double dabs = std::abs(bx * cy) + std::abs(by * cx);
  const double rd = 8 * kEps * dabs / std::abs(d);  // relative error of d
  if (!(rd < 0.125)) return false;
  const double bb = bx * bx + by * by, cc = cx * cx + cy * cy;
  const double ux = (cy * bb - by * cc) / (2 * d), uy = (bx * cc - cx * bb) / (2 * d);
  const double nx_err = 16 * kEps * (std::abs(cy) * bb + std::abs(by) * cc);
  const double ny_err = 16 * kEps * (std::abs(bx) * cc + std::abs(cx) * bb);
  const double ex = (nx_err / std::abs(2 * d) + std::abs(ux) * 2 * rd) * 1.5 + 2 * kEps * std::abs(ux);
  const double ey = (ny_err / std::abs(2 * d) + std::abs(uy) * 2 * rd) * 1.5 + 2 * kEps * std::abs(uy);
  const double r = std::sqrt(ux * ux + uy * uy);
  const double centre = a.x + ux;
  const double slack = 4 * (2 * ex + ey + 8 * kEps * (std::abs(a.x) + std::abs(ux) + r));
  return centre - r - slack > lo && centre + r + slack < hi;
}

// An array whose elements are not zero-filled before they are written
// (std::vector's resize would do that, serially, ahead of the parallel
// passes that write it). malloc creates the elements: they are
// implicit-lifetime types (C++20).
template <class T>
class RawArray {
 public:
  void allocate(std::size_t n) {
    p_.reset(static_cast<T*>(std::malloc(std::max<std::size_t>(1, n) * sizeof(T))));
    if (!p_) throw std::bad_alloc();
    n_ = n;
  }
  void release() {
    p_.reset();
    n_ = 0;
  }
  T* data() const { return p_.get(); }
  std::size_t size() const { return n_; }
  std::span<const T> span() const { return {p_.get(), n_}; }

 private:
  struct Free {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> p_;
  std::size_t n_ = 0;
};

// One slab: its points, its triangulation and what the merge needs of it.
struct Slab {
  double lo = 0, hi = 0;       // lo <= x < hi
  RawArray<VertexId> ids;      // its points' input indices, increasing (freed once mapped)
  Mesh mesh;                   // closed (ghosts), in the slab's insertion order
  std::vector<VertexId> gid;   // slab vertex -> input index (of the first copy, for duplicates)
  std::size_t duplicates = 0;
  std::vector<std::pair<VertexId, VertexId>> dup_of;  // (input index of a copy, the one kept)
  std::vector<TriId> rank;     // per slot: index among the kept triangles, or kNone
  std::size_t kept = 0;
  std::vector<HalfEdgeId> seams;       // half-edges of kept triangles whose other side is dropped
  std::vector<std::uint8_t> in_gap;    // per slab vertex: in a dropped triangle or on a seam
  std::vector<VertexId> gap_vertices;  // input indices of those vertices
  std::vector<HalfEdgeId> open;        // the seams as half-edges of the result
  std::vector<HalfEdgeId> last;        // per slab vertex: its out-edge in the result, or kNone
  bool failed = false;         // no triangle: the decomposition does not apply
};

// Triangulates and classifies one slab, all in the slab's insertion
// (BRIO/Hilbert) order: its triangles and their points are near each other
// in memory there, while input numbering would scatter every point access.
void triangulate_slab(std::span<const Point> points, Slab& s, bool first) {
  const std::size_t n = points.size();
  const VertexId* ids = s.ids.data();  // slab vertex (input order) -> input index
  InsertionOrderDelaunay built;
  try {
    auto t0 = Clock::now();
    // The first slab's arrays also take the other slabs' triangles later.
    // (Its triangles, by Euler's bound, and its hole; all the points.)
    // Its points are read in place through `ids` (no copy of them).
    const std::size_t k = s.ids.size();
    built = delaunay_in_insertion_order(points, nullptr, nullptr, t0, first ? 2 * n + 2 + 2 * k + 2 : 0,
                                        first ? n : 0, {}, false, s.ids.span());
  } catch (const InputError&) {
    s.failed = true;
    return;
  }
  s.mesh = std::move(built.mesh);
  const Mesh& m = s.mesh;
  const std::size_t k = s.ids.size();
  s.gid.resize(k);
  for (std::size_t v = 0; v < k; ++v) s.gid[v] = ids[built.order[v]];
  // Of equal points the first in input order is kept (as delaunay() does).
  for (const auto& [d, got] : built.dups) s.gid[got] = std::min(s.gid[got], s.gid[d]);
  for (const auto& [d, got] : built.dups) {
    if (s.gid[d] != s.gid[got]) s.dup_of.emplace_back(s.gid[d], s.gid[got]);
    const VertexId own = ids[built.order[got]];
    if (own != s.gid[got]) s.dup_of.emplace_back(own, s.gid[got]);
  }
  s.duplicates = built.dups.size();
  s.ids.release();
  built.order = std::vector<VertexId>{};

  // The dropped triangles (and the ghosts), found from the hull instead of testing every
  // triangle: a triangle whose circumdisc reaches beyond a side of the slab
  // holds some point q there, and the triangles whose discs hold q (q's
  // Bowyer-Watson cavity, ghosts included) are connected and, q being
  // outside the hull, include a ghost. So every such triangle is joined to
  // a hull triangle through triangles that are dropped too, and only those
  // and their neighbours are tested: O(sqrt n) of the slab's triangles. The
  // test is conservative (false when unsure), so the walk never stops short
  // of one; a triangle it does not reach has its disc inside the slab, or
  // touching a side only (then a point of the next slab on the circle makes
  // it one of two Delaunay choices, and the gap, bounded by its seams,
  // fits either).
  const std::size_t slots = m.num_triangle_slots();
  constexpr std::uint8_t kUntested = 0, kKept = 1, kDropped = 2;
  std::vector<std::uint8_t> state(slots, kUntested);
  std::vector<TriId> dropped;
  const auto test = [&](TriId t) {
    if (state[t] != kUntested || !m.is_real(t)) return;
    const auto [a, b, c] = m.triangle(t);
    state[t] = disc_inside_slab(m.point(a), m.point(b), m.point(c), s.lo, s.hi) ? kKept : kDropped;
    if (state[t] == kDropped) dropped.push_back(t);
  };
  std::vector<HalfEdgeId> hull;  // the real triangles' half-edges along the hull
  for (TriId g = 0; g < slots; ++g)
    if (!m.is_dead(g) && m.is_ghost(g))
      for (HalfEdgeId e = 3 * g; e < 3 * g + 3; ++e) {
        const HalfEdgeId o = m.twin(e);
        if (!m.is_real(tri_of(o))) continue;
        hull.push_back(o);
        test(tri_of(o));
      }
  for (std::size_t i = 0; i < dropped.size(); ++i)
    for (HalfEdgeId e = 3 * dropped[i]; e < 3 * dropped[i] + 3; ++e) test(tri_of(m.twin(e)));
  s.rank.assign(slots, kNone);
  for (TriId t = 0; t < slots; ++t)
    if (state[t] != kDropped && m.is_real(t)) s.rank[t] = static_cast<TriId>(s.kept++);
  s.in_gap.assign(k, 0);
  for (TriId t : dropped)
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      s.in_gap[m.origin(e)] = 1;
      const HalfEdgeId o = m.twin(e);
      if (s.rank[tri_of(o)] != kNone) s.seams.push_back(o);
    }
  // A kept triangle on the hull borders the gap too (the ghosts are dropped).
  for (HalfEdgeId o : hull)
    if (s.rank[tri_of(o)] != kNone) {
      s.seams.push_back(o);
      s.in_gap[m.origin(o)] = s.in_gap[m.dest(o)] = 1;
    }
  std::sort(s.seams.begin(), s.seams.end());  // slot order, as a scan of the kept triangles lists them
  for (VertexId v = 0; v < k; ++v)
    if (s.in_gap[v]) s.gap_vertices.push_back(s.gid[v]);
  // Only the triangles are needed from here on: less memory at the merge
  // (the first slab's point array is reused for the result's points).
  if (!first) MeshEditor(s.mesh).points() = std::vector<Point>{};
  MeshEditor(s.mesh).out_edges() = std::vector<HalfEdgeId>{};
}

// Writes a slab's kept triangles (slab arrays sv, sw) into the result at
// triangle `first`, notes their vertices' out-edges (s.last) and the seams'
// half-edges; then frees the slab's mesh (on this thread, in parallel). The
// first slab is moved in place (sv == tv, first == 0): a kept triangle only
// moves to a lower slot, after it is read.
void copy_slab(Slab& s, std::size_t first, const VertexId* sv, const HalfEdgeId* sw, VertexId* tv, HalfEdgeId* tw) {
  const std::size_t base = 3 * first;
  // The last out-edge in slot order, as Mesh::compact() picks it: noted per
  // slab vertex (near in memory, in insertion order), then written once per
  // vertex into the result's input numbering (write_out_edges).
  std::vector<HalfEdgeId>& last = s.last;
  last.assign(s.gid.size(), kNone);
  for (TriId t = 0; t < s.rank.size(); ++t) {
    if (s.rank[t] == kNone) continue;
    const std::size_t f = base + 3 * std::size_t{s.rank[t]};
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i, o = sw[e];
      const VertexId v = sv[e];
      tv[f + i] = s.gid[v];
      last[v] = static_cast<HalfEdgeId>(f + i);
      const TriId u = s.rank[tri_of(o)];
      tw[f + i] = u == kNone ? kNone : static_cast<HalfEdgeId>(base + 3 * std::size_t{u} + o % 3);
    }
  }
  for (HalfEdgeId e : s.seams) s.open.push_back(static_cast<HalfEdgeId>(base + 3 * std::size_t{s.rank[tri_of(e)]} + e % 3));
  s.mesh = Mesh{};
  s.rank = std::vector<TriId>{};
}

// The out-edges of the slab's vertices that no other part touches.
void write_out_edges(Slab& s, HalfEdgeId* ve) {
  for (std::size_t v = 0; v < s.last.size(); ++v)
    if (s.last[v] != kNone && !s.in_gap[v]) ve[s.gid[v]] = s.last[v];
  s.last = std::vector<HalfEdgeId>{};
  s.in_gap = std::vector<std::uint8_t>{};
}

// Each slab's points (their input indices, increasing), from one
// partition pass in parallel chunks: counted per chunk and slab, then
// scattered, instead of every slab scanning all the points.
void partition_points(std::span<const Point> points, const std::vector<double>& cuts, std::vector<Slab>& slabs,
                      unsigned threads) {
  const std::size_t n = points.size(), parts = slabs.size();
  constexpr std::size_t kMinChunk = std::size_t{1} << 16;
  const std::size_t chunks = std::max<std::size_t>(1, std::min<std::size_t>(threads, n / kMinChunk));
  const auto begin = [&](std::size_t c) { return n * c / chunks; };
  const auto slab_of = [&cuts](double x) {
    return static_cast<std::size_t>(std::upper_bound(cuts.begin(), cuts.end(), x) - cuts.begin());
  };
  std::vector<std::size_t> at(chunks * parts, 0);  // per chunk and slab: a count, then where it starts
  run_tasks(chunks, threads, [&](std::size_t c) {
    std::vector<std::size_t> count(parts, 0);
    for (std::size_t i = begin(c); i < begin(c + 1); ++i) ++count[slab_of(points[i].x)];
    std::copy(count.begin(), count.end(), at.begin() + c * parts);
  });
  for (std::size_t j = 0; j < parts; ++j) {
    std::size_t total = 0;
    for (std::size_t c = 0; c < chunks; ++c) total += std::exchange(at[c * parts + j], total);
    slabs[j].ids.allocate(total);
  }
  run_tasks(chunks, threads, [&](std::size_t c) {
    std::vector<std::size_t> pos(at.begin() + c * parts, at.begin() + (c + 1) * parts);
    for (std::size_t i = begin(c); i < begin(c + 1); ++i) {
      const std::size_t j = slab_of(points[i].x), k = pos[j]++;
      slabs[j].ids.data()[k] = static_cast<VertexId>(i);
    }
  });
}

// Slab boundaries: quantiles of x over a fixed sample of the points, so the
// cut depends only on the input and the number of parts.
std::vector<double> slab_boundaries(std::span<const Point> points, unsigned parts) {
  const std::size_t step = std::max<std::size_t>(1, points.size() / 65536);
  std::vector<double> xs;
  for (std::size_t i = 0; i < points.size(); i += step) xs.push_back(points[i].x);
  // The order statistics alone (a selection each, on the serial path), not
  // a sort: the values at these ranks are the same either way.
  const double lowest = *std::min_element(xs.begin(), xs.end());
  std::vector<double> cuts;
  auto from = xs.begin();
  for (unsigned j = 1; j < parts; ++j) {
    const auto at = xs.begin() + static_cast<std::ptrdiff_t>(j * xs.size() / parts);
    std::nth_element(from, at, xs.end());  // what lies before `from` ranks below `at`
    from = at;
    const double c = *at;
    if (c > lowest && (cuts.empty() || c > cuts.back())) cuts.push_back(c);
  }
  return cuts;
}

}  // namespace

std::optional<Mesh> parallel_delaunay(std::span<const Point> points, unsigned parts, unsigned threads,
                                      DelaunayStats* stats) {
  const std::size_t n = points.size();
  if (parts < 2 || n < 3) return std::nullopt;
  auto t0 = Clock::now();
  const std::vector<double> cuts = slab_boundaries(points, parts);
  if (cuts.empty()) return std::nullopt;
  std::vector<Slab> slabs(cuts.size() + 1);
  for (std::size_t j = 0; j < slabs.size(); ++j) {
    slabs[j].lo = j == 0 ? -std::numeric_limits<double>::infinity() : cuts[j - 1];
    slabs[j].hi = j == cuts.size() ? std::numeric_limits<double>::infinity() : cuts[j];
  }
  // The first slab's triangle arrays become the result's (sized for all of
  // it, by Euler's bound): no copy of that slab and no second allocation.
  partition_points(points, cuts, slabs, threads);
  run_tasks(slabs.size(), threads, [&](std::size_t j) { triangulate_slab(points, slabs[j], j == 0); });
  for (const Slab& s : slabs)
    if (s.failed) return std::nullopt;
  if (stats) stats->sort_seconds = seconds_since(t0);
  t0 = Clock::now();

  // The gap: its vertices (input order) and its segments (the seams).
  std::vector<VertexId> gap_ids;
  for (const Slab& s : slabs) gap_ids.insert(gap_ids.end(), s.gap_vertices.begin(), s.gap_vertices.end());
  std::sort(gap_ids.begin(), gap_ids.end());
  std::unordered_map<VertexId, VertexId> gap_index;
  gap_index.reserve(2 * gap_ids.size());
  Pslg g;
  g.points.reserve(gap_ids.size());
  for (VertexId v : gap_ids) {
    gap_index.emplace(v, static_cast<VertexId>(g.points.size()));
    g.points.push_back(points[v]);
  }
  for (const Slab& s : slabs)
    for (HalfEdgeId e : s.seams) {
      const VertexId a = gap_index.at(s.gid[s.mesh.origin(e)]), b = gap_index.at(s.gid[s.mesh.dest(e)]);
      g.segments.push_back({std::min(a, b), std::max(a, b), 0});
    }
  std::sort(g.segments.begin(), g.segments.end(),
            [](const Segment& x, const Segment& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  g.segments.erase(std::unique(g.segments.begin(), g.segments.end(),
                               [](const Segment& x, const Segment& y) { return x.a == y.a && x.b == y.b; }),
                   g.segments.end());
  CdtOptions copt;
  copt.strict = true;  // seams are edges of Delaunay triangles: they cannot cross
  Mesh gap;
  try {
    gap = constrained_triangulation(g, copt);
  } catch (const InputError& e) {
    throw InternalError("parallel_delaunay", std::string("the seams do not make a triangulation: ") + e.what());
  }
  if (gap.num_vertices() != gap_ids.size())
    throw InternalError("parallel_delaunay", "the gap's triangulation added vertices");

  // The kept regions seen from the gap: flood from the kept side of every
  // seam, never across a seam.
  std::unordered_map<std::uint64_t, HalfEdgeId> gap_edge;
  gap_edge.reserve(4 * gap.num_triangle_slots());
  const std::size_t gap_slots = gap.num_triangle_slots();
  for (TriId t = 0; t < gap_slots; ++t)
    if (gap.is_real(t))
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) gap_edge.emplace(directed_key(gap.origin(e), gap.dest(e)), e);
  std::vector<std::uint8_t> covered(gap_slots, 0);
  std::vector<TriId> stack;
  for (const Slab& s : slabs)
    for (HalfEdgeId e : s.seams) {
      const auto it = gap_edge.find(
          directed_key(gap_index.at(s.gid[s.mesh.origin(e)]), gap_index.at(s.gid[s.mesh.dest(e)])));
      if (it == gap_edge.end()) throw InternalError("parallel_delaunay", "a seam is not an edge of the gap");
      const TriId t = tri_of(it->second);
      if (!covered[t]) {
        covered[t] = 1;
        stack.push_back(t);
      }
    }
  while (!stack.empty()) {
    const TriId t = stack.back();
    stack.pop_back();
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (gap.is_constrained(e) || gap.twin(e) == kNone) continue;
      const TriId u = tri_of(gap.twin(e));
      if (gap.is_real(u) && !covered[u]) {
        covered[u] = 1;
        stack.push_back(u);
      }
    }
  }

  // The result: each slab's kept triangles in slot order, slab after slab,
  // then the gap's triangles outside the kept regions. The first slab is
  // compacted in place, so the others start after its slots; the hole it
  // leaves (its dropped triangles and ghosts, a few per hull and seam edge)
  // is filled from the end below.
  std::vector<std::size_t> offset(slabs.size() + 1, 0);
  const std::size_t first_slots = slabs[0].rank.size();
  for (std::size_t j = 0; j < slabs.size(); ++j) offset[j + 1] = (j == 0 ? first_slots : offset[j] + slabs[j].kept);
  std::vector<TriId> gap_rank(gap_slots, kNone);
  std::size_t gap_count = 0;
  for (TriId t = 0; t < gap_slots; ++t)
    if (gap.is_real(t) && !covered[t]) gap_rank[t] = static_cast<TriId>(gap_count++);
  const std::size_t end = offset.back() + gap_count;  // slots in use, holes included
  const std::size_t total = end - (first_slots - slabs[0].kept);
  if (end >= kNone / 3) throw InputError("too many triangles: at most 1431655764 are supported");

  std::size_t duplicates = 0;
  for (const Slab& s : slabs) duplicates += s.duplicates;
  Mesh out;
  std::vector<VertexId>& tv = MeshEditor(out).triangle_vertices();
  std::vector<HalfEdgeId>& tw = MeshEditor(out).twins();
  std::vector<HalfEdgeId>& ve = MeshEditor(out).out_edges();
  tv = std::move(MeshEditor(slabs[0].mesh).triangle_vertices());
  tw = std::move(MeshEditor(slabs[0].mesh).twins());
  if (tv.size() != 3 * first_slots) throw InternalError("parallel_delaunay", "the first slab's arrays changed size");
  if (3 * end > tv.capacity() || 3 * end > tw.capacity()) {  // (reserved by Euler's bound: not expected)
    tv.resize(3 * end);
    tw.resize(3 * end);
  }
  // The result's arrays are filled (std::vector zero-fills what it grows)
  // by the first two tasks, beside the copies, not serially before them:
  // task 0 the points and out-edges, then it compacts the first slab in
  // place (below its old size); task 1 grows the triangle arrays within
  // their capacity (their data does not move), then copies its slab and
  // fills the duplicate map. Tasks are taken in index order, so a task that
  // waits for these two waits for tasks already running. A flag is set on
  // every exit; `fill_failed` says the fill threw (run_tasks rethrows it).
  VertexId* const tvp = tv.data();
  HalfEdgeId* const twp = tw.data();
  const bool grows = 3 * end > tv.size();  // (read here: task 1 resizes)
  std::atomic<bool> grown{false}, filled{false}, fill_failed{false};
  struct Raise {
    std::atomic<bool>& flag;
    ~Raise() { flag.store(true, std::memory_order_release); }
  };
  const auto wait = [&](const std::atomic<bool>& flag) {
    while (!flag.load(std::memory_order_acquire)) std::this_thread::yield();
    return !fill_failed.load(std::memory_order_acquire);
  };
  run_tasks(slabs.size(), threads, [&](std::size_t j) {
    Slab& s = slabs[j];
    if (j == 0) {
      // The second half of what task 1's growth will zero-fill: its page
      // faults taken here (nothing is written), so that the two tasks share
      // them; task 1 also has the other slab's copy to fault in.
      if (grows) {
        const std::size_t from = 3 * first_slots, half = from + (3 * end - from) / 2;
        // (The twins first: task 1 grows the vertices first.)
        prefault_for_write(twp + half, (3 * end - half) * sizeof(HalfEdgeId));
        prefault_for_write(tvp + half, (3 * end - half) * sizeof(VertexId));
      }
      {
        const Raise done{filled};
        try {
          MeshEditor(out).points() = std::move(MeshEditor(s.mesh).points());  // capacity for all
          MeshEditor(out).points().assign(points.begin(), points.end());
          // Duplicates keep kNone; every other vertex is given an out-edge.
          ve.assign(n, kNone);
        } catch (...) {
          fill_failed.store(true, std::memory_order_release);
          throw;
        }
      }
      copy_slab(s, 0, tvp, twp, tvp, twp);
    } else {
      if (j == 1) {
        const Raise done{grown};
        try {
          tv.resize(3 * end);
          tw.resize(3 * end);
        } catch (...) {
          fill_failed.store(true, std::memory_order_release);
          throw;
        }
      } else if (!wait(grown)) {
        return;
      }
      copy_slab(s, offset[j], s.mesh.triangle_vertices().data(), MeshEditor(s.mesh).twins().data(), tvp, twp);
      // After the copy has freed this slab's mesh: no higher peak of memory.
      if (j == 1 && stats) stats->duplicate_of.assign(n, kNone);
    }
    if (wait(filled)) write_out_edges(s, ve.data());
  });
  // Half-edges left without a twin: seams, the gap's edges along them, and
  // the hull; paired by their vertices. The gap's vertices get their
  // out-edges here: from the seams, then from the gap's triangles.
  std::vector<HalfEdgeId> open;
  for (const Slab& s : slabs) {
    open.insert(open.end(), s.open.begin(), s.open.end());
    for (HalfEdgeId h : s.open) ve[tv[h]] = h;
  }
  const std::size_t gap_base = 3 * offset.back();
  for (TriId t = 0; t < gap_slots; ++t) {
    if (gap_rank[t] == kNone) continue;
    const std::size_t f = gap_base + 3 * std::size_t{gap_rank[t]};
    for (int i = 0; i < 3; ++i) {
      const HalfEdgeId e = 3 * t + i, o = gap.twin(e);
      tv[f + i] = gap_ids[gap.origin(e)];
      ve[tv[f + i]] = static_cast<HalfEdgeId>(f + i);
      const TriId u = o == kNone ? kNone : gap_rank[tri_of(o)];
      tw[f + i] = u == kNone ? kNone : static_cast<HalfEdgeId>(gap_base + 3 * std::size_t{u} + o % 3);
      if (u == kNone) open.push_back(static_cast<HalfEdgeId>(f + i));
    }
  }
  std::unordered_map<std::uint64_t, HalfEdgeId> by_vertices;
  by_vertices.reserve(2 * open.size());
  for (HalfEdgeId h : open) by_vertices.emplace(directed_key(tv[h], tv[next_edge(h)]), h);
  std::size_t hull = 0;
  for (HalfEdgeId h : open) {
    const auto it = by_vertices.find(directed_key(tv[next_edge(h)], tv[h]));
    if (it == by_vertices.end()) {
      ++hull;
      ve[tv[h]] = h;  // a boundary vertex starts its fan at its boundary edge, as Mesh::compact() has it
      continue;
    }
    tw[h] = it->second;
  }
  // The first slab's hole, [kept, first_slots) as far as it lies below
  // `total`, takes the triangles beyond `total`, in order (as
  // Mesh::compact() fills its holes, over these few slots only).
  {
    std::size_t to = slabs[0].kept, from = std::max(first_slots, total);
    for (; from < end; ++from, ++to)
      for (int i = 0; i < 3; ++i) {
        const std::size_t o = 3 * from + i, m = 3 * to + i;
        tv[m] = tv[o];
        tw[m] = tw[o];
        if (tw[m] != kNone) tw[tw[m]] = static_cast<HalfEdgeId>(m);
        if (ve[tv[m]] == o) ve[tv[m]] = static_cast<HalfEdgeId>(m);
      }
    if (to != std::min(first_slots, total)) throw InternalError("parallel_delaunay", "the first slab's hole is not filled");
    tv.resize(3 * total);
    tw.resize(3 * total);
  }
  // Euler: a triangulation of k distinct points with h hull edges has
  // 2k - 2 - h triangles; anything else is an overlap or a hole.
  if (total + 2 + hull != 2 * (n - duplicates))
    throw InternalError("parallel_delaunay", "the merged triangulation has " + std::to_string(total) +
                                                 " triangles, " + std::to_string(hull) + " hull edges and " +
                                                 std::to_string(n - duplicates) + " vertices");
  for (VertexId v : gap_ids)
    if (ve[v] == kNone || tv[ve[v]] != v)
      throw InternalError("parallel_delaunay", "vertex " + std::to_string(v) + " of the gap has no out-edge");
  // The result is compact as built (only real triangles, no free slots,
  // out-edges set): no Mesh::compact() pass over all of it.
  MeshEditor(out).set_live_real(total);
  MeshEditor(out).set_compacted();

  if (stats) {
    stats->duplicates = duplicates;
    for (const Slab& s : slabs)
      for (const auto& [copy, kept] : s.dup_of) stats->duplicate_of[copy] = kept;
    stats->insert_seconds = seconds_since(t0);
  }
  return out;
}

}  // namespace deltamesh::detail
