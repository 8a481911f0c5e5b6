// Watching the algorithms: an observer the triangulation, segment recovery,
// refinement, coarsening and smoothing report each step to (a vertex
// inserted, an edge flipped and why, a Steiner point and the rule that chose
// it, ...). Attach one with TriangulateOptions::trace or Plan::trace; with
// none attached the algorithms only test a null pointer off their hot paths.
// JsonLinesTrace writes the events in the format of docs/trace.md.
//
// The events are complete: applying each event's `removed` then `added`
// triangles to a set, from the first event on, gives the final mesh.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <cstdint>
#include <memory>
#include <ostream>
#include <span>
#include <string_view>
#include <vector>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

enum class TraceKind : std::uint8_t {
  Phase,          // a phase starts: `phase` names it
  Points,         // input vertices `vertex`, `vertex`+1, ... exist: `points`
  Insert,         // vertex `vertex` at `point` inserted (split of its triangle or edge)
  Flip,           // edge edge[0]-edge[1] flipped into edge[2]-edge[3]
  Recover,        // segment edge[0]-edge[1] is an edge now (`count`: flips it took)
  Retriangulate,  // the triangles a segment edge[0]-edge[1] crossed were replaced
  SplitSegment,   // R1: subsegment edge[0]-edge[1] split at `vertex`; encroached by `other` or `at`
  SplitTriangle,  // R2: triangle `tri` split at Steiner point `vertex`
  Reject,         // R2: the Steiner point `at` for `tri` was not inserted
  Remove,         // coarsening removed `vertex`
  Move,           // smoothing moved `vertex` from `at` to `point`
  Carve,          // triangles outside the domain removed
  Renumber,       // vertex i is now map[i] (kNone: gone); `count` vertices after
  Undo,           // refinement beyond 34 degrees undone: back to the mesh kept before it
  End,            // the run is over: `count` vertices, edge[0] triangles
};

enum class TraceReason : std::uint8_t {
  None,
  Delaunay,        // insertion / Lawson flip after an insertion
  Crossing,        // a vertex where two segments cross
  Lawson,          // constrained Lawson flip
  Recovery,        // flip-based edge recovery (Ct)
  Lifting,         // lifting-map ordered flip
  Coarsen,         // coarsening
  Ct,              // Recover: by which method
  LawsonMethod,
  LiftingMethod,
  Fast,
  Present,         // the segment was an edge already
  Encroached,      // R1
  RejectedPoint,   // R1 because an R2 point would encroach
  Conforming,      // -D
  Circumcentre,    // R2 rules
  OffCentre,
  BestPoint,
  Area,            // too large: circumcentre
  Encroaches,      // Reject reasons
  Outside,
  Precision,
  Budget,
  Laplacian,       // Move targets
  Odt,
  Holes,           // Carve reasons
  Exterior,
};

// The names docs/trace.md gives the kinds and reasons.
std::string_view trace_name(TraceKind k);
std::string_view trace_name(TraceReason r);

using TraceTriangle = std::array<VertexId, 3>;

struct TraceEvent {
  TraceKind kind = TraceKind::Phase;
  TraceReason reason = TraceReason::None;
  std::string_view phase;            // Phase
  VertexId vertex = kNone;           // the vertex the event is about
  Point point{};                     // its coordinates (after the event)
  VertexId other = kNone;            // SplitSegment: the encroaching vertex
  Point at{};                        // Reject / SplitSegment: the point not inserted; Move: old position
  bool has_at = false;
  std::array<VertexId, 4> edge{kNone, kNone, kNone, kNone};
  TraceTriangle tri{kNone, kNone, kNone};
  std::size_t count = 0;
  std::span<const TraceTriangle> removed;  // real triangles only, counter-clockwise
  std::span<const TraceTriangle> added;
  std::span<const Point> points;     // Points
  std::span<const VertexId> map;     // Renumber
};

namespace detail {
struct TraceAccess;
}

// Receives the events. The algorithms report slot changes; the base class
// keeps a copy of the triangle slots it has been told about and turns them
// into removed/added triangles, so an observer sees plain triangle sets.
class TraceObserver {
 public:
  TraceObserver();
  virtual ~TraceObserver();
  TraceObserver(const TraceObserver&) = delete;
  TraceObserver& operator=(const TraceObserver&) = delete;

  virtual void on_event(const TraceEvent& event) = 0;

  // Events reported so far.
  std::size_t events() const { return events_; }

 private:
  friend struct detail::TraceAccess;
  std::vector<VertexId> slots_;  // 3 per triangle slot, as last reported
  std::vector<TraceTriangle> removed_, added_;
  std::vector<Point> points_;  // an event's points in the user's frame
  int frame_exponent_ = 0;     // the run's coordinates are the user's times 2^this
  std::size_t events_ = 0;
};

// Writes docs/trace.md's JSON Lines: the header, then one line per event,
// in blocks of about 64 KiB to `sink` (or a stream); finish() writes the
// rest (the destructor does too, for a stream).
class JsonLinesTrace : public TraceObserver {
 public:
  using Sink = std::function<void(std::string_view)>;
  explicit JsonLinesTrace(Sink sink);
  explicit JsonLinesTrace(std::ostream& out);
  ~JsonLinesTrace() override;
  void on_event(const TraceEvent& event) override;
  void finish();

 private:
  Sink sink_;
  std::string buf_;
  bool stream_ = false;
};

}  // namespace deltamesh
