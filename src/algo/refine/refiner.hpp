// The state of one Delaunay refinement, and its steps declared by concern.
// Each group of methods is defined in the file named above it; docs/internals.md
// maps the published rules to them.
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "algo/refine/queue.hpp"
#include "algo/refine_parallel.hpp"
#include "core/angles.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/progress.hpp"
#include "deltamesh/refine.hpp"
#include "mesh/cavity.hpp"
#include "mesh/editor.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh::refinement {

using Clock = std::chrono::steady_clock;

inline double dist2(const Point& a, const Point& b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

// Exact sign of (a - p)·(b - p): negative iff p lies strictly inside the
// circle with diameter ab (encroachment.cpp).
double diametral_dot(const Point& a, const Point& b, const Point& p);

// sin^2 of the angle bound theta in degrees (0: no angle criterion).
inline double angle_bound_sin2(double theta) {
  const double rad = theta * std::numbers::pi / 180.0;
  return theta > 0 ? std::sin(rad) * std::sin(rad) : 0.0;
}

// The diametral lens of angle bound theta (Shewchuk 2002): cos^2 of the
// smallest angle a subsegment subtends at a point that encroaches upon it.
inline double lens_angle_cos2(double theta) {
  const double phi = std::max(90.0, 180.0 - 2.0 * theta) * std::numbers::pi / 180.0;
  return std::cos(phi) * std::cos(phi);
}

// Whether p encroaches upon subsegment ab: inside its diametral lens
// (lens_cos2 from lens_angle_cos2), or without a lens its diametral circle
// (Ruppert 1995; exact sign).
inline bool encroaches_upon(const Point& a, const Point& b, const Point& p, bool lens, double lens_cos2) {
  if (!lens) return diametral_dot(a, b, p) < 0;
  const double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y;
  const double dot = ax * bx + ay * by;
  if (!(dot < 0)) return false;
  return dot * dot > lens_cos2 * (ax * ax + ay * ay) * (bx * bx + by * by);
}

// Triangle abc seen from its shortest edge PQ, which its smallest angle
// faces: sin^2 of that angle is cross^2 / den.
struct ShortestEdgeShape {
  double l2[3];       // squared lengths of ab, bc, ca
  int shortest = 0;   // index of PQ in l2
  double cross = 0;   // twice the signed area, from P
  double den = 0;     // product of the other two squared lengths
};

inline ShortestEdgeShape shortest_edge_shape(const Point& a, const Point& b, const Point& c) {
  ShortestEdgeShape sh{{dist2(a, b), dist2(b, c), dist2(c, a)}};
  const int s = shortest_edge_index(sh.l2);
  // Twice the area from an end P of the shortest edge PQ: (Q - P) and
  // (R - P) lose nothing to cancellation even where P and Q are far smaller
  // than R (a tiny feature seen from far away), which the differences from
  // another corner would round away.
  const Point& P = s == 0 ? a : (s == 1 ? b : c);
  const Point& Q = s == 0 ? b : (s == 1 ? c : a);
  const Point& R = s == 0 ? c : (s == 1 ? a : b);
  sh.shortest = s;
  sh.cross = (Q.x - P.x) * (R.y - P.y) - (Q.y - P.y) * (R.x - P.x);
  sh.den = sh.l2[(s + 1) % 3] * sh.l2[(s + 2) % 3];
  return sh;
}

// Wedges narrower than this get the mid-wedge small-angle rule and mirrored
// segment splits (wider ones are refined; only the triangle holding the
// input angle is left). Measured on the corpus.
constexpr double kWedgeAngle = 10.0;

// Why a bad triangle was left alone.
enum class Reason : std::uint8_t { None, SmallAngle, Protected, Precision, Budget, OutOfReach };

// A triangle judged by the quality criteria (quality.cpp).
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
        tv_(detail::MeshEditor(mesh).triangle_vertices()),
        tw_(detail::MeshEditor(mesh).twins()),
        fl_(detail::MeshEditor(mesh).edge_flags()),
        mk_(detail::MeshEditor(mesh).edge_markers()),
        pts_(detail::MeshEditor(mesh).points()),
        ve_(detail::MeshEditor(mesh).out_edges()) { trace_ = mesh.trace(); }

  void run();
  // Threads for the passes that evaluate every triangle (the first look and
  // the statistics); the result is the same for any count. Only without
  // callbacks, which would be called concurrently (refine_in_parts' last pass).
  void set_scan_threads(unsigned threads) { scan_threads_ = threads; }
  // A stage of refine_in_parts (refine_parallel.hpp): a first look given,
  // the final verdicts kept, no reserve.
  void set_stage(detail::RefineStage* stage) { stage_ = stage; }

 private:
  // ---- driver.cpp: setup, the R1/R2 loop, decisions ----------------------
  // (Methods declared inline are defined in the file that uses them, or in a
  // header it includes, so that the compiler may inline them into the loop.)
  void setup();
  void set_unit();
  void set_bound(double theta);
  void reserve_for_area_bounds();
  double area_ratio(TriId t, bool global) const;
  void queue_encroached();
  // ---- setup_scan.cpp: setup()'s passes on scan_threads_ threads ----------
  void scan_edges_in_parallel();
  void queue_encroached_in_parallel();
  double area_estimate_in_parallel(bool global) const;
  void refine_loop(ProgressReporter& progress);
  inline bool tick();
  inline void split_encroached_segment();
  inline void split_bad_triangle();
  inline bool look_again_at_skipped();
  struct Decision {
    enum Kind { Skip, Split, Insert } kind = Skip;
    Reason reason = Reason::None;
    bool transient = false;  // a skip that may change when neighbours change
    Point c;
    bool offcenter = false;
    TraceReason rule = TraceReason::None;  // which Steiner rule chose c (for the trace)
    std::vector<SubsegmentRef> segments;
    // A hub wedge's far side, split at the near side's radius after the
    // segments above (hub_wedge_side); kNone: none.
    std::uint32_t mirror_seg = kNone;
    VertexId mirror_apex = kNone;
    double mirror_radius = 0;
  };
  inline void decide(TriId t, Decision& d);
  void decide_segments(TriId t, const std::vector<HalfEdgeId>& encroached, const Eval& ev, Decision& d);
  bool budget_left();
  std::uint32_t input_segment(VertexId a, VertexId b) const;
  std::uint32_t segment_of(VertexId a, VertexId b) const;
  HalfEdgeId edge(VertexId a, VertexId b, HalfEdgeId hint) const;

  // ---- beyond.cpp: bounds above kAutomaticBudgetAngle, with a progress watch --
  void go_beyond(ProgressReporter& progress);
  void checkpoint();
  double smallest_sin2(bool outside_small_angles) const;

  // ---- quality.cpp: the criteria, and queueing bad triangles -----------------
  inline double area_bound(TriId t, const Point& a, const Point& b, const Point& c) const;
  Eval eval(TriId t, const Point& a, const Point& b, const Point& c) const;
  Eval eval(TriId t) const {
    const HalfEdgeId e = 3 * t;
    return eval(t, pts_[tv_[e]], pts_[tv_[e + 1]], pts_[tv_[e + 2]]);
  }
  void consider(TriId t);
  // Per triangle slot, 1 when eval() finds it bad; empty on one scan thread.
  // After the first look (first_bad_ kept by run()), slots that no fan has
  // rewritten since (insert.cpp marks them kLookAgain) are not evaluated again.
  std::vector<std::uint8_t> bad_slots() const;
  void look_again_at_fan(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      if (fan_[i] < first_bad_.size()) first_bad_[fan_[i]] = detail::kLookAgain;
  }
  std::vector<std::uint8_t> first_look() const;  // from stage_
  std::vector<std::uint8_t> first_bad_;
  // Why subsegment e may not be split: Reason::None when it may.
  Reason split_refusal(HalfEdgeId e) const;
  bool splittable(HalfEdgeId e) const { return split_refusal(e) == Reason::None; }
  // A new coordinate below the exact predicates' smallest magnitude
  // (kMinCoordinate) is rounded to 0 (a move far below any ulp of the
  // triangle's own coordinates).
  static Point within_predicate_range(Point p) {
    if (std::fabs(p.x) < kMinCoordinate) p.x = std::copysign(0.0, p.x);  // -0 stays -0
    if (std::fabs(p.y) < kMinCoordinate) p.y = std::copysign(0.0, p.y);
    return p;
  }
  bool alive(const QueueEntry& e) const {
    return e.t < tv_.size() / 3 && tv_[3 * e.t] == e.a && tv_[3 * e.t + 1] == e.b && tv_[3 * e.t + 2] == e.c;
  }

  // ---- steiner.cpp: where a bad triangle is split ------------------------------
  inline Point steiner_point(TriId t, const Eval& ev, bool& offcenter) const;  // steiner.hpp
  Point best_point(TriId t, const Eval& ev, const Point& primary);
  Point grid_point(TriId t, const Eval& ev, const Point& primary);
  bool score(TriId t, const Point& c, double min2, int& bad, double& radius2);
  bool gather_petal(TriId t, const Point& centre, double radius);
  bool near_encroachment(const Point& a, const Point& b, const Point& c) const;
  // skinny: when given, the boundary edges (a, b) that c leaves skinny are appended.
  bool score_local(const Point& c, double min2, int best_bad, double best_r2, int& bad, double& radius2,
                   std::vector<std::array<Point, 2>>* skinny = nullptr);
  void prepare_grid();

  // ---- encroachment.cpp: encroachment, and where a segment is split -----------
  // Whether p encroaches upon subsegment ab: inside its diametral lens
  // (Shewchuk 2002), or its diametral circle (Ruppert 1995; exact sign) with
  // EncroachmentRule::DiametralCircle or -D.
  bool encroaches(const Point& a, const Point& b, const Point& p) const {
    return encroaches_upon(a, b, p, lens_, lens_cos2_);
  }
  bool encroached(HalfEdgeId e) const;
  void push_if_encroached(HalfEdgeId e, VertexId apex);
  Point segment_split_point(VertexId a, VertexId b) const;
  bool keep_split_inside(HalfEdgeId e, Point& m) const;

  // ---- small_angle.cpp: the rules that make refinement terminate --------------
  void find_small_angles();
  struct Sector {  // from constrained out-edge e0 counter-clockwise to g
    HalfEdgeId e0, g;
    double angle;
  };
  bool sector_at(Sector& s) const;
  void note_sector(const Sector& s);
  void sectors_in_parallel(std::vector<Sector>& out) const;
  void mark_spikes();
  TriView view(TriId t) const;
  bool faces_small_angle(TriId t, const Eval& ev) const { return faces_small_angle(view(t), ev); }
  bool faces_small_angle(const TriView& tv, const Eval& ev, bool holding = true) const;
  bool in_small_input_angle(const TriView& tv, const Eval& ev, bool holding) const;
  void apexes(VertexId v, std::uint32_t seg, std::array<std::pair<VertexId, std::uint32_t>, 2>& small, int& n,
              std::vector<std::pair<VertexId, std::uint32_t>>& many) const;
  bool in_channel(const TriView& tv) const;
  bool channel_pair(std::uint32_t sa, std::uint32_t sb, double& gap2) const;
  bool near_channel(const Point& p, std::uint32_t sa, std::uint32_t sb, double gap2) const;
  template <class F>
  void spike_segments(VertexId v, std::uint32_t seg, F&& f) const;
  bool left_alone(const TriView& tv, bool holding) const;
  bool refuse_split_near_apex(HalfEdgeId e, const Eval& ev, TriId t) const;
  void measure_apex_feature_sizes();
  // A hub with shells: an input vertex with three or more segments and a
  // small angle between two of them (few; inline, the scan asks every half-edge).
  bool shelled_hub(VertexId v) const {
    return v < n_input_ && apex_cos_[v] > shell_cos_ && adj_start_[v + 1] - adj_start_[v] >= 3;
  }
  bool apex_distance(HalfEdgeId e, double& d2) const;
  void note_apex_distance(VertexId v, double d2) {
    if (apex_lfs2_[v] == 0 || d2 < apex_lfs2_[v]) apex_lfs2_[v] = d2;
    has_hubs_ = true;
  }
  void apex_feature_sizes_in_parallel();  // setup_scan.cpp
  bool in_small_sector(VertexId apex, const Point& g) const;
  HalfEdgeId hub_wedge_side(const Point& c, std::uint32_t& far_seg, VertexId& apex) const;
  bool leave_for_narrow_wedge(TriId t, const Point& c) const;
  bool exempt_from_r1(HalfEdgeId e) const;
  void mirror_split(std::uint32_t seg, VertexId apex, double radius, int depth);
  double gap2(std::uint32_t s, std::uint32_t t, VertexId apex, double radius) const;

  // ---- cavity.cpp: point location and Bowyer-Watson cavities -------------------
  struct Walk {
    enum Kind { Found, OnVertex, Blocked, Failed } kind;
    TriId tri = kNone;
    HalfEdgeId edge = kNone;  // Found: the edge c lies on (or kNone); Blocked: the segment crossed
  };
  Walk walk(TriId t, const Point& c) const;
  inline bool cavity(const Point& c, TriId seed);  // cavity.hpp
  bool split_cavity(HalfEdgeId e, const Point& m);
  bool in_circumcircle(TriId t, const Point& p) const;
  bool grow(const Point& c);
  inline void record_boundary(HalfEdgeId e);  // (inline: grow()'s callback, once per boundary edge)
  bool boundary_visible(const Point& c, std::size_t from, std::size_t to) const;
  void begin_cavity() {
    cav_.begin();
    bnd_.clear();
    stack_.clear();
  }
  void add_to_cavity(TriId t) { cav_.add(t); }
  bool in_cavity(TriId t) const { return cav_.contains(t); }
  // The mesh's arrays for the cavity kernels (mesh/cavity.hpp): flags
  // always, markers when the mesh has them.
  detail::MeshArrays arrays() {
    return {.tv = tv_.data(), .tw = tw_.data(), .flags = fl_.data(), .markers = has_markers_ ? mk_.data() : nullptr,
            .out = ve_.data(), .pts = pts_.data()};
  }

  // ---- insert.cpp: mesh updates ------------------------------------------------
  VertexId new_vertex(const Point& p, std::uint32_t seg, int marker);
  void insert_interior(const Point& c, TriId seed);
  bool split_segment(HalfEdgeId e, const Point* at = nullptr, int depth = 0);
  TriId new_slot(VertexId v);
  void carry_attributes();

  // ---- stats.cpp: what is left when refinement ends ----------------------------
  void remember_skip(TriId t, Reason r) {
    if (t >= why_.size()) why_.resize(std::max<std::size_t>(t + 1, tv_.size() / 3), Reason::None);
    why_[t] = r;
  }
  void count_appended();  // adds appended_ to the mesh's triangle count
  void finish();

  Mesh& m_;
  // ---- the trace (insert.cpp): what the next split reports as its cause ----
  TraceObserver* trace_ = nullptr;
  TraceEvent cause_;
  void trace_r1(HalfEdgeId e);
  void trace_r2(TriId t, TraceKind kind, TraceReason why);
  void trace_fan(TraceKind kind, VertexId v, VertexId a, VertexId b);
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
  bool best_ = false;             // SteinerRule::Best or Grid: choose among candidates
  bool sized_ = false;            // some size bound (area or edge length) applies
  double bound_rad_ = 0;          // the angle bound in radians
  // A length fixed by the input (the larger side of its bounding box when
  // refinement starts): the queue's buckets and the concentric shells are
  // laid out in powers of two of it, not of the absolute unit, so that
  // scaling the input by any factor (not only a power of two) scales the
  // mesh with it (docs/robustness.md, "Any finite coordinates").
  double unit_ = 1;
  // The queue's keys are squared lengths over unit_^2. (Known limit: a
  // ratio exactly at a bucket's bound, a power of two such as the halvings of
  // a segment as long as the box, is put on either side by rounding. Moving
  // the bounds off such ratios changed the order enough to make the hub
  // tests, whose lengths are powers of two, cascade.)
  double key_scale_ = 1;
  bool has_markers_ = false;
  int perturb_ = 0;             // order_perturbation_for_tests (queue.hpp) when refinement started
  double shell_cos_ = -2;       // input vertices whose smallest segment angle has a larger cosine get shells
  double small_cos2_ = 0.25;    // cos^2 of the largest input angle the small-angle rule treats as small
  double channel_sin2_ = 0;     // sin^2 of the largest angle between the two sides of a channel
  std::vector<float> apex_cos_; // per input vertex: cosine of its smallest angle between segments (-2: none)
  // Per input vertex with shells and three or more segments (a hub): its
  // squared local feature size in the input (the distance to the nearest
  // input vertex or segment not incident to it); 0 for the others.
  std::vector<double> apex_lfs2_;
  bool has_hubs_ = false;  // some apex_lfs2_ set: hub_wedge_side() can apply
  std::size_t budget_ = kUnlimited;
  std::size_t n_input_ = 0;
  unsigned scan_threads_ = 1;
  detail::RefineStage* stage_ = nullptr;

  // Input segments (the constrained edges when refinement starts).
  std::vector<std::array<VertexId, 2>> segs_;
  std::vector<std::uint8_t> seg_small_;      // bit 0/1: endpoint 0/1 is a small-angle apex for it
  // Per segment: kBoundarySeg (domain on one side only, to the left of
  // segs_[s][0] -> segs_[s][1]) and kSpikeSeg (a boundary side of a spike,
  // see small_angle.cpp).
  static constexpr std::uint8_t kBoundarySeg = 1, kSpikeSeg = 2;
  std::vector<std::uint8_t> seg_spike_;
  bool has_spikes_ = false;
  std::vector<std::uint32_t> adj_start_;     // CSR over input vertices
  std::vector<HalfEdgeId> constrained_;      // the constrained half-edges at setup, in order (setup_scan.cpp)
  std::vector<std::pair<VertexId, std::uint32_t>> adj_;  // (other endpoint, segment)
  std::vector<std::uint32_t> seg_of_;        // per Steiner vertex on a segment: its segment
  // Per segment end (2 s + 0/1): the segments bounding a small domain angle
  // with it at that end, whose splits are mirrored at the same radius.
  std::vector<std::array<std::uint32_t, 2>> partners_;

  BadQueue queue_;
  std::vector<SubsegmentRef> encroached_;  // R1's stack
  std::vector<QueueEntry> skipped_;  // transient skips, for another look
  // Per triangle slot: why it was last left alone (reset when the slot is
  // rewritten), so that finish() classifies what is left in linear time.
  std::vector<Reason> why_;

  // Scratch, reused by every insertion.
  detail::CavitySet cav_;
  std::vector<BoundaryEdge> bnd_;
  std::vector<HalfEdgeId> stack_;
  std::vector<TriId> fan_;
  std::vector<HalfEdgeId> enc_scratch_;
  std::vector<double> attr_scratch_;
  std::size_t side_split_ = 0;  // split cavities: boundary edges of side one
  Decision decision_;
  // The best point's neighbourhood (steiner.cpp): the triangles whose
  // circumcircle meets the petal, with their circles and local neighbours
  // (>= 0: index in petal_; kOut: a triangle outside; kWall: a segment or
  // the hull), so that candidates are scored without touching the mesh.
  // Its corners and squared edge lengths (edge k: p[k] -> p[k+1]) are
  // copied in, so that scoring reads one record per triangle.
  struct PetalTri {
    Point p[3];
    double e2[3];
    double cx, cy, r2;
    double r2_in, r2_out;  // r2 shrunk and grown by kNear (steiner.cpp): between them, degenerate
    std::int32_t nb[3];
  };
  static constexpr std::int32_t kOut = -1, kWall = -2;
  static constexpr std::size_t kMaxPetal = 96;
  std::vector<PetalTri> petal_;
  std::vector<std::uint32_t> petal_index_;  // per triangle slot in the cavity stamp: its index in petal_
  std::array<std::uint32_t, kMaxPetal> petal_in_{};  // per petal_ entry: the candidate stamp when in its cavity
  std::uint32_t petal_stamp_ = 0;
  std::array<std::int32_t, kMaxPetal> petal_stack_{};
  std::vector<std::array<Point, 2>> skinny_edges_;  // the primary's skinny cavity edges (best_point's seeds)
  std::vector<std::array<double, 2>> grid_cells_;  // best_point's coarse grid (height, shift) within the petal
  double grid_rad_ = -1;                           // the bound grid_cells_ was made for
  double grid_tan_ = 0, grid_half_cot_ = 0, grid_disc_ = 0;  // tan of the bound; the petal's disc per unit |PQ|

  std::size_t appended_ = 0;  // triangles appended without Mesh::add_triangle
  Clock::time_point start_;
  std::size_t iterations_ = 0;
  int requeues_ = 0;
  std::size_t requeue_mark_ = SIZE_MAX;  // Steiner points when the last requeue round began
  bool stopped_ = false;

  // Progress watch (above the guaranteed range; beyond.cpp).
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

}  // namespace deltamesh::refinement
