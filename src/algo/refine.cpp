// Delaunay refinement (seed §3, Figure 18) with off-centres and the §3.6
// small-angle rules. See include/deltamesh/refine.hpp for the interface.
//
// Method, from the literature (no code taken from any implementation):
//  - J. Ruppert, "A Delaunay refinement algorithm for quality 2-dimensional
//    mesh generation", J. Algorithms 1995: rules R1/R2, diametral circles.
//  - J. R. Shewchuk, "Delaunay refinement algorithms for triangular mesh
//    generation", CGTA 2002: concentric shells around input vertices,
//    diametral lenses, refusing segment splits that would cascade at small
//    angles, worst-first processing.
//  - A. Üngör, "Off-centers: a new type of Steiner points for computing
//    size-optimal quality-guaranteed Delaunay triangulations", LATIN 2004.
//  - G. L. Miller, S. E. Pav, N. J. Walkington, "When and why Ruppert's
//    algorithm works", IMR 2003: do not split skinny triangles whose shortest
//    edge faces a small input angle.
//
// Design (see docs in refine.hpp):
//  - Insertion is Bowyer-Watson on the raw mesh arrays: the cavity (triangles
//    whose circumcircle strictly contains the point, grown without crossing
//    constrained edges) is found read-only first, so the same search tells
//    whether a Steiner point encroaches a segment (R2) before anything
//    changes; committing rewrites the k cavity slots and appends two.
//  - A point is located by a straight walk from the skinny triangle towards
//    it that stops at the first segment it would cross: a point beyond a
//    segment splits that segment instead.
//  - Bad triangles wait in a queue of 1024 buckets keyed by the sine of their
//    smallest angle (worst first, O(1) push/pop with a bitmap); triangles
//    that are only too large wait on a LIFO stack (depth-first, which keeps
//    the working set in cache). Entries carry their slot and three vertex
//    ids; a stale entry is recognised on pop.
//  - Encroached subsegments (R1) go first, on a stack of vertex pairs.
#include "deltamesh/refine.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>

#include "core/expansion.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/progress.hpp"

namespace deltamesh {

namespace {

using Clock = std::chrono::steady_clock;

// Exact sign of (a - p)·(b - p): negative iff p lies strictly inside the
// circle with diameter ab. The magnitude is an approximation.
double diametral_dot(const Point& a, const Point& b, const Point& p) {
  const double ax = a.x - p.x, bx = b.x - p.x, ay = a.y - p.y, by = b.y - p.y;
  const double t1 = ax * bx, t2 = ay * by;
  const double det = t1 + t2;
  const double bound = 8.0 * detail::kEpsilon * (std::fabs(t1) + std::fabs(t2));
  if (det > bound || -det > bound) return det;
  double dax[2], dbx[2], day[2], dby[2];
  detail::two_diff(a.x, p.x, dax[1], dax[0]);
  detail::two_diff(b.x, p.x, dbx[1], dbx[0]);
  detail::two_diff(a.y, p.y, day[1], day[0]);
  detail::two_diff(b.y, p.y, dby[1], dby[0]);
  double px[8], py[8], work[12], sum[16];
  const int nx = detail::expansion_product(2, dax, 2, dbx, px, work);
  const int ny = detail::expansion_product(2, day, 2, dby, py, work);
  const int n = detail::fast_expansion_sum_zeroelim(nx, px, ny, py, sum);
  return detail::signed_estimate(n, sum);
}

// The coarsest multiple of a power of two in the middle of [lo, hi], at
// least 1 - 1/sqrt2 of the way from either end (for lo = 0, the concentric
// shell). Splits of the segments around one apex then all fall on one
// nested set of radii: vertices of neighbouring segments sit at equal radii
// or as far apart as the subsegments they split. Midpoints of subsegments
// of unequal segments drift into pairs of radii far closer than the local
// feature size; the short edges between them make skinny triangles whose
// splits, mirrored around the apex, cascade (hubs of many spokes of random
// lengths ran to the budget).
double grid_radius(double lo, double hi) {
  const double margin = (1.0 - 0.5 * std::numbers::sqrt2) * (hi - lo);
  const double l = lo + margin, h = hi - margin;
  int ex;
  std::frexp(hi, &ex);  // hi < 2^ex
  for (double step = std::ldexp(1.0, ex); step > 0; step *= 0.5) {
    const double r = std::floor(h / step) * step;
    if (r >= l) return r;
  }
  return 0.5 * (lo + hi);
}

inline double dist2(const Point& a, const Point& b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

constexpr int kBuckets = 2048;

// Tuning, measured on the corpus (see the report in the refinement notes):
// off-centres a little nearer than the bound's petal tip, so that new
// triangles clear the bound after rounding; concentric shells only around
// input vertices with a domain angle under 60° (midpoints elsewhere); the
// mid-wedge small-angle rule for wedges under 10° (wider wedges are refined,
// only the triangle holding the input angle is left).
constexpr double kOffcentreShrink = 0.98;
constexpr double kShellApexAngle = 60.0;
constexpr double kWedgeAngle = 10.0;
// Thin channels (spikes): the sides of a wedge under kWedgeAngle, continued
// through input vertices that bend less than kChannelBend, bound a channel
// where two of them run within kChannelParallel of each other, closer than
// 1/kChannelGap of their lengths. Refining there cascades down the spike
// (a star polygon with 1e-4 rad spikes needs ~L/gap triangles per spike).
constexpr double kChannelBend = 30.0;
constexpr double kChannelParallel = 10.0;
constexpr double kChannelGap = 64.0;
// Triangles skipped for reasons that depend on their neighbours (a refused
// or impossible segment split) get this many more looks once the queue runs dry.
constexpr int kRequeueRounds = 4;

// Why a bad triangle was left alone.
enum class Reason : std::uint8_t { None, SmallAngle, Protected, Precision, Budget, OutOfReach };

struct QueueEntry {
  TriId t;
  VertexId a, b, c;
};

// The bad-triangle queue: skinny triangles in buckets by quality (worst
// first), triangles that are only too large on a LIFO stack.
class BadQueue {
 public:
  BadQueue() {
    for (auto& b : buckets_) b.reserve(4);
  }
  void push_skinny(int key, const QueueEntry& e) {
    buckets_[key].push_back(e);
    bits_[key >> 6] |= std::uint64_t{1} << (key & 63);
    ++size_;
    ++skinny_;
  }
  void push_large(const QueueEntry& e) {
    large_.push_back(e);
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  QueueEntry pop() {
    --size_;
    if (skinny_ == 0) {
      const QueueEntry e = large_.back();
      large_.pop_back();
      return e;
    }
    --skinny_;
    for (int w = 0; w < kBuckets / 64; ++w) {
      if (bits_[w] == 0) continue;
      const int key = 64 * w + std::countr_zero(bits_[w]);
      std::vector<QueueEntry>& b = buckets_[key];
      const QueueEntry e = b.back();
      b.pop_back();
      if (b.empty()) bits_[w] &= ~(std::uint64_t{1} << (key & 63));
      return e;
    }
    const QueueEntry e = large_.back();
    large_.pop_back();
    return e;
  }
  template <class F>
  void for_each(F&& f) const {
    for (const auto& b : buckets_)
      for (const QueueEntry& e : b) f(e);
    for (const QueueEntry& e : large_) f(e);
  }

 private:
  std::array<std::vector<QueueEntry>, kBuckets> buckets_;
  std::array<std::uint64_t, kBuckets / 64> bits_{};
  std::vector<QueueEntry> large_;
  std::size_t size_ = 0;
  std::size_t skinny_ = 0;
};

struct Eval {
  bool skinny = false;
  bool large = false;
  int shortest = 0;       // local index i of the shortest edge (3t+i)
  double sin2 = 1.0;      // sin^2 of the smallest angle
  double shortest2 = 0;   // squared length of the shortest edge
};

// A triangle as the small-angle rules see it: a mesh triangle, or one a
// segment split would make (its new vertex not in the mesh yet).
struct TriView {
  TriId t;                  // the mesh triangle (or the one split), for size bounds
  VertexId v[3];            // counter-clockwise
  Point p[3];
  std::uint32_t seg[3];     // the segment a Steiner vertex lies on (kNone: none, or an input vertex)
  bool constrained[3];      // edge v[i] -> v[i+1]
};

// A subsegment to split later: its vertices and a half-edge that may still be it.
struct SubsegmentRef {
  VertexId a, b;
  HalfEdgeId hint;
};

// One edge of a cavity's boundary, copied before the cavity is rewritten.
struct BoundaryEdge {
  VertexId a, b;        // a -> b, counter-clockwise around the cavity
  HalfEdgeId inner;     // the half-edge a -> b inside the cavity (valid until it is rewritten)
  HalfEdgeId outer;     // the half-edge b -> a outside the cavity, or kNone
  std::uint8_t flags;
  int marker;
  double area_bound;
};

class Refiner {
 public:
  Refiner(Mesh& mesh, const RefineOptions& opt, RefineStats& st)
      : m_(mesh),
        opt_(opt),
        st_(st),
        tv_(mesh.tri_v_mut()),
        tw_(mesh.twin_mut()),
        fl_(mesh.edge_flags_mut()),
        mk_(mesh.edge_markers_mut()),
        pts_(mesh.points_mut()),
        ve_(mesh.vert_edge_mut()) {}

  void run();

 private:
  void set_bound(double theta);
  void queue_encroached();
  void refine_loop(ProgressReporter& progress);
  void go_beyond(ProgressReporter& progress);
  void checkpoint();
  double smallest_sin2(bool outside_small_angles) const;
  // ---- setup -------------------------------------------------------------
  void setup();
  void reserve_for_area_bounds();
  std::uint32_t input_segment(VertexId a, VertexId b) const;
  void mark_spikes();

  // ---- triangle quality ----------------------------------------------------
  double area_bound(TriId t, const Point& a, const Point& b, const Point& c) const;
  Eval eval(TriId t) const;
  Eval eval(TriId t, const Point& a, const Point& b, const Point& c) const;
  TriView view(TriId t) const;
  void consider(TriId t);
  void remember_skip(TriId t, Reason r) {
    if (t >= why_.size()) why_.resize(std::max<std::size_t>(t + 1, tv_.size() / 3), Reason::None);
    why_[t] = r;
  }
  bool alive(const QueueEntry& e) const {
    return e.t < tv_.size() / 3 && tv_[3 * e.t] == e.a && tv_[3 * e.t + 1] == e.b && tv_[3 * e.t + 2] == e.c;
  }
  bool faces_small_angle(TriId t, const Eval& ev) const { return faces_small_angle(view(t), ev); }
  bool faces_small_angle(const TriView& tv, const Eval& ev, bool holding = true) const;
  bool wedge_rule(const TriView& tv, const Eval& ev, bool holding) const;
  bool in_channel(const TriView& tv) const;
  bool channel_pair(std::uint32_t sa, std::uint32_t sb, double& gap2) const;
  bool near_channel(const Point& p, std::uint32_t sa, std::uint32_t sb, double gap2) const;
  template <class F>
  void spike_segments(VertexId v, std::uint32_t seg, F&& f) const;
  bool left_alone(const TriView& tv, bool holding) const;
  void apexes(VertexId v, std::uint32_t seg, std::array<std::pair<VertexId, std::uint32_t>, 2>& small, int& n,
              std::vector<std::pair<VertexId, std::uint32_t>>& many) const;

  // ---- Steiner points --------------------------------------------------------
  Point steiner_point(TriId t, const Eval& ev, bool& offcenter) const;
  Point best_point(TriId t, const Eval& ev, const Point& primary);
  bool score(TriId t, const Point& c, double min2, int& bad, double& radius2);
  Point split_point(VertexId a, VertexId b) const;

  // ---- location and cavities --------------------------------------------------
  struct Walk {
    enum Kind { Found, OnVertex, Blocked, Failed } kind;
    TriId tri = kNone;
    HalfEdgeId edge = kNone;  // Found: the edge c lies on (or kNone); Blocked: the segment crossed
  };
  Walk walk(TriId t, const Point& c) const;
  bool cavity(const Point& c, TriId seed);
  bool split_cavity(HalfEdgeId e, const Point& m);
  bool in_circumcircle(TriId t, const Point& p) const;
  bool keep_split_inside(HalfEdgeId e, Point& m) const;
  bool grow(const Point& c, std::size_t stack_base);
  void record_boundary(HalfEdgeId e);
  bool boundary_visible(const Point& c, std::size_t from, std::size_t to) const;

  // ---- encroachment -----------------------------------------------------------
  bool encroaches(const Point& a, const Point& b, const Point& p) const;
  bool encroached(HalfEdgeId e) const;
  bool splittable(HalfEdgeId e) const;
  bool refuse_split(HalfEdgeId e, const Eval& ev) const;
  bool excused(HalfEdgeId e) const;
  void check_encroached(HalfEdgeId e, VertexId apex);

  // ---- actions ------------------------------------------------------------------
  struct Decision {
    enum Kind { Skip, Split, Insert } kind = Skip;
    Reason reason = Reason::None;
    bool transient = false;  // a skip that may change when neighbours change
    Point c;
    bool offcenter = false;
    std::vector<SubsegmentRef> segments;
  };
  void decide(TriId t, Decision& d);
  void decide_segments(const std::vector<HalfEdgeId>& encroached, const Eval& ev, Decision& d);
  VertexId new_vertex(const Point& p, std::uint32_t seg, int marker);
  void insert_interior(const Point& c, TriId seed);
  bool split_segment(HalfEdgeId e, const Point* at = nullptr, int depth = 0);
  void mirror(std::uint32_t seg, VertexId apex, double radius, int depth);
  double gap2(std::uint32_t s, std::uint32_t t, VertexId apex, double radius) const;
  TriId take_slot(std::size_t i, std::size_t fan, VertexId v);
  void carry_attributes();
  bool budget_left();
  HalfEdgeId edge(VertexId a, VertexId b, HalfEdgeId hint) const;
  void finish();

  Mesh& m_;
  const RefineOptions& opt_;
  RefineStats& st_;
  std::vector<VertexId>& tv_;
  std::vector<HalfEdgeId>& tw_;
  std::vector<std::uint8_t>& fl_;
  std::vector<int>& mk_;
  std::vector<Point>& pts_;
  std::vector<HalfEdgeId>& ve_;

  // Parameters.
  double sin2_bound_ = 0;       // sin^2 of the angle bound (0: no angle criterion)
  double off_factor_ = 0;       // off-centre distance from the shortest edge, per unit of its length
  double lens_cos2_ = 0;        // lens: cos^2 of the smallest subtended angle that encroaches
  bool lens_ = false;
  bool has_area_bounds_ = false;  // refine for the mesh's per-triangle bounds
  bool carry_bounds_ = false;     // the mesh has per-triangle bounds: keep them on new triangles
  bool shortest_first_ = true;    // queue order
  bool best_ = false;             // SteinerRule::Best: choose among candidates
  bool sized_ = false;            // some size bound (area or edge length) applies
  double bound_rad_ = 0;          // the angle bound in radians
  bool has_markers_ = false;
  double precision2_ = 0;       // squared shortest edge below which nothing is split
  double shell_cos_ = -2;       // input vertices whose smallest segment angle has a larger cosine get shells
  double small_cos2_ = 0.25;    // cos^2 of the largest input angle the small-angle rule treats as small
  double channel_sin2_ = 0;     // sin^2 of the largest angle between the two sides of a channel
  std::vector<float> apex_cos_; // per input vertex: cosine of its smallest angle between segments (-2: none)
  std::size_t budget_ = kUnlimited;
  std::size_t n_input_ = 0;

  // Input segments (the constrained edges when refinement starts).
  std::vector<std::array<VertexId, 2>> segs_;
  std::vector<std::uint8_t> seg_small_;      // bit 0/1: endpoint 0/1 is a small-angle apex for it
  // Per segment: kBoundarySeg (domain on one side only, to the left of
  // segs_[s][0] -> segs_[s][1]) and kSpikeSeg (a boundary side of a spike,
  // see kChannelBend).
  static constexpr std::uint8_t kBoundarySeg = 1, kSpikeSeg = 2;
  std::vector<std::uint8_t> seg_spike_;
  bool has_spikes_ = false;
  std::vector<std::uint32_t> adj_start_;     // CSR over input vertices
  std::vector<std::pair<VertexId, std::uint32_t>> adj_;  // (other endpoint, segment)
  std::vector<std::uint32_t> seg_of_;        // per Steiner vertex on a segment: its segment
  // Per segment end (2 s + 0/1): the segments bounding a small domain angle
  // with it at that end, whose splits are mirrored at the same radius.
  std::vector<std::array<std::uint32_t, 2>> partners_;

  BadQueue queue_;
  std::vector<SubsegmentRef> encroached_;
  std::vector<QueueEntry> skipped_;  // transient skips, for another look
  // Per triangle slot: why it was last left alone (reset when the slot is
  // rewritten), so that finish() classifies what is left in linear time.
  std::vector<Reason> why_;

  // Scratch, reused by every insertion.
  std::vector<TriId> cav_;
  // Cavity membership in O(1): in_cav_[t] == cav_stamp_ while t is in cav_
  // (a huge cocircular cavity made the linear search quadratic).
  std::vector<std::uint32_t> in_cav_;
  std::uint32_t cav_stamp_ = 0;
  void begin_cavity() {
    cav_.clear();
    bnd_.clear();
    stack_.clear();
    if (++cav_stamp_ == 0) {
      std::fill(in_cav_.begin(), in_cav_.end(), 0);
      cav_stamp_ = 1;
    }
  }
  void add_to_cavity(TriId t) {
    if (t >= in_cav_.size()) in_cav_.resize(std::max<std::size_t>(t + 1, 2 * in_cav_.size()), 0);
    in_cav_[t] = cav_stamp_;
    cav_.push_back(t);
  }
  bool in_cavity(TriId t) const { return t < in_cav_.size() && in_cav_[t] == cav_stamp_; }
  std::vector<BoundaryEdge> bnd_;
  std::vector<HalfEdgeId> stack_;
  std::vector<TriId> fan_;
  std::vector<HalfEdgeId> enc_scratch_;
  std::vector<double> attr_scratch_;
  std::size_t side_split_ = 0;  // split cavities: boundary edges of side one
  Decision decision_;

  std::size_t appended_ = 0;  // triangles appended without Mesh::add_triangle
  void count_appended();     // adds them to the mesh's count
  Clock::time_point start_;
  std::size_t iterations_ = 0;
  int requeues_ = 0;
  std::size_t requeue_mark_ = SIZE_MAX;  // Steiner points when the last requeue round began
  bool stopped_ = false;

  // Progress watch (above the guaranteed range).
  bool watch_ = false;
  std::size_t watch_cap_ = 0;
  std::size_t next_check_ = 0;
  std::size_t check_interval_ = 0;
  std::size_t window_start_ = 0;       // first vertex added since the last checkpoint
  std::size_t best_bad_ = SIZE_MAX;    // fewest triangles below the bound at a checkpoint
  double best_sin2_ = -1;              // best smallest angle (sin^2) outside small input angles
  int stale_checks_ = 0;
  bool stalled_ = false;
  bool beyond_ = false;                // the bound is above kAutomaticBudgetAngle
};

// ===========================================================================
// Setup

void Refiner::setup() {
  n_input_ = pts_.size();
  st_.input_vertices = n_input_;
  const double theta = std::clamp(opt_.min_angle_deg, 0.0, 60.0);
  shell_cos_ = std::cos(kShellApexAngle * std::numbers::pi / 180);
  small_cos2_ = std::cos(kWedgeAngle * std::numbers::pi / 180) * std::cos(kWedgeAngle * std::numbers::pi / 180);
  shortest_first_ = opt_.order == RefineOrder::ShortestEdgeFirst;
  best_ = opt_.steiner == SteinerRule::Best && theta > 0;
  lens_ = opt_.encroachment == EncroachmentRule::DiametralLens && !opt_.conforming_delaunay;
  // Beyond the bounds refinement reaches in practice, first refine to
  // kAutomaticBudgetAngle, which terminates, then go on (go_beyond()).
  beyond_ = theta > kAutomaticBudgetAngle;
  set_bound(beyond_ ? kAutomaticBudgetAngle : theta);
  carry_bounds_ = m_.has_triangle_area_bounds();
  has_area_bounds_ = opt_.use_triangle_area_bounds && carry_bounds_;
  sized_ = opt_.max_area > 0 || has_area_bounds_ || opt_.max_area_at || opt_.max_edge_at;
  budget_ = opt_.max_steiner;
  if (budget_ == kAutomaticBudget) budget_ = kAutomaticBudgetBase + kAutomaticBudgetPerVertex * n_input_;

  // Bounding box: the precision floor for splitting.
  double lox = 0, hix = 0, loy = 0, hiy = 0;
  bool first = true;
  for (VertexId v : tv_) {
    if (v >= pts_.size()) continue;
    const Point& p = pts_[v];
    if (first) {
      lox = hix = p.x;
      loy = hiy = p.y;
      first = false;
    }
    lox = std::min(lox, p.x), hix = std::max(hix, p.x), loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
  }
  // Edges shorter than 2^-36 of the coordinates' magnitude (or 2^-45 of the
  // diameter) are not split: below that, rounded split points bend segments
  // visibly and circumcentres lose their meaning.
  const double mag = std::max({std::fabs(lox), std::fabs(hix), std::fabs(loy), std::fabs(hiy)});
  const double diag = std::sqrt((hix - lox) * (hix - lox) + (hiy - loy) * (hiy - loy));
  const double floor_len = std::max(mag * 0x1p-36, diag * 0x1p-45);
  precision2_ = floor_len * floor_len;

  // Every boundary edge is a segment.
  const std::size_t ne = tv_.size();
  for (HalfEdgeId e = 0; e < ne; ++e)
    if (tw_[e] == kNone && !m_.is_constrained(e)) m_.set_edge_flags(e, m_.edge_flags(e) | kConstrained);
  has_markers_ = m_.has_edge_markers();

  // Input segments and their incidence at input vertices.
  adj_start_.assign(n_input_ + 1, 0);
  for (HalfEdgeId e = 0; e < ne; ++e) {
    if (!(fl_[e] & kConstrained) || (tw_[e] != kNone && tw_[e] < e)) continue;
    const VertexId a = tv_[e], b = tv_[next_edge(e)];
    segs_.push_back({a, b});
    seg_spike_.push_back(tw_[e] == kNone ? kBoundarySeg : 0);  // a boundary one runs with the domain on its left
    ++adj_start_[a + 1];
    ++adj_start_[b + 1];
  }
  for (std::size_t v = 0; v < n_input_; ++v) adj_start_[v + 1] += adj_start_[v];
  adj_.resize(adj_start_[n_input_]);
  {
    std::vector<std::uint32_t> fill(adj_start_.begin(), adj_start_.end() - 1);
    for (std::uint32_t s = 0; s < segs_.size(); ++s) {
      const auto [a, b] = segs_[s];
      adj_[fill[a]++] = {b, s};
      adj_[fill[b]++] = {a, s};
    }
  }
  // Small-angle apexes: two segments at an input vertex that bound a sector
  // of the domain narrower than 60° (the angle inside a hole or outside the
  // domain does not count). A sector runs counter-clockwise from a
  // constrained out-edge through unconstrained edges to the next
  // constrained edge; its angle is the sum of the triangle corners in it.
  seg_small_.assign(segs_.size(), 0);
  partners_.assign(2 * segs_.size(), {kNone, kNone});
  apex_cos_.assign(n_input_, -2.0f);
  for (HalfEdgeId e0 = 0; e0 < ne; ++e0) {
    const VertexId v = tv_[e0];
    if (v >= n_input_ || !(fl_[e0] & kConstrained)) continue;
    const Point& A = pts_[v];
    double angle = 0;
    HalfEdgeId g = e0;
    bool closed = false;
    for (std::size_t guard = 0; guard < 1u << 20; ++guard) {
      const HalfEdgeId p = prev_edge(g);  // y -> v, the corner's other edge
      const Point& X = pts_[tv_[next_edge(g)]];
      const Point& Y = pts_[tv_[p]];
      const double ux = X.x - A.x, uy = X.y - A.y, wx = Y.x - A.x, wy = Y.y - A.y;
      angle += std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
      if (fl_[p] & kConstrained) {
        closed = true;
        g = p;
        break;
      }
      g = tw_[p];
      if (g == kNone || g == e0) break;
    }
    if (!closed) continue;
    const float c = static_cast<float>(std::cos(std::min(angle, std::numbers::pi)));
    apex_cos_[v] = std::max(apex_cos_[v], c);
    if (angle < std::numbers::pi / 3) {
      const std::uint32_t s1 = input_segment(v, tv_[next_edge(e0)]);
      const std::uint32_t s2 = input_segment(v, tv_[g]);
      for (std::uint32_t sg : {s1, s2})
        if (sg != kNone) seg_small_[sg] |= segs_[sg][0] == v ? 1 : 2;
      // Mirrored splits only in the narrow wedges where cascades happen.
      if (s1 != kNone && s2 != kNone && s1 != s2 && angle < kWedgeAngle * std::numbers::pi / 180) {
        auto add = [&](std::uint32_t x, std::uint32_t y) {
          auto& slot = partners_[2 * x + (segs_[x][0] == v ? 0 : 1)];
          if (slot[0] == kNone) slot[0] = y;
          else if (slot[1] == kNone && slot[0] != y) slot[1] = y;
        };
        add(s1, s2);
        add(s2, s1);
        seg_spike_[s1] |= kSpikeSeg;
        seg_spike_[s2] |= kSpikeSeg;
      }
    }
  }
  mark_spikes();
  // Out-edges from scratch: any out-edge for an interior vertex, the
  // boundary one (most clockwise) for a boundary vertex, as compact() sets them.
  std::fill(ve_.begin(), ve_.end(), kNone);
  for (HalfEdgeId e = 0; e < ne; ++e)
    if (ve_[tv_[e]] == kNone || tw_[e] == kNone) ve_[tv_[e]] = e;
  seg_of_.assign(n_input_, kNone);
  if (!m_.vertex_markers().empty()) m_.vertex_markers().resize(n_input_, 0);
  reserve_for_area_bounds();
}

// The angle criterion and what depends on it.
void Refiner::set_bound(double theta) {
  st_.min_angle_deg = theta;
  const double rad = theta * std::numbers::pi / 180.0;
  sin2_bound_ = theta > 0 ? std::sin(rad) * std::sin(rad) : 0.0;
  // The off-centre sits where the shortest edge pq subtends the bound
  // angle, i.e. at distance |pq|/2 · cot(theta/2) from pq's midpoint; a
  // little nearer, so that the new triangle clears the bound after rounding.
  off_factor_ = theta > 0 ? 0.5 * kOffcentreShrink / std::tan(rad / 2) : 0.0;
  bound_rad_ = rad;
  if (lens_) {
    const double phi = std::max(90.0, 180.0 - 2.0 * theta) * std::numbers::pi / 180.0;
    lens_cos2_ = std::cos(phi) * std::cos(phi);
  }
}

// Spike sides: from the sides of the narrow wedges, along chains of
// segments through input vertices of two segments that bend less than
// kChannelBend (linear: every segment is marked once).
void Refiner::mark_spikes() {
  channel_sin2_ = std::sin(kChannelParallel * std::numbers::pi / 180);
  channel_sin2_ *= channel_sin2_;
  const double bend_cos = std::cos((180.0 - kChannelBend) * std::numbers::pi / 180);  // < 0
  std::vector<std::uint32_t> work;
  for (std::uint32_t s = 0; s < segs_.size(); ++s) {
    if (!(seg_spike_[s] & kBoundarySeg)) seg_spike_[s] = 0;  // channels between boundary sides only
    if (seg_spike_[s] & kSpikeSeg) work.push_back(s);
  }
  has_spikes_ = !work.empty();
  while (!work.empty()) {
    const std::uint32_t s = work.back();
    work.pop_back();
    for (const VertexId w : segs_[s]) {
      if (adj_start_[w + 1] - adj_start_[w] != 2) continue;
      const auto [x0, s0] = adj_[adj_start_[w]];
      const auto [x1, s1] = adj_[adj_start_[w] + 1];
      const std::uint32_t next = s0 == s ? s1 : s0;
      if (next == s || seg_spike_[next] != kBoundarySeg) continue;
      const Point& W = pts_[w];
      const double ux = pts_[x0].x - W.x, uy = pts_[x0].y - W.y, vx = pts_[x1].x - W.x, vy = pts_[x1].y - W.y;
      const double dot = ux * vx + uy * vy;
      // The angle at w is over 180° - kChannelBend: cos below bend_cos.
      if (!(dot < 0 && dot * dot > bend_cos * bend_cos * (ux * ux + uy * uy) * (vx * vx + vy * vy))) continue;
      seg_spike_[next] |= kSpikeSeg;
      work.push_back(next);
    }
  }
}

std::uint32_t Refiner::input_segment(VertexId a, VertexId b) const {
  if (a < n_input_) {
    for (std::uint32_t i = adj_start_[a]; i < adj_start_[a + 1]; ++i)
      if (adj_[i].first == b) return adj_[i].second;
  }
  return kNone;
}

// With area bounds the final size is predictable: reserve it, so the arrays
// do not double (and briefly triple) at the end.
void Refiner::reserve_for_area_bounds() {
  const bool global = opt_.max_area > 0;
  if (!global && !has_area_bounds_) return;
  double estimate = 0;
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    if (tv_[3 * t] >= pts_.size()) continue;
    const Point& a = pts_[tv_[3 * t]];
    const Point& b = pts_[tv_[3 * t + 1]];
    const Point& c = pts_[tv_[3 * t + 2]];
    const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    double bound = global ? opt_.max_area : -1;
    if (has_area_bounds_) {
      const double tb = m_.triangle_area_bound(t);
      if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
    }
    if (bound > 0) estimate += area / bound;
  }
  // Refinement to an area bound A ends with triangles of mean area ~0.6 A.
  const double tris = 1.75 * estimate + static_cast<double>(nt);
  if (tris > 1e10) return;
  auto want_t = static_cast<std::size_t>(tris);
  // Size bounds ask for about want_t / 2 vertices: the automatic budget
  // leaves room for four times that.
  if (opt_.max_steiner == kAutomaticBudget) budget_ = std::max(budget_, 2 * want_t);
  // Reserve no more than the Steiner budget can fill (a point adds at most
  // two triangles) and no more than kMaxReserve triangles: a tiny area bound
  // with a small budget asked for gigabytes up front (found by fuzz_mesh).
  constexpr std::size_t kMaxReserve = std::size_t{1} << 23;
  want_t = std::min({want_t, nt + 2 * std::min(budget_, kMaxReserve), kMaxReserve});
  if (want_t > nt) {
    m_.reserve(pts_.size() + want_t / 2 + 16, want_t + 16);
    fl_.reserve(3 * (want_t + 16));
    if (has_markers_) mk_.reserve(3 * (want_t + 16));
    seg_of_.reserve(pts_.size() + want_t / 2 + 16);
  }
}

// ===========================================================================
// Quality

double Refiner::area_bound(TriId t, const Point& a, const Point& b, const Point& c) const {
  double bound = opt_.max_area;
  if (has_area_bounds_) {
    const double tb = m_.triangle_area_bound(t);
    if (tb > 0 && (bound <= 0 || tb < bound)) bound = tb;
  }
  if (opt_.max_area_at) {
    const double cb = opt_.max_area_at((a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0);
    if (cb > 0 && (bound <= 0 || cb < bound)) bound = cb;
  }
  return bound;
}

Eval Refiner::eval(TriId t) const {
  const HalfEdgeId e = 3 * t;
  return eval(t, pts_[tv_[e]], pts_[tv_[e + 1]], pts_[tv_[e + 2]]);
}

// Quality of triangle abc (counter-clockwise) under t's size bound.
Eval Refiner::eval(TriId t, const Point& a, const Point& b, const Point& c) const {
  Eval ev;
  const double l0 = dist2(a, b), l1 = dist2(b, c), l2 = dist2(c, a);
  const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  double lo = l0, o1 = l1, o2 = l2;
  int s = 0;
  if (l1 < lo) lo = l1, o1 = l2, o2 = l0, s = 1;
  if (l2 < lo) lo = l2, o1 = l0, o2 = l1, s = 2;
  ev.shortest = s;
  ev.shortest2 = lo;
  // The smallest angle faces the shortest edge: sin = cross / (|o1| |o2|).
  const double den = o1 * o2;
  ev.skinny = cross * cross < sin2_bound_ * den;
  if (ev.skinny) ev.sin2 = den > 0 ? cross * cross / den : 0.0;
  const double bound = area_bound(t, a, b, c);
  if (bound > 0 && 0.5 * cross > bound) ev.large = true;
  if (opt_.max_edge_at) {
    const double eb = opt_.max_edge_at((a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0);
    if (eb > 0 && std::max({l0, l1, l2}) > eb * eb) ev.large = true;
  }
  return ev;
}

TriView Refiner::view(TriId t) const {
  TriView tv;
  tv.t = t;
  for (int i = 0; i < 3; ++i) {
    const HalfEdgeId f = 3 * t + i;
    tv.v[i] = tv_[f];
    tv.p[i] = pts_[tv_[f]];
    tv.seg[i] = tv_[f] >= n_input_ ? seg_of_[tv_[f]] : kNone;
    tv.constrained[i] = (fl_[f] & kConstrained) != 0;
  }
  return tv;
}

void Refiner::consider(TriId t) {
  if (t < why_.size()) why_[t] = Reason::None;
  const Eval ev = eval(t);
  if (!ev.skinny && !ev.large) return;
  const QueueEntry q{t, tv_[3 * t], tv_[3 * t + 1], tv_[3 * t + 2]};
  if (ev.skinny) {
    int key;
    if (shortest_first_) {
      // Three buckets per octave of the squared shortest edge (exponent
      // from frexp: no logarithm), shortest first.
      int ex;
      const double f = std::frexp(ev.shortest2, &ex);  // shortest2 = f 2^ex, f in [0.5, 1)
      key = 3 * (ex + 340) + (f < 0.63 ? 0 : (f < 0.794 ? 1 : 2));
    } else {
      key = static_cast<int>(ev.sin2 / sin2_bound_ * kBuckets);  // worst first
    }
    key = std::clamp(key, 0, kBuckets - 1);
    queue_.push_skinny(key, q);
  } else {
    queue_.push_large(q);
  }
}

// The segments an apex candidate list holds for vertex v: (apex, segment)
// pairs such that v lies on the segment and the apex is its other end.
void Refiner::apexes(VertexId v, std::uint32_t seg, std::array<std::pair<VertexId, std::uint32_t>, 2>& two,
                     int& n, std::vector<std::pair<VertexId, std::uint32_t>>& many) const {
  n = 0;
  many.clear();
  if (v >= n_input_) {
    const std::uint32_t s = seg;
    if (s == kNone || !seg_small_[s]) return;
    if (seg_small_[s] & 1) two[n++] = {segs_[s][0], s};
    if (seg_small_[s] & 2) two[n++] = {segs_[s][1], s};
    return;
  }
  for (std::uint32_t i = adj_start_[v]; i < adj_start_[v + 1]; ++i) {
    const auto [w, s] = adj_[i];
    // v is an endpoint of s; the apex is the other endpoint w.
    const std::uint8_t bit = segs_[s][0] == w ? 1 : 2;
    if (seg_small_[s] & bit) many.push_back({w, s});
  }
}

// Miller-Pav-Walkington: the shortest edge joins two different segments
// that meet at an apex at an angle below 60°.
// holding: also a triangle that holds an input angle under the bound.
bool Refiner::faces_small_angle(const TriView& tv, const Eval& ev, bool holding) const {
  if (wedge_rule(tv, ev, holding)) return true;
  return has_spikes_ && in_channel(tv);
}

bool Refiner::wedge_rule(const TriView& tv, const Eval& ev, bool holding) const {
  // The triangle holds an input angle below the bound between two segments:
  // no split can remove that angle.
  for (int i = 0; i < 3 && holding; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (tv.v[i] >= n_input_ || !tv.constrained[i] || !tv.constrained[k]) continue;
    const Point& A = tv.p[i];
    const Point& B = tv.p[j];
    const Point& C = tv.p[k];
    const double ux = B.x - A.x, uy = B.y - A.y, wx = C.x - A.x, wy = C.y - A.y;
    const double cross = ux * wy - uy * wx, l = (ux * ux + uy * uy) * (wx * wx + wy * wy);
    if (ux * wx + uy * wy > 0 && cross * cross < sin2_bound_ * l) return true;
  }
  const int ip = ev.shortest, iq = (ev.shortest + 1) % 3, ir = (ev.shortest + 2) % 3;
  const VertexId p = tv.v[ip], q = tv.v[iq];
  std::array<std::pair<VertexId, std::uint32_t>, 2> tp, tq;
  int np = 0, nq = 0;
  thread_local std::vector<std::pair<VertexId, std::uint32_t>> mp, mq;
  apexes(p, tv.seg[ip], tp, np, mp);
  if (np == 0 && mp.empty()) return false;
  apexes(q, tv.seg[iq], tq, nq, mq);
  if (nq == 0 && mq.empty()) return false;
  for (int i = 0; i < np; ++i) mp.push_back(tp[i]);
  for (int i = 0; i < nq; ++i) mq.push_back(tq[i]);
  for (const auto& [ap, sp] : mp)
    for (const auto& [aq, sq] : mq) {
      if (ap != aq || sp == sq) continue;
      const Point& A = pts_[ap];
      const VertexId op = segs_[sp][0] == ap ? segs_[sp][1] : segs_[sp][0];
      const VertexId oq = segs_[sq][0] == aq ? segs_[sq][1] : segs_[sq][0];
      const double ux = pts_[op].x - A.x, uy = pts_[op].y - A.y;
      const double wx = pts_[oq].x - A.x, wy = pts_[oq].y - A.y;
      const double dot = ux * wx + uy * wy;
      if (!(dot > 0 && dot * dot > small_cos2_ * (ux * ux + uy * uy) * (wx * wx + wy * wy))) continue;
      // ... and the triangle lies in the wedge between them: its third
      // vertex is inside the (convex, < 60°) cone at the apex. A triangle
      // beyond the wedge's mouth is skinny for other reasons and is split.
      const VertexId r = tv.v[ir];
      // On one of the two segments (split points are off their line by rounding).
      if (r == op || r == oq || (r >= n_input_ && (tv.seg[ir] == sp || tv.seg[ir] == sq))) return true;
      const Point& R = tv.p[ir];
      const double rx = R.x - A.x, ry = R.y - A.y;
      const double side = ux * wy - uy * wx;  // orientation of the cone u -> w
      const double s1 = ux * ry - uy * rx, s2 = rx * wy - ry * wx;
      if (side > 0 ? (s1 >= 0 && s2 >= 0) : (s1 <= 0 && s2 <= 0)) return true;
    }
  return false;
}

// The spike sides vertex v lies on (a Steiner vertex: its segment).
template <class F>
void Refiner::spike_segments(VertexId v, std::uint32_t seg, F&& f) const {
  if (v >= n_input_) {
    const std::uint32_t s = seg;
    if (s != kNone && (seg_spike_[s] & kSpikeSeg)) f(s);
    return;
  }
  for (std::uint32_t i = adj_start_[v]; i < adj_start_[v + 1]; ++i)
    if (seg_spike_[adj_[i].second] & kSpikeSeg) f(adj_[i].second);
}

// Two spike sides that can bound a channel: boundary segments facing each
// other, antiparallel within kChannelParallel (two pieces of one chain run
// parallel; the sides of a notch face away, which near_channel rejects).
// gap2: the squared width allowed, 1/kChannelGap of the shorter one.
bool Refiner::channel_pair(std::uint32_t sa, std::uint32_t sb, double& gap2) const {
  if (sa == sb) return false;
  const auto [a0, a1] = segs_[sa];
  const auto [b0, b1] = segs_[sb];
  const double ux = pts_[a1].x - pts_[a0].x, uy = pts_[a1].y - pts_[a0].y;
  const double wx = pts_[b1].x - pts_[b0].x, wy = pts_[b1].y - pts_[b0].y;
  const double la2 = ux * ux + uy * uy, lb2 = wx * wx + wy * wy;
  const double cross = ux * wy - uy * wx;
  if (!(ux * wx + uy * wy < 0 && cross * cross < channel_sin2_ * la2 * lb2)) return false;
  gap2 = std::min(la2, lb2) / (kChannelGap * kChannelGap);
  return true;
}

// p lies in the strip between the two sides: on the domain side of both
// lines (up to rounding) and closer than the allowed width to each.
bool Refiner::near_channel(const Point& p, std::uint32_t sa, std::uint32_t sb, double gap2) const {
  for (const std::uint32_t s : {sa, sb}) {
    const Point& A = pts_[segs_[s][0]];
    const Point& B = pts_[segs_[s][1]];
    const double ux = B.x - A.x, uy = B.y - A.y;
    const double l2 = ux * ux + uy * uy;
    const double cross = ux * (p.y - A.y) - uy * (p.x - A.x);  // |u| times the signed distance
    const double gap_l = std::sqrt(gap2 * l2);
    if (cross < -1e-3 * gap_l || cross > gap_l) return false;
  }
  return true;
}

// A triangle in a thin channel between two spike sides (every vertex in
// the channel, some vertex on each side): it cannot be made good without
// refining the whole spike down to the channel's width, so it is left as
// an input angle's triangle is.
bool Refiner::in_channel(const TriView& tv) const {
  std::array<std::uint32_t, 4> segs[3];
  int n[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    spike_segments(tv.v[i], tv.seg[i], [&](std::uint32_t s) {
      if (n[i] < 4) segs[i][n[i]++] = s;
    });
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      for (int x = 0; x < n[i]; ++x)
        for (int y = 0; y < n[j]; ++y) {
          double gap2;
          const std::uint32_t sa = segs[i][x], sb = segs[j][y];
          if (!channel_pair(sa, sb, gap2)) continue;
          if (near_channel(tv.p[0], sa, sb, gap2) && near_channel(tv.p[1], sa, sb, gap2) &&
              near_channel(tv.p[2], sa, sb, gap2))
            return true;
        }
  return false;
}

// A bad triangle the small-angle rules leave as it is.
bool Refiner::left_alone(const TriView& tv, bool holding) const {
  const Eval ev = eval(tv.t, tv.p[0], tv.p[1], tv.p[2]);
  return ev.skinny && !ev.large && faces_small_angle(tv, ev, holding);
}

// ===========================================================================
// Steiner points

Point Refiner::steiner_point(TriId t, const Eval& ev, bool& offcenter) const {
  offcenter = false;
  const HalfEdgeId e = 3 * t + ev.shortest;
  const Point P = pts_[tv_[e]];
  const Point Q = pts_[tv_[next_edge(e)]];
  const Point R = pts_[tv_[prev_edge(e)]];
  const double dx = Q.x - P.x, dy = Q.y - P.y, ex = R.x - P.x, ey = R.y - P.y;
  const double l2 = dx * dx + dy * dy, e2 = ex * ex + ey * ey;
  const double det = orient2d(P, Q, R);  // adaptive: accurate for skinny triangles
  const double den = 0.5 / det;
  const double ux = (ey * l2 - dy * e2) * den, uy = (dx * e2 - ex * l2) * den;
  if (opt_.steiner == SteinerRule::Circumcenter || !ev.skinny) return {P.x + ux, P.y + uy};
  // Off-centre: along the bisector of PQ from its midpoint towards the circumcentre.
  const double mx = ux - 0.5 * dx, my = uy - 0.5 * dy;
  const double dc2 = mx * mx + my * my;
  const double h = off_factor_ * std::sqrt(l2);
  if (dc2 <= h * h) return {P.x + ux, P.y + uy};
  offcenter = true;
  const double s = h / std::sqrt(dc2);
  return {P.x + 0.5 * dx + mx * s, P.y + 0.5 * dy + my * s};
}


// Scores candidate c for bad triangle t: its cavity must hold t (c inside
// t's circumcircle), be star-shaped from c, touch no segment c encroaches, and
// keep c at least sqrt(min2) away from every vertex (no edge shorter than
// t's). `bad` counts the new triangles that would still be skinny (size is
// left to the size bound's own splits); radius2 is the squared distance to
// the nearest vertex. The cavity is
// grown from t itself and checked in floating point: the chosen point is
// located and its cavity built exactly afterwards by decide().
bool Refiner::score(TriId t, const Point& c, double min2, int& bad, double& radius2) {
  const HalfEdgeId b0 = 3 * t;
  if (!(incircle(pts_[tv_[b0]], pts_[tv_[b0 + 1]], pts_[tv_[b0 + 2]], c) > 0)) return false;
  begin_cavity();
  add_to_cavity(t);
  stack_.push_back(b0 + 2);
  stack_.push_back(b0 + 1);
  stack_.push_back(b0);
  if (!grow(c, 0)) return false;
  bad = 0;
  radius2 = INFINITY;
  for (const BoundaryEdge& b : bnd_) {
    const Point& A = pts_[b.a];
    const Point& B = pts_[b.b];
    const double cross = (B.x - A.x) * (c.y - A.y) - (B.y - A.y) * (c.x - A.x);
    if (!(cross > 0)) return false;
    if ((b.flags & kConstrained) && encroaches(A, B, c)) return false;
    const double la = dist2(A, c), lb = dist2(B, c), lab = dist2(A, B);
    radius2 = std::min({radius2, la, lb});
    if (radius2 < min2) return false;
    // sin of the smallest angle = cross / (product of the two longer edges).
    const double lo = std::min({la, lb, lab});
    const double den = la * lb * lab / lo;
    if (cross * cross < sin2_bound_ * den) ++bad;
  }
  return true;
}

// SteinerRule::Best: a search over the petal of t's shortest edge PQ (the
// points from which PQ makes a triangle within the angle bound: above the
// lines at the bound's angle from P and Q, inside the circle through P and Q
// on which PQ subtends the bound). A coarse grid, then a pattern search at
// three step sizes around the best point so far, pick the point whose
// insertion leaves the fewest skinny triangles, then the one farthest from
// every vertex. On the corpus this gives 14% (q30) to 19% (q33) fewer
// triangles than the off-centre alone (docs/benchmarks.md); the off-centre is
// kept when it leaves none. Finer coarse grids and wider shifts were measured:
// the width (shifts up to ±|PQ|) and the local search matter most.
Point Refiner::best_point(TriId t, const Eval& ev, const Point& primary) {
  const HalfEdgeId e = 3 * t + ev.shortest;
  const Point P = pts_[tv_[e]];
  const Point Q = pts_[tv_[next_edge(e)]];
  const double l = std::sqrt(ev.shortest2);
  const double ux = (Q.x - P.x) / l, uy = (Q.y - P.y) / l;
  const double nx = -uy, ny = ux;  // towards the triangle's third vertex (counter-clockwise)
  const Point M{0.5 * (P.x + Q.x), 0.5 * (P.y + Q.y)};
  // Heights and shifts below are in units of l; the primary is the highest.
  const double ymax = ((primary.x - M.x) * nx + (primary.y - M.y) * ny) / l;
  const double min2 = ev.shortest2 * 0.999;  // no new edge shorter than PQ
  int best_bad = 0;
  double best_r2 = 0;
  Point best = primary;
  double best_y = ymax, best_s = 0;
  if (!score(t, primary, min2, best_bad, best_r2)) best_bad = std::numeric_limits<int>::max(), best_r2 = 0;
  if (best_bad == 0) return primary;
  // Next to triangles that are too large the bad ones are split anyway by
  // the size bound's refinement: the search would cost time for nothing.
  if (sized_ && best_bad != std::numeric_limits<int>::max())
    for (const BoundaryEdge& b : bnd_)
      if (b.outer != kNone && eval(tri_of(b.outer)).large) return primary;
  const double tan_a = std::tan(bound_rad_);
  const auto consider = [&](double y, double s) {
    if (y >= ymax || y <= 0) return;
    // Angles at P and Q, then at the new vertex (sine rule), at least the bound.
    if (y < tan_a * (0.5 + s) || y < tan_a * (0.5 - s)) return;
    const double a2 = (0.5 + s) * (0.5 + s) + y * y, b2 = (0.5 - s) * (0.5 - s) + y * y;
    if (y * y * std::min({1.0, a2, b2}) < sin2_bound_ * a2 * b2) return;
    const Point c{M.x + l * (s * ux + y * nx), M.y + l * (s * uy + y * ny)};
    int bad;
    double r2;
    if (!score(t, c, min2, bad, r2)) return;
    if (bad < best_bad || (bad == best_bad && r2 > best_r2)) {
      best_bad = bad, best_r2 = r2, best = c;
      best_y = y, best_s = s;
    }
  };
  static constexpr double kHeights[] = {0.87, 1.0, 1.15, 1.3, 1.5, 1.75, 2.0};
  static constexpr double kShifts[] = {0.0, -0.25, 0.25, -0.5, 0.5, -0.75, 0.75, -1.0, 1.0};
  for (const double y : kHeights)
    for (const double s : kShifts) consider(y, s);
  // Pattern search: step to the best neighbour while that improves, then halve.
  for (double dy = 0.075, ds = 0.125; dy > 0.015 && best_bad > 0; dy *= 0.5, ds *= 0.5) {
    for (int move = 0; move < 3 && best_bad > 0; ++move) {
      const double y0 = best_y, s0 = best_s;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          if (i != 0 || j != 0) consider(y0 + i * dy, s0 + j * ds);
      if (best_y == y0 && best_s == s0) break;
    }
  }
  return best;
}

// Where subsegment ab is split: on a concentric shell (a power-of-two
// distance) around its input-vertex end when exactly one end is an input
// vertex, so that the splits of segments meeting at an apex stay at equal
// distances from it and never encroach each other; otherwise the midpoint.
Point Refiner::split_point(VertexId a, VertexId b) const {
  const Point& A = pts_[a];
  const Point& B = pts_[b];
  const bool ain = a < n_input_, bin = b < n_input_;
  if (opt_.small_angle_protection && ain != bin && apex_cos_[ain ? a : b] > shell_cos_) {
    const Point& apex = ain ? A : B;
    const Point& other = ain ? B : A;
    const double len = std::sqrt(dist2(apex, other));
    const double half = 0.5 * len;
    int ex;
    std::frexp(half, &ex);  // half = f * 2^ex, f in [0.5, 1)
    double shell = std::ldexp(1.0, ex - 1);  // <= half < 2 * shell
    if (half > shell * std::numbers::sqrt2) shell *= 2;
    const double f = shell / len;
    return {apex.x + (other.x - apex.x) * f, apex.y + (other.y - apex.y) * f};
  }
  // Subsegments further out, on a segment in a narrow wedge (one with
  // mirrored partners) at an apex of three or more segments (a hub): on the
  // grid of radii around that apex. At a spike's tip (two segments) the
  // channel rule copes and midpoints grade better.
  if (opt_.small_angle_protection && !(ain && bin)) {
    const std::uint32_t s = seg_of_[ain ? b : a];
    if (s != kNone) {
      VertexId apex = kNone;
      double nearest = INFINITY;
      for (int end = 0; end < 2; ++end) {
        const VertexId w = segs_[s][end];
        if (w == a || w == b || partners_[2 * s + end][0] == kNone ||
            adj_start_[w + 1] - adj_start_[w] < 3)
          continue;
        const double d = std::min(dist2(pts_[w], A), dist2(pts_[w], B));
        if (d < nearest) nearest = d, apex = w;
      }
      if (apex != kNone) {
        const Point& P = pts_[apex];
        const Point& O = pts_[segs_[s][0] == apex ? segs_[s][1] : segs_[s][0]];
        const double ra = std::sqrt(dist2(P, A)), rb = std::sqrt(dist2(P, B));
        const double f = grid_radius(std::min(ra, rb), std::max(ra, rb)) / std::sqrt(dist2(P, O));
        return {P.x + (O.x - P.x) * f, P.y + (O.y - P.y) * f};
      }
    }
  }
  return {0.5 * (A.x + B.x), 0.5 * (A.y + B.y)};
}

// ===========================================================================
// Location

// Straight walk along the ray from t's centroid to c. Stops in the triangle
// holding c, or at the first segment (or boundary edge) the ray crosses.
// A vertex exactly on the ray is treated as lying to its left (a symbolic
// perturbation), so each step is decided by one exact orientation.
Refiner::Walk Refiner::walk(TriId t, const Point& c) const {
  Walk w;
  const HalfEdgeId b0 = 3 * t;
  const Point& A = pts_[tv_[b0]];
  const Point& B = pts_[tv_[b0 + 1]];
  const Point& C = pts_[tv_[b0 + 2]];
  {
    const double o0 = orient2d(A, B, c), o1 = orient2d(B, C, c), o2 = orient2d(C, A, c);
    if (o0 >= 0 && o1 >= 0 && o2 >= 0) {
      w.tri = t;
      if (c == A || c == B || c == C) {
        w.kind = Walk::OnVertex;
        return w;
      }
      w.kind = Walk::Found;
      if (o0 == 0) w.edge = b0;
      else if (o1 == 0) w.edge = b0 + 1;
      else if (o2 == 0) w.edge = b0 + 2;
      return w;
    }
  }
  const Point o{(A.x + B.x + C.x) / 3.0, (A.y + B.y + C.y) / 3.0};
  if (!(orient2d(A, B, o) > 0 && orient2d(B, C, o) > 0 && orient2d(C, A, o) > 0)) {
    w.kind = Walk::Failed;
    return w;
  }
  const bool left[3] = {orient2d(o, c, A) >= 0, orient2d(o, c, B) >= 0, orient2d(o, c, C) >= 0};
  HalfEdgeId exit = kNone;
  for (int i = 0; i < 3; ++i)
    if (!left[i] && left[(i + 1) % 3]) exit = b0 + i;
  if (exit == kNone) {
    w.kind = Walk::Failed;
    return w;
  }
  const std::size_t limit = tv_.size();
  for (std::size_t steps = 0; steps < limit; ++steps) {
    const HalfEdgeId f = tw_[exit];
    if (f == kNone || (fl_[exit] & kConstrained)) {
      w.kind = Walk::Blocked;
      w.tri = tri_of(exit);
      w.edge = exit;
      return w;
    }
    // Entered triangle u through f = (x -> y), x left of the ray, y right.
    const VertexId apex = tv_[prev_edge(f)];
    const Point& W = pts_[apex];
    const HalfEdgeId cand = orient2d(o, c, W) >= 0 ? next_edge(f) : prev_edge(f);
    const Point& P = pts_[tv_[cand]];
    const Point& Q = pts_[tv_[next_edge(cand)]];
    const double oc = orient2d(P, Q, c);
    if (oc >= 0) {
      w.tri = tri_of(f);
      if (c == P || c == Q || c == W) {
        w.kind = Walk::OnVertex;
        return w;
      }
      w.kind = Walk::Found;
      if (oc == 0) w.edge = cand;
      return w;
    }
    exit = cand;
  }
  w.kind = Walk::Failed;
  return w;
}

void Refiner::record_boundary(HalfEdgeId e) {
  BoundaryEdge b;
  b.a = tv_[e];
  b.b = tv_[next_edge(e)];
  b.inner = e;
  b.outer = tw_[e];
  b.flags = fl_[e];
  b.marker = has_markers_ ? mk_[e] : 0;
  b.area_bound = carry_bounds_ ? m_.triangle_area_bound(tri_of(e)) : -1.0;
  bnd_.push_back(b);
}

// Depth-first growth of the cavity from the half-edges on stack_ above
// stack_base; boundary edges are recorded in counter-clockwise order.
bool Refiner::grow(const Point& c, std::size_t stack_base) {
  while (stack_.size() > stack_base) {
    const HalfEdgeId e = stack_.back();
    stack_.pop_back();
    const HalfEdgeId f = tw_[e];
    if (f != kNone && !(fl_[e] & kConstrained)) {
      const TriId u = tri_of(f);
      const Point& pa = pts_[tv_[f]];
      const Point& pb = pts_[tv_[next_edge(f)]];
      const Point& pc = pts_[tv_[prev_edge(f)]];
      if (incircle(pa, pb, pc, c) > 0) {
        // The cavity's dual graph is a tree; meeting a triangle twice means
        // the predicates and the mesh disagree: give up on this point.
        if (in_cavity(u)) return false;
        add_to_cavity(u);
        stack_.push_back(prev_edge(f));
        stack_.push_back(next_edge(f));
        continue;
      }
    }
    record_boundary(e);
  }
  return true;
}

bool Refiner::boundary_visible(const Point& c, std::size_t from, std::size_t to) const {
  for (std::size_t i = from; i < to; ++i)
    if (!(orient2d(pts_[bnd_[i].a], pts_[bnd_[i].b], c) > 0)) return false;
  return true;
}

bool Refiner::in_circumcircle(TriId t, const Point& p) const {
  return incircle(pts_[tv_[3 * t]], pts_[tv_[3 * t + 1]], pts_[tv_[3 * t + 2]], p) > 0;
}

// A boundary segment's rounded split point may fall outside the domain,
// and where pieces of the domain touch (a vertex shared by separate fans, a
// nearly collinear boundary edge of another piece) inside a neighbouring
// piece: the new triangles would overlap it. Keeps m on the segment or
// inside, strictly between a and b (exact tests): m itself or the nearest
// double at most two ulps away per coordinate; false when none is.
bool Refiner::keep_split_inside(HalfEdgeId e, Point& m) const {
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  const Point& apex = pts_[tv_[prev_edge(e)]];
  auto inside = [&](const Point& c) {
    return orient2d(a, b, c) >= 0 && orient2d(b, apex, c) > 0 && orient2d(apex, a, c) > 0 && diametral_dot(a, b, c) < 0;
  };
  if (inside(m)) return true;
  auto step = [](double v, int k) {
    for (; k > 0; --k) v = std::nextafter(v, INFINITY);
    for (; k < 0; ++k) v = std::nextafter(v, -INFINITY);
    return v;
  };
  for (int r = 1; r <= 2; ++r)
    for (int d = 1; d <= 2 * r; ++d)  // nearest first: axis steps, then diagonals
      for (int dx = -r; dx <= r; ++dx)
        for (int dy = -r; dy <= r; ++dy) {
          if (std::max(std::abs(dx), std::abs(dy)) != r || std::abs(dx) + std::abs(dy) != d) continue;
          const Point c{step(m.x, dx), step(m.y, dy)};
          if (inside(c)) {
            m = c;
            return true;
          }
        }
  return false;
}

// Cavity of point c (inside seed or on one of its unconstrained edges).
bool Refiner::cavity(const Point& c, TriId seed) {
  begin_cavity();
  add_to_cavity(seed);
  stack_.push_back(3 * seed + 2);
  stack_.push_back(3 * seed + 1);
  stack_.push_back(3 * seed);
  if (!grow(c, 0)) return false;
  // A cavity grown through unconstrained (locally Delaunay) edges around a
  // point inside it is star-shaped (exact incircle); only segments on its
  // boundary can break that, so only then is every edge checked.
  for (const BoundaryEdge& b : bnd_)
    if (b.flags & kConstrained) return boundary_visible(c, 0, bnd_.size());
  return true;
}

// Cavity of point m splitting the constrained edge e = (a -> b): side one
// (e's triangle) then side two (its twin's), each boundary running b ... a
// and a ... b respectively. Both triangles of e join only when m lies
// strictly inside their circumcircles (exact incircle), like every other
// triangle: m is rounded and may lie off the segment's line, and a
// far-side triangle whose circle misses it would keep an edge that is not
// locally Delaunay against m. Then the split fails.
bool Refiner::split_cavity(HalfEdgeId e, const Point& m) {
  begin_cavity();
  if (!in_circumcircle(tri_of(e), m)) return false;
  add_to_cavity(tri_of(e));
  stack_.push_back(prev_edge(e));
  stack_.push_back(next_edge(e));
  if (!grow(m, 0)) return false;
  side_split_ = bnd_.size();
  const HalfEdgeId f = tw_[e];
  if (f != kNone) {
    if (!in_circumcircle(tri_of(f), m)) return false;
    add_to_cavity(tri_of(f));
    stack_.push_back(prev_edge(f));
    stack_.push_back(next_edge(f));
    if (!grow(m, 0)) return false;
  }
  return boundary_visible(m, 0, bnd_.size());
}

// ===========================================================================
// Encroachment

bool Refiner::encroaches(const Point& a, const Point& b, const Point& p) const {
  if (!lens_) return diametral_dot(a, b, p) < 0;
  const double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y;
  const double dot = ax * bx + ay * by;
  if (!(dot < 0)) return false;
  return dot * dot > lens_cos2_ * (ax * ax + ay * ay) * (bx * bx + by * by);
}

bool Refiner::encroached(HalfEdgeId e) const {
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  if (encroaches(a, b, pts_[tv_[prev_edge(e)]])) return true;
  const HalfEdgeId f = tw_[e];
  return f != kNone && encroaches(a, b, pts_[tv_[prev_edge(f)]]);
}

bool Refiner::splittable(HalfEdgeId e) const {
  switch (opt_.segment_splitting) {
    case SegmentSplitting::All: break;
    case SegmentSplitting::InteriorOnly:
      if (tw_[e] == kNone) return false;
      break;
    case SegmentSplitting::None: return false;
  }
  const Point& a = pts_[tv_[e]];
  const Point& b = pts_[tv_[next_edge(e)]];
  const Point m = split_point(tv_[e], tv_[next_edge(e)]);
  return !(m == a || m == b) && dist2(a, b) >= precision2_;
}

// Shewchuk's rule against cascades at small angles: a segment next to a
// small-angle apex is not split on behalf of a skinny triangle when the split
// would make a subsegment shorter than the triangle's shortest edge.
bool Refiner::refuse_split(HalfEdgeId e, const Eval& ev) const {
  if (!opt_.small_angle_protection) return false;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  std::uint32_t s = a >= n_input_ ? seg_of_[a] : (b >= n_input_ ? seg_of_[b] : input_segment(a, b));
  if (s == kNone || !seg_small_[s]) return false;
  const Point m = split_point(a, b);
  const double part = std::min(dist2(m, pts_[a]), dist2(m, pts_[b]));
  return part < ev.shortest2;
}

// Rule R1 yields when splitting the subsegment would only make triangles
// the small-angle rules leave alone anyway: on each side where a vertex
// encroaches, both halves of its triangle, by the mid-wedge rule (wedges
// under kWedgeAngle) or the channel rule. Splitting would start the cascade
// those rules avoid (in a thin channel, every subsegment of a side is
// encroached from across; a narrow wedge's side by the other side's end).
// Not with conforming Delaunay, which needs every split.
bool Refiner::excused(HalfEdgeId e) const {
  if (!opt_.small_angle_protection || opt_.conforming_delaunay) return false;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  const Point& A = pts_[a];
  const Point& B = pts_[b];
  const std::uint32_t seg = a >= n_input_ ? seg_of_[a] : (b >= n_input_ ? seg_of_[b] : input_segment(a, b));
  const Point m = split_point(a, b);
  const auto mv = static_cast<VertexId>(pts_.size());  // the vertex the split would add
  bool any = false;
  for (const HalfEdgeId f : {e, tw_[e]}) {
    if (f == kNone || !encroaches(A, B, pts_[tv_[prev_edge(f)]])) continue;
    const VertexId w = tv_[prev_edge(f)];
    // Not where that vertex is itself an apex of angles under 60°: the
    // shells around it refine there anyway, and the unsplit subsegment
    // then drives a cascade into the apex (seen on ne110m_land at -q33).
    if (w < n_input_ && apex_cos_[w] > shell_cos_) return false;
    // f = x -> y with apex w becomes x -> m -> w and m -> y -> w.
    const TriView whole = view(tri_of(f));
    const int i = static_cast<int>(f % 3), j = (i + 1) % 3, k = (i + 2) % 3;
    TriView h1 = whole, h2 = whole;
    h1.v[j] = mv, h1.p[j] = m, h1.seg[j] = seg;
    h1.constrained[j] = false;  // m -> w
    h2.v[i] = mv, h2.p[i] = m, h2.seg[i] = seg;
    h2.constrained[k] = false;  // w -> m
    if (!left_alone(h1, false) || !left_alone(h2, false)) return false;
    any = true;
  }
  return any;
}

void Refiner::check_encroached(HalfEdgeId e, VertexId apex) {
  if (!(fl_[e] & kConstrained)) return;
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  if (!encroaches(pts_[a], pts_[b], pts_[apex])) return;
  if (!splittable(e)) return;
  encroached_.push_back({a, b, e});
}

// ===========================================================================
// Decisions

// What to do with bad triangle t: skip it (and why), split segments, or
// insert its Steiner point (cavity left in cav_/bnd_).
void Refiner::decide(TriId t, Decision& d) {
  d.kind = Decision::Skip;
  d.reason = Reason::None;
  d.transient = false;
  d.segments.clear();
  const Eval ev = eval(t);
  if (!ev.skinny && !ev.large) return;
  if (ev.skinny && !ev.large && opt_.small_angle_protection && faces_small_angle(t, ev)) {
    d.reason = Reason::SmallAngle;
    return;
  }
  if (ev.shortest2 < precision2_) {
    d.reason = Reason::Precision;
    return;
  }
  d.c = steiner_point(t, ev, d.offcenter);
  if (!std::isfinite(d.c.x) || !std::isfinite(d.c.y)) {
    d.reason = Reason::Precision;
    return;
  }
  if (ev.skinny && !ev.large && best_) d.c = best_point(t, ev, d.c);
  const Walk w = walk(t, d.c);
  enc_scratch_.clear();
  switch (w.kind) {
    case Walk::Failed:
    case Walk::OnVertex:
      d.reason = Reason::Precision;
      return;
    case Walk::Blocked:
      enc_scratch_.push_back(w.edge);
      decide_segments(enc_scratch_, ev, d);
      return;
    case Walk::Found:
      break;
  }
  if (w.edge != kNone && (fl_[w.edge] & kConstrained)) {  // on a segment
    enc_scratch_.push_back(w.edge);
    decide_segments(enc_scratch_, ev, d);
    return;
  }
  if (!cavity(d.c, w.tri)) {
    d.reason = Reason::Precision;
    return;
  }
  bool protected_only = false;
  for (const BoundaryEdge& b : bnd_) {
    if (!(b.flags & kConstrained) || !encroaches(pts_[b.a], pts_[b.b], d.c)) continue;
    const HalfEdgeId e = b.inner;  // the cavity is still intact
    if (!splittable(e)) {
      protected_only = true;
      continue;
    }
    enc_scratch_.push_back(e);
  }
  (void)protected_only;  // a point encroaching only unsplittable segments is inserted anyway
  if (!enc_scratch_.empty()) {
    decide_segments(enc_scratch_, ev, d);
    return;
  }
  d.kind = Decision::Insert;
}

void Refiner::decide_segments(const std::vector<HalfEdgeId>& enc, const Eval& ev, Decision& d) {
  Reason why = Reason::None;
  for (HalfEdgeId e : enc) {
    if (!splittable(e)) {
      why = Reason::Protected;
      continue;
    }
    // The rule against cascades is for skinny triangles (as the small-angle
    // skip in decide()): a triangle above its size bound gets its split, and
    // size bounds end those splits.
    if (!ev.large && refuse_split(e, ev)) {
      if (why == Reason::None) why = Reason::SmallAngle;
      continue;
    }
    d.segments.push_back({tv_[e], tv_[next_edge(e)], e});
  }
  if (d.segments.empty()) {
    d.kind = Decision::Skip;
    d.reason = why == Reason::None ? Reason::Precision : why;
    d.transient = true;
  } else {
    d.kind = Decision::Split;
  }
}

// ===========================================================================
// Mesh updates

VertexId Refiner::new_vertex(const Point& p, std::uint32_t seg, int marker) {
  const auto v = static_cast<VertexId>(pts_.size());
  pts_.push_back(p);
  ve_.push_back(kNone);
  seg_of_.push_back(seg);
  if (!m_.vertex_markers().empty()) m_.vertex_markers().push_back(marker);
  const std::size_t na = m_.num_vertex_attributes();
  if (na > 0) m_.vertex_attributes().resize(m_.vertex_attributes().size() + na, 0.0);
  ++st_.steiner_points;
  return v;
}

// Slot for fan triangle i of `fan` triangles: the cavity's slots first, then new ones.
TriId Refiner::take_slot(std::size_t i, std::size_t /*fan*/, VertexId v) {
  if (i < cav_.size()) return cav_[i];
  if (!carry_bounds_ && m_.num_triangle_attributes() == 0) {
    // The arrays this refinement touches, grown by hand (Mesh::add_triangle
    // also handles bounds and attributes, at a cost per call).
    const auto t = static_cast<TriId>(tv_.size() / 3);
    tv_.resize(tv_.size() + 3, v);
    tw_.resize(tw_.size() + 3, kNone);
    fl_.resize(fl_.size() + 3, 0);
    if (has_markers_) mk_.resize(mk_.size() + 3, 0);
    ++appended_;
    return t;
  }
  return m_.add_triangle(v, v, v);  // resizes every per-triangle array
}

// Triangle attributes of the fan fan_[0..n): each new triangle takes those
// of the cavity triangle on its boundary edge, as area bounds do. A segment
// split's cavity spans both sides of the segment, so slots (and the
// attributes they held) pass from one region to the other; regional
// attributes (-A) must not leak across it.
void Refiner::carry_attributes() {
  const std::size_t na = m_.num_triangle_attributes();
  if (na == 0) return;
  std::vector<double>& at = m_.triangle_attributes();
  const std::size_t n = bnd_.size();
  attr_scratch_.resize(n * na);
  for (std::size_t i = 0; i < n; ++i)  // read every source before writing any slot
    for (std::size_t k = 0; k < na; ++k) attr_scratch_[i * na + k] = at[tri_of(bnd_[i].inner) * na + k];
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < na; ++k) at[fan_[i] * na + k] = attr_scratch_[i * na + k];
}

// Interpolated attributes for a new vertex: barycentric in the seed triangle.
static void interpolate_attributes(Mesh& m, VertexId v, const VertexId (&tri)[3], const Point& p) {
  const std::size_t na = m.num_vertex_attributes();
  if (na == 0) return;
  const Point& a = m.point(tri[0]);
  const Point& b = m.point(tri[1]);
  const Point& c = m.point(tri[2]);
  const double det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  double wb = det != 0 ? ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / det : 0.0;
  double wc = det != 0 ? ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / det : 0.0;
  double wa = 1.0 - wb - wc;
  std::vector<double>& at = m.vertex_attributes();
  for (std::size_t k = 0; k < na; ++k)
    at[v * na + k] = wa * at[tri[0] * na + k] + wb * at[tri[1] * na + k] + wc * at[tri[2] * na + k];
}

// Inserts c, whose cavity is in cav_/bnd_, as a fan of triangles.
void Refiner::insert_interior(const Point& c, TriId seed) {
  const VertexId seed_v[3] = {tv_[3 * seed], tv_[3 * seed + 1], tv_[3 * seed + 2]};
  const VertexId v = new_vertex(c, kNone, 0);
  interpolate_attributes(m_, v, seed_v, c);
  ++st_.interior_points;
  const std::size_t n = bnd_.size();
  fan_.resize(n);
  for (std::size_t i = cav_.size(); i < n; ++i) fan_[i] = take_slot(i, n, v);
  for (std::size_t i = 0; i < cav_.size(); ++i) fan_[i] = cav_[i];
  // Vertices whose out-edge lies in the cavity get the fan's outer edge.
  for (std::size_t i = 0; i < n; ++i) {
    const HalfEdgeId oe = ve_[bnd_[i].a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[bnd_[i].a] = 3 * fan_[i] + 1;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const TriId t = fan_[i];
    const HalfEdgeId e = 3 * t;
    const BoundaryEdge& b = bnd_[i];
    tv_[e] = v;
    tv_[e + 1] = b.a;
    tv_[e + 2] = b.b;
    tw_[e + 1] = b.outer;
    if (b.outer != kNone) tw_[b.outer] = e + 1;
    const HalfEdgeId nxt = 3 * fan_[i + 1 == n ? 0 : i + 1];
    tw_[e + 2] = nxt;
    tw_[nxt] = e + 2;
    fl_[e] = 0;
    fl_[e + 1] = b.flags;
    fl_[e + 2] = 0;
    if (has_markers_) {
      mk_[e] = 0;
      mk_[e + 1] = b.marker;
      mk_[e + 2] = 0;
    }
    if (carry_bounds_) m_.set_triangle_area_bound(t, b.area_bound);
  }
  ve_[v] = 3 * fan_[0];
  carry_attributes();
  for (std::size_t i = 0; i < n; ++i) {
    consider(fan_[i]);
    if (bnd_[i].flags & kConstrained) check_encroached(3 * fan_[i] + 1, v);
  }
}

// Splits the constrained edge e = (a -> b) at its split point.
bool Refiner::split_segment(HalfEdgeId e, const Point* at, int depth) {
  const VertexId a = tv_[e], b = tv_[next_edge(e)];
  Point mp = at ? *at : split_point(a, b);
  const int marker = has_markers_ ? mk_[e] : 0;
  const std::uint8_t flags = fl_[e];
  const bool boundary = tw_[e] == kNone;
  if ((boundary && !keep_split_inside(e, mp)) || !split_cavity(e, mp)) {
    // The split point is off the segment's line by rounding and some
    // neighbouring triangle is too flat to take it: leave this segment.
    ++st_.failed_splits;
    return false;
  }
  const std::uint32_t seg = a >= n_input_ ? seg_of_[a] : (b >= n_input_ ? seg_of_[b] : input_segment(a, b));
  int vmarker = marker != 0 ? marker : (boundary ? 1 : 0);
  const VertexId v = new_vertex(mp, seg, vmarker);
  {
    const std::size_t na = m_.num_vertex_attributes();
    if (na > 0) {
      std::vector<double>& at = m_.vertex_attributes();
      const double la = std::sqrt(dist2(mp, pts_[a])), lb = std::sqrt(dist2(mp, pts_[b]));
      const double wa = la + lb > 0 ? lb / (la + lb) : 0.5;
      for (std::size_t k = 0; k < na; ++k) at[v * na + k] = wa * at[a * na + k] + (1 - wa) * at[b * na + k];
    }
  }
  ++st_.segment_splits;
  const std::size_t n = bnd_.size();
  const std::size_t n1 = side_split_;  // side one: boundary edges [0, n1), b ... a
  fan_.resize(n);
  // Slots: side one uses its cavity slots first; new slots fill up as needed.
  // Any assignment works as long as every cavity slot is reused.
  for (std::size_t i = 0; i < n; ++i) fan_[i] = i < cav_.size() ? cav_[i] : kNone;
  for (std::size_t i = cav_.size(); i < n; ++i) fan_[i] = take_slot(i, n, v);
  for (std::size_t i = 0; i < n; ++i) {
    const HalfEdgeId oe = ve_[bnd_[i].a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[bnd_[i].a] = 3 * fan_[i] + 1;
  }
  if (boundary) {
    const HalfEdgeId oe = ve_[a];
    if (oe == kNone || in_cavity(tri_of(oe))) ve_[a] = 3 * fan_[n1 - 1] + 2;
  }
  auto write = [&](std::size_t i) {
    const TriId t = fan_[i];
    const HalfEdgeId f = 3 * t;
    const BoundaryEdge& bd = bnd_[i];
    tv_[f] = v;
    tv_[f + 1] = bd.a;
    tv_[f + 2] = bd.b;
    tw_[f + 1] = bd.outer;
    if (bd.outer != kNone) tw_[bd.outer] = f + 1;
    fl_[f] = 0;
    fl_[f + 1] = bd.flags;
    fl_[f + 2] = 0;
    if (has_markers_) {
      mk_[f] = 0;
      mk_[f + 1] = bd.marker;
      mk_[f + 2] = 0;
    }
    if (carry_bounds_) m_.set_triangle_area_bound(t, bd.area_bound);
  };
  for (std::size_t i = 0; i < n; ++i) write(i);
  auto chain = [&](std::size_t lo, std::size_t hi) {
    for (std::size_t i = lo; i + 1 < hi; ++i) {
      tw_[3 * fan_[i] + 2] = 3 * fan_[i + 1];
      tw_[3 * fan_[i + 1]] = 3 * fan_[i] + 2;
    }
  };
  chain(0, n1);
  chain(n1, n);
  auto seg_edge = [&](HalfEdgeId h) {
    fl_[h] = flags;
    if (has_markers_) mk_[h] = marker;
  };
  const HalfEdgeId mb1 = 3 * fan_[0], am1 = 3 * fan_[n1 - 1] + 2;  // m->b, a->m on side one
  seg_edge(mb1);
  seg_edge(am1);
  if (boundary) {
    tw_[mb1] = kNone;
    tw_[am1] = kNone;
  } else {
    const HalfEdgeId ma2 = 3 * fan_[n1], bm2 = 3 * fan_[n - 1] + 2;  // m->a, b->m on side two
    seg_edge(ma2);
    seg_edge(bm2);
    tw_[am1] = ma2;
    tw_[ma2] = am1;
    tw_[mb1] = bm2;
    tw_[bm2] = mb1;
  }
  ve_[v] = mb1;
  carry_attributes();
  for (std::size_t i = 0; i < n; ++i) {
    consider(fan_[i]);
    if (bnd_[i].flags & kConstrained) check_encroached(3 * fan_[i] + 1, v);
  }
  // The two new subsegments against the apexes next to them.
  check_encroached(mb1, tv_[prev_edge(mb1)]);
  check_encroached(am1, tv_[prev_edge(am1)]);
  if (!boundary) {
    const HalfEdgeId ma2 = tw_[am1], bm2 = tw_[mb1];
    check_encroached(ma2, tv_[prev_edge(ma2)]);
    check_encroached(bm2, tv_[prev_edge(bm2)]);
  }
  // Segments that bound a small angle with this one get a vertex at the
  // same distance from the apex: vertices at equal radii never encroach
  // the partner's subsegments, where unequal ones would start a cascade of
  // splits down to the width of the wedge.
  if (opt_.small_angle_protection && seg != kNone && seg_small_[seg] && depth < 4) {
    for (int end = 0; end < 2; ++end) {
      if (!(seg_small_[seg] & (1 << end))) continue;
      const VertexId apex = segs_[seg][end];
      const double radius = std::sqrt(dist2(mp, pts_[apex]));
      const double piece2 = std::min(dist2(mp, pts_[a]), dist2(mp, pts_[b]));
      for (std::uint32_t partner : partners_[2 * seg + end]) {
        if (partner == kNone) continue;
        // Pieces shorter than the gap to the partner there do not encroach
        // it: mirroring them would carry fine splits made for some other
        // feature (a crossing further out) to where the partner needs none.
        if (piece2 < gap2(seg, partner, apex, radius)) continue;
        mirror(partner, apex, radius, depth + 1);
      }
    }
  }
  return true;
}

// Squared distance between segments s and t (both ending at apex) at
// distance `radius` from the apex.
double Refiner::gap2(std::uint32_t s, std::uint32_t t, VertexId apex, double radius) const {
  const Point& A = pts_[apex];
  const Point& S = pts_[segs_[s][0] == apex ? segs_[s][1] : segs_[s][0]];
  const Point& T = pts_[segs_[t][0] == apex ? segs_[t][1] : segs_[t][0]];
  const double ux = S.x - A.x, uy = S.y - A.y, wx = T.x - A.x, wy = T.y - A.y;
  const double cross = ux * wy - uy * wx;
  return radius * radius * cross * cross / ((ux * ux + uy * uy) * (wx * wx + wy * wy));
}

// Splits segment `seg` (one end at `apex`) at distance `radius` from the
// apex, unless a vertex of it is already about that far.
void Refiner::mirror(std::uint32_t seg, VertexId apex, double radius, int depth) {
  const VertexId other = segs_[seg][0] == apex ? segs_[seg][1] : segs_[seg][0];
  const Point A = pts_[apex], O = pts_[other];
  const double len = std::sqrt(dist2(A, O));
  if (!(radius > 0) || radius >= len) return;
  auto on_seg = [&](VertexId w) { return w == other || (w >= n_input_ && seg_of_[w] == seg); };
  VertexId u = apex;
  double ru = 0;
  for (std::size_t steps = 0; steps < 100000; ++steps) {
    // The next vertex of the segment beyond u.
    VertexId next = kNone;
    double rn = INFINITY;
    HalfEdgeId hint = kNone;
    auto consider_w = [&](VertexId w, HalfEdgeId h) {
      if (!on_seg(w)) return;
      const double r = std::sqrt(dist2(pts_[w], A));
      if (r > ru && r < rn) rn = r, next = w, hint = h;
    };
    m_.for_each_out_edge(u, [&](HalfEdgeId h) {
      if (fl_[h] & kConstrained) consider_w(tv_[next_edge(h)], h);
      const HalfEdgeId p = prev_edge(h);
      if (fl_[p] & kConstrained) consider_w(tv_[p], p);
      return true;
    });
    if (next == kNone) return;
    if (rn < radius) {
      u = next;
      ru = rn;
      continue;
    }
    const double piece = rn - ru;
    if (radius - ru < 0.05 * piece || rn - radius < 0.05 * piece) return;  // already (nearly) there
    const HalfEdgeId e = tv_[hint] == u ? hint : tw_[hint];
    if (e == kNone || tv_[e] != u) {
      const HalfEdgeId f = edge(u, next, kNone);
      if (f == kNone) return;
      if (!splittable(f) || !budget_left()) return;
      const Point p{A.x + (O.x - A.x) * (radius / len), A.y + (O.y - A.y) * (radius / len)};
      split_segment(f, &p, depth);
      return;
    }
    if (!splittable(e) || !budget_left()) return;
    const Point p{A.x + (O.x - A.x) * (radius / len), A.y + (O.y - A.y) * (radius / len)};
    split_segment(e, &p, depth);
    return;
  }
}

// The half-edge a -> b: the hint if it still is one, else a rotation around
// a, else the twin of b -> a (a vertex where holes touch has two fans and
// the rotation from its out-edge sees only one).
HalfEdgeId Refiner::edge(VertexId a, VertexId b, HalfEdgeId hint) const {
  if (hint < tv_.size() && tv_[hint] == a && tv_[next_edge(hint)] == b) return hint;
  HalfEdgeId e = m_.find_edge(a, b);
  if (e != kNone) return e;
  e = m_.find_edge(b, a);
  return e != kNone ? tw_[e] : kNone;
}

bool Refiner::budget_left() {
  if (st_.steiner_points >= budget_) {
    st_.budget_exhausted = true;
    stopped_ = true;
    return false;
  }
  return true;
}

// ===========================================================================
// Driver

void Refiner::run() {
  start_ = Clock::now();
  // When a sizing callback throws, the exception leaves run() between two
  // insertions: the triangles are whole, only their count lags behind.
  struct CountAppended {
    Refiner& r;
    ~CountAppended() { r.count_appended(); }
  } count_on_exit{*this};
  setup();
  queue_encroached();
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) consider(t);
  ProgressReporter progress(opt_.progress, "refine", "Steiner points");
  refine_loop(progress);
  if (beyond_ && !stopped_) go_beyond(progress);
  else if (beyond_) set_bound(std::clamp(opt_.min_angle_deg, 0.0, 60.0));  // report against the bound asked for
  finish();
}

// sin^2 of the smallest angle of the mesh; outside_small_angles: of the
// triangles not left alone at small input angles.
double Refiner::smallest_sin2(bool outside_small_angles) const {
  double low = 1.0;
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    if (outside_small_angles && t < why_.size() && why_[t] == Reason::SmallAngle) continue;
    const Point& a = pts_[tv_[3 * t]];
    const Point& b = pts_[tv_[3 * t + 1]];
    const Point& c = pts_[tv_[3 * t + 2]];
    const double l0 = dist2(a, b), l1 = dist2(b, c), l2 = dist2(c, a);
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double den = std::max({l0 * l1, l1 * l2, l2 * l0});  // the two longer edges
    if (den > 0) low = std::min(low, cross * cross / den);
  }
  return low;
}

// Above kAutomaticBudgetAngle, where Delaunay refinement need not end
// (Shewchuk 2002 reports termination in practice up to about 33.8°): the
// mesh refined to kAutomaticBudgetAngle is kept aside, and refinement goes
// on to the requested bound, worst triangles first (shortest-edge-first
// lets the smallest angle collapse where points spiral into a corner),
// watched by checkpoint(). If it stops short, the mesh with the larger
// smallest angle (overall and outside small input angles) is returned.
void Refiner::go_beyond(ProgressReporter& progress) {
  count_appended();
  const double kept_all = smallest_sin2(false), kept_outside = smallest_sin2(true);
  Mesh kept = m_;
  const std::vector<Reason> kept_why = why_;
  const RefineStats kept_st = st_;
  set_bound(std::clamp(opt_.min_angle_deg, 0.0, 60.0));
  shortest_first_ = false;
  skipped_.clear();
  requeues_ = 0;
  requeue_mark_ = SIZE_MAX;
  queue_encroached();
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) consider(t);
  watch_ = true;
  watch_cap_ = st_.steiner_points + 4 * pts_.size() + 10000;
  refine_loop(progress);
  count_appended();
  if (!(stalled_ || st_.budget_exhausted || st_.time_exhausted)) return;
  if (smallest_sin2(false) >= kept_all && smallest_sin2(true) >= kept_outside) return;
  const RefineStats later = st_;
  m_ = std::move(kept);  // the references to its arrays stay valid
  why_ = kept_why;
  st_ = kept_st;
  st_.min_angle_deg = later.min_angle_deg;
  st_.stalled = later.stalled;
  st_.stall_x = later.stall_x, st_.stall_y = later.stall_y, st_.stall_radius = later.stall_radius;
  st_.budget_exhausted = later.budget_exhausted;
  st_.time_exhausted = later.time_exhausted;
  st_.peak_queue = later.peak_queue;
  st_.discarded_steiner = later.steiner_points - kept_st.steiner_points;
  st_.kept_angle_deg = kAutomaticBudgetAngle;
}

// Encroached subsegments, for rule R1 before anything else.
void Refiner::queue_encroached() {
  for (HalfEdgeId e = 0; e < tv_.size(); ++e)
    if ((fl_[e] & kConstrained) && (tw_[e] == kNone || tw_[e] > e) && encroached(e) && splittable(e))
      encroached_.push_back({tv_[e], tv_[next_edge(e)], e});
}

// Rules R1 and R2 until nothing is left to do or a budget stops them.
void Refiner::refine_loop(ProgressReporter& progress) {
  const bool timed = opt_.time_limit_seconds > 0;
  if (watch_) {
    check_interval_ = std::max<std::size_t>(256, pts_.size() / 8);
    next_check_ = st_.steiner_points + check_interval_;
    window_start_ = pts_.size();
  }
  while (!stopped_) {
    if (progress.active()) progress.set(st_.steiner_points);
    if (watch_ && st_.steiner_points >= next_check_) {
      checkpoint();
      if (stopped_) break;
    }
    if (timed && (++iterations_ & 255) == 0 &&
        std::chrono::duration<double>(Clock::now() - start_).count() > opt_.time_limit_seconds) {
      st_.time_exhausted = true;
      break;
    }
    if (!encroached_.empty()) {
      const SubsegmentRef r = encroached_.back();
      encroached_.pop_back();
      const HalfEdgeId e = edge(r.a, r.b, r.hint);
      if (e == kNone || !(fl_[e] & kConstrained) || !encroached(e) || !splittable(e)) continue;
      if (excused(e)) continue;
      if (!budget_left()) break;
      split_segment(e);
      continue;
    }
    if (queue_.empty()) {
      // Another look at the transient skips, a bounded number of times.
      // Only while the last round changed the mesh: else the same skips come back.
      if (skipped_.empty() || requeues_ >= kRequeueRounds || st_.steiner_points == requeue_mark_) break;
      requeue_mark_ = st_.steiner_points;
      ++requeues_;
      std::vector<QueueEntry> again;
      again.swap(skipped_);
      for (const QueueEntry& s : again)
        if (alive(s)) consider(s.t);
      continue;
    }
    st_.peak_queue = std::max(st_.peak_queue, queue_.size());
    const QueueEntry q = queue_.pop();
    if (!alive(q)) continue;
    decide(q.t, decision_);
    switch (decision_.kind) {
      case Decision::Skip:
        if (decision_.reason == Reason::SmallAngle) ++st_.small_angle_skips;
        if (decision_.transient) skipped_.push_back(q);
        if (decision_.reason != Reason::None) remember_skip(q.t, decision_.reason);
        break;
      case Decision::Insert:
        if (!budget_left()) break;
        if (decision_.offcenter) ++st_.offcenters;
        insert_interior(decision_.c, cav_[0]);
        break;
      case Decision::Split: {
        ++st_.rejected_points;
        bool split = false;
        for (const SubsegmentRef& r : decision_.segments) {
          const HalfEdgeId e = edge(r.a, r.b, r.hint);
          if (e == kNone) continue;
          if (!budget_left()) break;
          split |= split_segment(e);
        }
        // Requeue the triangle for another look, unless no split could be
        // made (then the same decision would come back forever).
        if (split && alive(q)) consider(q.t);
        else if (!split && !stopped_) remember_skip(q.t, Reason::Precision);
        break;
      }
    }
  }
}

// Progress above the guaranteed range: every check_interval_ Steiner points,
// the triangles still below the bound (outside small input angles) and the
// smallest angle among them. Refinement that neither cuts their number by a
// tenth nor raises that angle over two intervals is not converging: its
// points pile up in one neighbourhood (off-centres spiralling into a corner)
// while the smallest angle there stays put, as Delaunay refinement does
// beyond the bounds it is known to reach (Shewchuk 2002: ~33.8° in
// practice). The last interval's points name the place.
void Refiner::checkpoint() {
  next_check_ = st_.steiner_points + check_interval_;
  std::size_t bad = 0;
  double low = 1.0;
  const std::size_t nt = tv_.size() / 3;
  for (TriId t = 0; t < nt; ++t) {
    const Eval ev = eval(t);
    if (!ev.skinny || (t < why_.size() && why_[t] == Reason::SmallAngle)) continue;
    ++bad;
    low = std::min(low, ev.sin2);
  }
  const bool fewer = bad < best_bad_ - best_bad_ / 4 || best_bad_ == SIZE_MAX;
  const bool higher = low > best_sin2_ * 1.02;  // about half a degree near 35°
  best_bad_ = std::min(best_bad_, bad);
  best_sin2_ = std::max(best_sin2_, low);
  const bool capped = st_.steiner_points >= watch_cap_;
  if (!capped && (fewer || higher)) {
    stale_checks_ = 0;
  } else if (capped || ++stale_checks_ >= 2) {
    // Where the last interval's points went: their coordinate-wise median,
    // and the median distance from it.
    std::vector<double> xs, ys, ds;
    for (std::size_t v = window_start_; v < pts_.size(); ++v) xs.push_back(pts_[v].x), ys.push_back(pts_[v].y);
    if (!xs.empty()) {
      auto median = [](std::vector<double>& a) {
        std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
        return a[a.size() / 2];
      };
      const Point c{median(xs), median(ys)};
      for (std::size_t v = window_start_; v < pts_.size(); ++v) ds.push_back(std::sqrt(dist2(pts_[v], c)));
      st_.stall_x = c.x, st_.stall_y = c.y, st_.stall_radius = median(ds);
    }
    stalled_ = true;
    stopped_ = true;
    st_.stalled = true;
  }
  window_start_ = pts_.size();
}

void Refiner::count_appended() {
  m_.set_live_real(m_.live_real() + appended_);
  appended_ = 0;
}

void Refiner::finish() {
  count_appended();
  const bool stopped = st_.budget_exhausted || st_.time_exhausted || stalled_;
  // Classify what is left by the reason recorded when each triangle was
  // last left alone (linear: no decision is repeated here). A bad triangle
  // without one was still waiting when a budget stopped refinement.
  const std::size_t nt = tv_.size() / 3;
  double low_outside = 2.0;
  for (TriId t = 0; t < nt; ++t) {
    const Eval ev = eval(t);
    if (!ev.skinny && !ev.large) continue;
    Reason why = t < why_.size() ? why_[t] : Reason::None;
    if (why == Reason::None) why = stalled_ ? Reason::OutOfReach : (stopped ? Reason::Budget : Reason::Precision);
    if (ev.large) {
      ++st_.too_large;
      if (why == Reason::Precision) ++st_.too_large_precision;
    }
    if (!ev.skinny) continue;
    ++st_.below_bound;
    if (why != Reason::SmallAngle) low_outside = std::min(low_outside, ev.sin2);
    switch (why) {
      case Reason::SmallAngle: ++st_.below_small_input_angle; break;
      case Reason::Protected: ++st_.below_segment_protected; break;
      case Reason::Budget: ++st_.below_budget; break;
      case Reason::OutOfReach: ++st_.below_out_of_reach; break;
      default: ++st_.below_precision; break;
    }
  }
  // Complete: no budget stopped it and every triangle is within its size
  // bound (skinny triangles may remain for the reasons counted above).
  st_.reached_angle_deg =
      low_outside > 1.0 ? st_.min_angle_deg : std::asin(std::sqrt(low_outside)) * 180.0 / std::numbers::pi;
  st_.complete = !stopped && st_.too_large == 0;
  if (stalled_) st_.budget_exhausted = true;  // the progress watch is a budget: the mesh is as good as it got
  st_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
}

}  // namespace

std::string RefineStats::summary() const {
  std::ostringstream out;
  const bool stopped = budget_exhausted || time_exhausted;
  out << "refinement " << (complete ? "complete" : (stopped ? "stopped early" : "incomplete"));
  if (stalled) {
    out << " (" << min_angle_deg << "° out of reach: no progress while half the last Steiner points went within "
        << stall_radius << " of (" << stall_x << ", " << stall_y << "); " << reached_angle_deg
        << "° reached outside small input angles";
    if (discarded_steiner)
      out << ", the mesh refined to " << kept_angle_deg << "° kept, " << discarded_steiner << " later Steiner points dropped";
    out << ")";
  } else if (budget_exhausted) {
    out << " (Steiner budget reached)";
  }
  if (time_exhausted) out << " (time limit reached)";
  out << ": " << steiner_points << " Steiner points (" << segment_splits << " on segments, " << interior_points
      << " inside, " << offcenters << " off-centres), " << rejected_points << " encroaching points rejected";
  if (below_bound > 0) {
    out << "; " << below_bound << " triangles below " << min_angle_deg << "°:";
    if (below_small_input_angle) out << " " << below_small_input_angle << " at input angles < 60°";
    if (below_segment_protected) out << " " << below_segment_protected << " need a split -Y forbids";
    if (below_budget) out << " " << below_budget << " left by the budget";
    if (below_out_of_reach) out << " " << below_out_of_reach << " where the bound is out of reach";
    if (below_precision) out << " " << below_precision << " at the precision of doubles";
  }
  if (too_large > 0) {
    out << "; " << too_large << " triangles above their size bound";
    if (too_large_precision) out << " (" << too_large_precision << " at the precision of doubles)";
  }
  return out.str();
}

RefineStats refine(Mesh& mesh, const RefineOptions& options) {
  RefineStats stats;
  if (!mesh.compacted()) mesh.compact();
  stats.input_vertices = mesh.num_vertices();
  stats.min_angle_deg = options.min_angle_deg;
  if (mesh.num_triangles() == 0) return stats;
  Refiner(mesh, options, stats).run();
  // Mesh::add_triangle (used when triangles carry bounds or attributes)
  // clears the compacted flag; the mesh has no dead or ghost slots.
  if (!mesh.compacted()) mesh.compact();
  return stats;
}

std::string_view to_string(SteinerRule r) {
  switch (r) {
    case SteinerRule::Best: return "best";
    case SteinerRule::Offcenter: return "offcenter";
    case SteinerRule::Circumcenter: break;
  }
  return "circumcenter";
}

std::optional<SteinerRule> parse_steiner_rule(std::string_view name) {
  if (name == "offcenter" || name == "off-center" || name == "offcentre") return SteinerRule::Offcenter;
  if (name == "circumcenter" || name == "circumcentre") return SteinerRule::Circumcenter;
  if (name == "best") return SteinerRule::Best;
  return std::nullopt;
}

std::string_view to_string(EncroachmentRule r) {
  return r == EncroachmentRule::DiametralCircle ? "circle" : "lens";
}

std::optional<EncroachmentRule> parse_encroachment_rule(std::string_view name) {
  if (name == "circle") return EncroachmentRule::DiametralCircle;
  if (name == "lens") return EncroachmentRule::DiametralLens;
  return std::nullopt;
}

}  // namespace deltamesh
