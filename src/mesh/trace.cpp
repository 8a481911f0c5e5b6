// The trace observer's bookkeeping (slot copies -> removed/added triangles)
// and the JSON Lines writer of docs/trace.md.
#include "deltamesh/trace.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <iterator>
#include <string>
#include <utility>

#include "deltamesh/errors.hpp"
#include "core/float_chars.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

std::string_view trace_name(TraceKind k) {
  switch (k) {
    case TraceKind::Phase: return "phase";
    case TraceKind::Points: return "points";
    case TraceKind::Insert: return "insert";
    case TraceKind::Flip: return "flip";
    case TraceKind::Recover: return "recover";
    case TraceKind::Retriangulate: return "retriangulate";
    case TraceKind::SplitSegment: return "split_segment";
    case TraceKind::SplitTriangle: return "split_triangle";
    case TraceKind::Reject: return "reject";
    case TraceKind::Remove: return "remove";
    case TraceKind::Move: return "move";
    case TraceKind::Carve: return "carve";
    case TraceKind::Renumber: return "renumber";
    case TraceKind::Undo: return "undo";
    case TraceKind::End: return "end";
  }
  return "unknown";
}

std::string_view trace_name(TraceReason r) {
  switch (r) {
    case TraceReason::None: return "";
    case TraceReason::Delaunay: return "delaunay";
    case TraceReason::Crossing: return "crossing";
    case TraceReason::Lawson: return "lawson";
    case TraceReason::Recovery: return "recovery";
    case TraceReason::Lifting: return "lifting";
    case TraceReason::Coarsen: return "coarsen";
    case TraceReason::Ct: return "ct";
    case TraceReason::LawsonMethod: return "lawson";
    case TraceReason::LiftingMethod: return "lifting";
    case TraceReason::Fast: return "fast";
    case TraceReason::Present: return "present";
    case TraceReason::Encroached: return "encroached";
    case TraceReason::RejectedPoint: return "rejected_point";
    case TraceReason::Conforming: return "conforming";
    case TraceReason::Circumcentre: return "circumcentre";
    case TraceReason::OffCentre: return "offcentre";
    case TraceReason::BestPoint: return "best_point";
    case TraceReason::Area: return "area";
    case TraceReason::Encroaches: return "encroaches";
    case TraceReason::Outside: return "outside";
    case TraceReason::Precision: return "precision";
    case TraceReason::Budget: return "budget";
    case TraceReason::Laplacian: return "laplacian";
    case TraceReason::Odt: return "odt";
    case TraceReason::Holes: return "holes";
    case TraceReason::Exterior: return "exterior";
  }
  return "unknown";
}

TraceObserver::TraceObserver() = default;
TraceObserver::~TraceObserver() = default;

namespace detail {

namespace {

bool real(VertexId a, VertexId b, VertexId c) { return a < kInfinite && b < kInfinite && c < kInfinite; }

// The triangle rotated to start at its smallest id (orientation kept).
TraceTriangle canonical(TraceTriangle t) {
  const int i = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
  return {t[i], t[(i + 1) % 3], t[(i + 2) % 3]};
}

std::vector<TraceTriangle> real_triangles(std::span<const VertexId> tv) {
  std::vector<TraceTriangle> out;
  for (std::size_t i = 0; i + 2 < tv.size(); i += 3)
    if (real(tv[i], tv[i + 1], tv[i + 2])) out.push_back(canonical({tv[i], tv[i + 1], tv[i + 2]}));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

void TraceAccess::slots(TraceObserver& o, TraceEvent ev, const VertexId* tv, std::span<const TriId> slots) {
  o.removed_.clear();
  o.added_.clear();
  for (TriId t : slots) {
    const std::size_t e = 3 * std::size_t{t};
    if (o.slots_.size() < e + 3) o.slots_.resize(e + 3, kNone);
    VertexId* old = &o.slots_[e];
    const VertexId* now = &tv[e];
    if (old[0] == now[0] && old[1] == now[1] && old[2] == now[2]) continue;
    if (real(old[0], old[1], old[2])) o.removed_.push_back({old[0], old[1], old[2]});
    if (real(now[0], now[1], now[2])) o.added_.push_back({now[0], now[1], now[2]});
    old[0] = now[0];
    old[1] = now[1];
    old[2] = now[2];
  }
  ev.removed = o.removed_;
  ev.added = o.added_;
  plain(o, ev);
}

void TraceAccess::plain(TraceObserver& o, const TraceEvent& ev) {
  ++o.events_;
  if (o.frame_exponent_ == 0) {
    o.on_event(ev);
    return;
  }
  // The run meshes in a power-of-two frame (algo/normalize.hpp): the
  // observer sees the user's coordinates, mapped back exactly.
  const auto back = [&](const Point& p) { return Point{std::ldexp(p.x, -o.frame_exponent_), std::ldexp(p.y, -o.frame_exponent_)}; };
  TraceEvent user = ev;
  user.point = back(ev.point);
  user.at = back(ev.at);
  o.points_.clear();
  for (const Point& p : ev.points) o.points_.push_back(back(p));
  user.points = o.points_;
  o.on_event(user);
}

void TraceAccess::flip(TraceObserver& o, TraceReason why, const VertexId* tv, const FlipQuad& q) {
  TraceEvent ev = trace_event(TraceKind::Flip, why);
  ev.edge = {tv[q.e1], tv[q.f1], tv[q.e], tv[q.f]};
  slots(o, ev, tv, {tri_of(q.e), tri_of(q.f)});
}

void TraceAccess::renumber(TraceObserver& o, std::span<const VertexId> map, std::size_t vertices) {
  for (VertexId& v : o.slots_)
    if (v < map.size()) v = map[v];
  TraceEvent ev;
  ev.kind = TraceKind::Renumber;
  ev.map = map;
  ev.count = vertices;
  plain(o, ev);
}

void TraceAccess::rewind(TraceObserver& o, std::span<const VertexId> tv, std::size_t vertices,
                         std::size_t before) {
  const std::size_t slots = std::max(tv.size(), o.slots_.size()) / 3;
  std::vector<VertexId> now(3 * slots, kNone);
  std::copy(tv.begin(), tv.end(), now.begin());
  std::vector<TriId> all(slots);
  for (std::size_t t = 0; t < slots; ++t) all[t] = static_cast<TriId>(t);
  TraceEvent ev;
  ev.kind = TraceKind::Undo;
  TraceAccess::slots(o, ev, now.data(), all);
  o.slots_.assign(tv.begin(), tv.end());
  if (before > vertices) {
    std::vector<VertexId> map(before, kNone);
    for (std::size_t v = 0; v < vertices; ++v) map[v] = static_cast<VertexId>(v);
    renumber(o, map, vertices);
  }
}

void TraceAccess::resync(TraceObserver& o, std::span<const VertexId> tv, const char* where) {
  const std::vector<TraceTriangle> told = real_triangles(o.slots_), now = real_triangles(tv);
  if (told != now) {
    std::vector<TraceTriangle> missed, stale;
    std::set_difference(now.begin(), now.end(), told.begin(), told.end(), std::back_inserter(missed));
    std::set_difference(told.begin(), told.end(), now.begin(), now.end(), std::back_inserter(stale));
    auto name = [](const std::vector<TraceTriangle>& ts) {
      if (ts.empty()) return std::string("none");
      return std::to_string(ts[0][0]) + "," + std::to_string(ts[0][1]) + "," + std::to_string(ts[0][2]);
    };
    throw InternalError(where, "the trace missed a change of the triangulation: " + std::to_string(missed.size()) +
                                   " triangles not reported (first " + name(missed) + "), " +
                                   std::to_string(stale.size()) + " reported but gone (first " + name(stale) + ")");
  }
  o.slots_.assign(tv.begin(), tv.end());
}

}  // namespace detail

// ---- JSON Lines ---------------------------------------------------------------

namespace {

void put_double(std::string& s, double x) {
  char buf[32];
  s.append(buf, chars::shortest(buf, buf + sizeof buf, x).ptr);  // shortest round-trip form
}
void put_id(std::string& s, VertexId v) {
  if (v >= kInfinite) {
    s += "-1";
    return;
  }
  char buf[16];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, r.ptr);
}
void put_point(std::string& s, const Point& p) {
  s += '[';
  put_double(s, p.x);
  s += ',';
  put_double(s, p.y);
  s += ']';
}
void put_ids(std::string& s, std::span<const VertexId> ids) {
  s += '[';
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i) s += ',';
    put_id(s, ids[i]);
  }
  s += ']';
}
void put_tris(std::string& s, const char* key, std::span<const TraceTriangle> ts) {
  s += ",\"";
  s += key;
  s += "\":[";
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (i) s += ',';
    put_ids(s, ts[i]);
  }
  s += ']';
}
void key(std::string& s, const char* k) {
  s += ",\"";
  s += k;
  s += "\":";
}

}  // namespace

JsonLinesTrace::JsonLinesTrace(Sink sink) : sink_(std::move(sink)) { buf_ = "{\"trace\":\"deltamesh\",\"version\":1}\n"; }

JsonLinesTrace::JsonLinesTrace(std::ostream& out)
    : JsonLinesTrace([&out](std::string_view s) { out.write(s.data(), static_cast<std::streamsize>(s.size())); }) {
  stream_ = true;
}

JsonLinesTrace::~JsonLinesTrace() {
  if (!stream_) return;
  try {
    finish();
  } catch (...) {  // a stream reports its own errors (its state)
  }
}

void JsonLinesTrace::finish() {
  if (buf_.empty()) return;
  sink_(buf_);
  buf_.clear();
}

void JsonLinesTrace::on_event(const TraceEvent& ev) {
  std::string& s = buf_;
  s += "{\"ev\":\"";
  s += trace_name(ev.kind);
  s += '"';
  if (ev.reason != TraceReason::None) {
    key(s, "why");
    s += '"';
    s += trace_name(ev.reason);
    s += '"';
  }
  const VertexId* e = ev.edge.data();
  switch (ev.kind) {
    case TraceKind::Phase:
      key(s, "name");
      s += '"';
      s += ev.phase;
      s += '"';
      break;
    case TraceKind::Points:
      key(s, "first");
      put_id(s, ev.vertex);
      key(s, "points");
      s += '[';
      for (std::size_t i = 0; i < ev.points.size(); ++i) {
        if (i) s += ',';
        put_point(s, ev.points[i]);
      }
      s += ']';
      break;
    case TraceKind::Flip:
      key(s, "edge");
      put_ids(s, std::span<const VertexId>(e, 2));
      key(s, "to");
      put_ids(s, std::span<const VertexId>(e + 2, 2));
      break;
    case TraceKind::Recover:
    case TraceKind::Retriangulate:
    case TraceKind::SplitSegment:
      key(s, "seg");
      put_ids(s, std::span<const VertexId>(e, 2));
      if (ev.kind == TraceKind::Recover) {
        key(s, "flips");
        s += std::to_string(ev.count);
      }
      break;
    case TraceKind::Renumber:
      key(s, "map");
      put_ids(s, ev.map);
      key(s, "vertices");
      s += std::to_string(ev.count);
      break;
    case TraceKind::End:
      key(s, "vertices");
      s += std::to_string(ev.count);
      key(s, "triangles");
      put_id(s, e[0]);
      break;
    default:
      break;
  }
  if (ev.vertex != kNone && ev.kind != TraceKind::Points) {
    key(s, "v");
    put_id(s, ev.vertex);
    key(s, "p");
    put_point(s, ev.point);
  }
  if (ev.tri[0] != kNone) {
    key(s, "tri");
    put_ids(s, ev.tri);
  }
  if (ev.other != kNone) {
    key(s, "by");
    put_id(s, ev.other);
  }
  if (ev.has_at) {
    key(s, ev.kind == TraceKind::Move ? "from" : "at");
    put_point(s, ev.at);
  }
  if (!ev.removed.empty()) put_tris(s, "del", ev.removed);
  if (!ev.added.empty()) put_tris(s, "add", ev.added);
  s += "}\n";
  if (s.size() >= (std::size_t{1} << 16)) finish();
}

}  // namespace deltamesh
