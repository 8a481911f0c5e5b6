// GeoJSON (RFC 7946) polygons as a PSLG for even-odd meshing.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "deltamesh/formats.hpp"
#include "deltamesh/predicates.hpp"
#include "io/geojson_json.hpp"
#include "io/text_reader.hpp"

namespace deltamesh {

namespace {

using io::Json;
using Id = Json::Id;
using Kind = Json::Kind;

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Open-addressing hash tables (linear probing, power-of-two capacity): the
// reader looks up every position and every ring edge, and node-based
// std::unordered_* spent most of its time chasing pointers.
class PointIndex {
 public:
  // The id stored for key (x, y), or `fresh` (which is then stored).
  VertexId find_or_insert(std::uint64_t x, std::uint64_t y, VertexId fresh, bool& inserted) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    std::size_t i = hash(x, y) & (slots_.size() - 1);
    while (slots_[i].id != kNone) {
      if (slots_[i].x == x && slots_[i].y == y) {
        inserted = false;
        return slots_[i].id;
      }
      i = (i + 1) & (slots_.size() - 1);
    }
    slots_[i] = {x, y, fresh};
    ++size_;
    inserted = true;
    return fresh;
  }

 private:
  struct Slot {
    std::uint64_t x = 0, y = 0;
    VertexId id = kNone;
  };
  static std::size_t hash(std::uint64_t x, std::uint64_t y) {
    return static_cast<std::size_t>(mix(x ^ mix(y + 0x9e3779b97f4a7c15ull)));
  }
  void grow() {
    std::vector<Slot> old(std::max<std::size_t>(64, 2 * slots_.size()));
    old.swap(slots_);
    for (const Slot& s : old) {
      if (s.id == kNone) continue;
      std::size_t i = hash(s.x, s.y) & (slots_.size() - 1);
      while (slots_[i].id != kNone) i = (i + 1) & (slots_.size() - 1);
      slots_[i] = s;
    }
  }
  std::vector<Slot> slots_;
  std::size_t size_ = 0;
};

// A set of undirected edges (vertex pairs).
class EdgeSet {
 public:
  // True when the edge was not in the set yet.
  bool insert(VertexId a, VertexId b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (std::uint64_t{a} << 32) | b;  // never kEmpty: a <= b < kNone
    if (2 * (size_ + 1) > slots_.size()) grow();
    std::size_t i = static_cast<std::size_t>(mix(key)) & (slots_.size() - 1);
    while (slots_[i] != kEmpty) {
      if (slots_[i] == key) return false;
      i = (i + 1) & (slots_.size() - 1);
    }
    slots_[i] = key;
    ++size_;
    return true;
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  void grow() {
    std::vector<std::uint64_t> old(std::max<std::size_t>(64, 2 * slots_.size()), kEmpty);
    old.swap(slots_);
    for (const std::uint64_t k : old) {
      if (k == kEmpty) continue;
      std::size_t i = static_cast<std::size_t>(mix(k)) & (slots_.size() - 1);
      while (slots_[i] != kEmpty) i = (i + 1) & (slots_.size() - 1);
      slots_[i] = k;
    }
  }
  std::vector<std::uint64_t> slots_;
  std::size_t size_ = 0;
};

std::uint64_t bits_of(double v) {
  if (v == 0.0) v = 0.0;  // -0 and +0 are one coordinate
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// A polygon as rings of points (first = outer), after cleaning.
using Ring = std::vector<Point>;

// Is p strictly inside the polygon (even-odd over all rings), exactly? false
// when p lies on an edge.
bool strictly_inside(const std::vector<Ring>& rings, const Point& p) {
  bool inside = false;
  for (const Ring& r : rings) {
    const std::size_t n = r.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Point& a = r[j];
      const Point& b = r[i];
      // On the edge?
      if (orient2d(a, b, p) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
          std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
        return false;
      // Half-open rule on y; crossing to the right of p decided exactly.
      if ((a.y > p.y) != (b.y > p.y)) {
        const double o = orient2d(a, b, p);
        // Upward edge (a below b): p left of it means the crossing is to the right.
        if ((b.y > a.y) ? o > 0.0 : o < 0.0) inside = !inside;
      }
    }
  }
  return inside;
}

// An interior point of a polygon with holes (see formats.hpp), or false.
bool interior_point(const std::vector<Ring>& rings, Point& out) {
  std::vector<double> ys;
  for (const Ring& r : rings)
    for (const Point& p : r) ys.push_back(p.y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  if (ys.size() < 2) return false;
  // Candidate scanlines: the middles of the tallest gaps between distinct
  // vertex heights (no vertex lies on them).
  std::vector<std::size_t> gaps(ys.size() - 1);
  for (std::size_t i = 0; i < gaps.size(); ++i) gaps[i] = i;
  const std::size_t tries = std::min<std::size_t>(gaps.size(), 24);
  std::partial_sort(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(tries), gaps.end(),
                    [&](std::size_t a, std::size_t b) { return ys[a + 1] - ys[a] > ys[b + 1] - ys[b]; });
  struct Candidate {
    Point p;
    double score;
  };
  std::vector<Candidate> found;
  std::vector<double> xs;
  for (std::size_t g = 0; g < tries; ++g) {
    const std::size_t i = gaps[g];
    const double y = ys[i] + 0.5 * (ys[i + 1] - ys[i]);
    if (!(y > ys[i] && y < ys[i + 1])) continue;  // adjacent doubles: no room
    xs.clear();
    for (const Ring& r : rings) {
      const std::size_t n = r.size();
      for (std::size_t a = 0, b = n - 1; a < n; b = a++) {
        const Point &p = r[a], &q = r[b];
        if ((p.y < y) == (q.y < y)) continue;
        xs.push_back(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
      }
    }
    if (xs.size() < 2 || xs.size() % 2 != 0) continue;
    std::sort(xs.begin(), xs.end());
    double best = -1.0;
    double mid = 0.0;
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      const double w = xs[k + 1] - xs[k];
      if (w > best) {
        best = w;
        mid = xs[k] + 0.5 * w;
      }
    }
    if (best <= 0.0) continue;
    found.push_back({{mid, y}, std::min(best, ys[i + 1] - ys[i])});
  }
  std::sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  for (const Candidate& c : found)
    if (strictly_inside(rings, c.p)) {
      out = c.p;
      return true;
    }
  return false;
}

class Reader {
 public:
  Reader(const Json& json, const GeoJsonReadOptions& opt, GeoJsonInfo& info) : j_(json), opt_(opt), info_(info) {}

  Pslg run() {
    const Id root = j_.root();
    if (j_.kind(root) != Kind::Object)
      j_.fail(root, std::string("expected a GeoJSON object, found ") + Json::describe(j_.kind(root)));
    object(root, Json::kNoNode);
    return std::move(pslg_);
  }

 private:
  std::string type_of(Id obj) {
    const Id t = j_.member(obj, "type");
    if (t == Json::kNoNode) j_.fail(obj, "GeoJSON object without a \"type\" member");
    if (j_.kind(t) != Kind::String)
      j_.fail(t, std::string("\"type\" must be a string, found ") + Json::describe(j_.kind(t)));
    return std::string(j_.string(t));
  }

  Id require(Id obj, const char* key, const std::string& type) {
    const Id v = j_.member(obj, key);
    if (v == Json::kNoNode) j_.fail(obj, type + " without \"" + key + "\"");
    return v;
  }

  void require_array(Id v, const std::string& what) {
    if (!j_.is_array(v)) j_.fail(v, what + " must be an array, found " + Json::describe(j_.kind(v)));
  }

  // Any GeoJSON object; `feature` is the enclosing Feature (for properties).
  void object(Id obj, Id feature) {
    const std::string type = type_of(obj);
    if (type == "FeatureCollection") {
      const Id features = require(obj, "features", type);
      require_array(features, "\"features\"");
      if (j_.kind(features) == Kind::NumberArray) j_.fail(features, "\"features\" must hold Feature objects");
      for (std::size_t i = 0; i < j_.size(features); ++i) {
        const Id f = j_.item(features, i);
        if (j_.kind(f) != Kind::Object)
          j_.fail(f, std::string("a feature must be an object, found ") + Json::describe(j_.kind(f)));
        if (type_of(f) != "Feature") j_.fail(f, "\"features\" holds a \"" + type_of(f) + "\", not a \"Feature\"");
        object(f, f);
      }
    } else if (type == "Feature") {
      ++info_.features;
      const Id geometry = require(obj, "geometry", type);
      if (j_.kind(geometry) == Kind::Null) {
        ++info_.skipped_geometries;
        return;
      }
      if (j_.kind(geometry) != Kind::Object)
        j_.fail(geometry, std::string("\"geometry\" must be an object or null, found ") +
                              Json::describe(j_.kind(geometry)));
      object(geometry, obj);
    } else if (type == "GeometryCollection") {
      const Id geometries = require(obj, "geometries", type);
      require_array(geometries, "\"geometries\"");
      if (j_.kind(geometries) == Kind::NumberArray) j_.fail(geometries, "\"geometries\" must hold geometry objects");
      for (std::size_t i = 0; i < j_.size(geometries); ++i) {
        const Id g = j_.item(geometries, i);
        if (j_.kind(g) != Kind::Object)
          j_.fail(g, std::string("a geometry must be an object, found ") + Json::describe(j_.kind(g)));
        object(g, feature);
      }
    } else if (type == "Polygon") {
      const Id coords = require(obj, "coordinates", type);
      polygon(coords, feature);
    } else if (type == "MultiPolygon") {
      const Id coords = require(obj, "coordinates", type);
      require_array(coords, "MultiPolygon \"coordinates\"");
      if (j_.kind(coords) == Kind::NumberArray) j_.fail(coords, "MultiPolygon \"coordinates\" must hold polygons");
      for (std::size_t i = 0; i < j_.size(coords); ++i) polygon(j_.item(coords, i), feature);
    } else if (type == "Point" || type == "MultiPoint" || type == "LineString" || type == "MultiLineString") {
      ++info_.skipped_geometries;
    } else {
      j_.fail(obj, "unknown GeoJSON type \"" + type + "\"");
    }
  }

  // The property `name` of a feature, or kNoNode.
  Id property(Id feature, const std::string& name) {
    if (name.empty() || feature == Json::kNoNode) return Json::kNoNode;
    const Id props = j_.member(feature, "properties");
    if (props == Json::kNoNode || j_.kind(props) != Kind::Object) return Json::kNoNode;
    const Id v = j_.member(props, name);
    return v == Json::kNoNode || j_.kind(v) == Kind::Null ? Json::kNoNode : v;
  }

  VertexId vertex(const Point& p) {
    bool inserted = false;
    const VertexId id =
        index_.find_or_insert(bits_of(p.x), bits_of(p.y), static_cast<VertexId>(pslg_.points.size()), inserted);
    if (inserted) {
      if (pslg_.points.size() >= kNone - 1) j_.fail_at(0, "too many distinct positions");
      pslg_.points.push_back({p.x == 0.0 ? 0.0 : p.x, p.y == 0.0 ? 0.0 : p.y});
    } else {
      ++info_.duplicate_points;
    }
    return id;
  }

  void polygon(Id coords, Id feature) {
    require_array(coords, "Polygon \"coordinates\"");
    if (j_.kind(coords) == Kind::NumberArray)
      j_.fail(coords, "Polygon \"coordinates\" must be an array of rings (arrays of positions)");
    ++info_.polygons;
    int marker_override = 0;
    bool has_marker = false;
    if (const Id m = property(feature, opt_.marker_property); m != Json::kNoNode) {
      if (j_.kind(m) != Kind::Number || j_.number(m) != std::floor(j_.number(m)) || std::fabs(j_.number(m)) > 2e9)
        j_.fail(m, "property \"" + opt_.marker_property + "\" must be an integer to be a boundary marker");
      marker_override = static_cast<int>(j_.number(m));
      has_marker = true;
    }
    const bool has_attribute = property(feature, opt_.attribute_property) != Json::kNoNode;
    const bool has_area = property(feature, opt_.area_property) != Json::kNoNode;
    info_.polygons_with_attribute += has_attribute;
    info_.polygons_with_area += has_area;
    const bool want_seed = has_attribute || has_area;
    std::vector<Ring> rings;
    for (std::size_t r = 0; r < j_.size(coords); ++r) {
      const Id ring = j_.item(coords, r);
      require_array(ring, "a linear ring");
      if (j_.kind(ring) == Kind::NumberArray) j_.fail(ring, "a linear ring must be an array of positions");
      const std::size_t n = j_.size(ring);
      std::vector<VertexId>& ids = ids_;
      std::vector<Point>& pts = pts_;
      ids.clear();
      pts.clear();
      for (std::size_t i = 0; i < n; ++i) {
        const Id pos = j_.item(ring, i);
        if (j_.kind(pos) != Kind::NumberArray || j_.count(pos) < 2)
          j_.fail(pos, "a position must be an array of 2 or 3 numbers");
        const double* xy = j_.numbers(pos);
        const Point p{xy[0], xy[1]};
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) j_.fail(pos, "coordinates must be finite");
        pts.push_back(p);
      }
      if (pts.size() >= 2 && pts.front() == pts.back()) {
        pts.pop_back();
      } else if (!pts.empty()) {
        ++info_.unclosed_rings;
      }
      for (const Point& p : pts) {
        const VertexId v = vertex(p);
        if (ids.empty() || ids.back() != v) ids.push_back(v);
      }
      while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
      // Fewer than 3 distinct vertices enclose nothing.
      std::vector<VertexId>& distinct = distinct_;
      distinct.assign(ids.begin(), ids.end());
      std::sort(distinct.begin(), distinct.end());
      distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
      if (distinct.size() < 3) {
        ++info_.degenerate_rings;
        continue;
      }
      ++info_.rings;
      const bool hole = r > 0;
      info_.holes += hole;
      const int marker = has_marker ? marker_override : (hole ? opt_.hole_marker : opt_.outer_marker);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const VertexId a = ids[i], b = ids[(i + 1) % ids.size()];
        if (!segments_.insert(a, b)) {
          ++info_.duplicate_segments;
          continue;
        }
        pslg_.segments.push_back({a, b, marker});
      }
      if (!want_seed) continue;
      Ring cleaned;
      for (const VertexId v : ids) cleaned.push_back(pslg_.points[v]);
      rings.push_back(std::move(cleaned));
    }
    if (want_seed) seed(rings, feature);
  }

  void seed(const std::vector<Ring>& rings, Id feature) {
    const Id attr = property(feature, opt_.attribute_property);
    const Id area = property(feature, opt_.area_property);
    if (attr == Json::kNoNode && area == Json::kNoNode) return;
    RegionSeed s;
    if (attr != Json::kNoNode) {
      switch (j_.kind(attr)) {
        case Kind::Number: s.attribute = j_.number(attr); break;
        case Kind::True: s.attribute = 1.0; break;
        case Kind::False: s.attribute = 0.0; break;
        case Kind::String: {
          const std::string v(j_.string(attr));
          auto it = std::find(info_.categories.begin(), info_.categories.end(), v);
          if (it == info_.categories.end()) {
            info_.categories.push_back(v);
            it = info_.categories.end() - 1;
          }
          s.attribute = static_cast<double>(it - info_.categories.begin() + 1);
          break;
        }
        default:
          j_.fail(attr, "property \"" + opt_.attribute_property + "\" must be a number, a boolean or a string, found " +
                            Json::describe(j_.kind(attr)));
      }
    }
    if (area != Json::kNoNode) {
      if (j_.kind(area) != Kind::Number)
        j_.fail(area, "property \"" + opt_.area_property + "\" must be a number (a maximum triangle area)");
      s.max_area = j_.number(area) > 0.0 ? j_.number(area) : -1.0;
    }
    if (rings.empty() || !interior_point(rings, s.p)) {
      ++info_.seeds_failed;
      return;
    }
    pslg_.regions.push_back(s);
    ++info_.seeds;
  }

  const Json& j_;
  const GeoJsonReadOptions& opt_;
  GeoJsonInfo& info_;
  Pslg pslg_;
  PointIndex index_;
  EdgeSet segments_;
  std::vector<VertexId> ids_, distinct_;  // per-ring scratch
  std::vector<Point> pts_;
};

}  // namespace

Pslg parse_geojson(std::string_view text, const std::string& name, const GeoJsonReadOptions& options,
                   GeoJsonInfo* info) {
  const io::Json json(text, name);
  GeoJsonInfo local;
  GeoJsonInfo& out = info ? *info : local;
  out = GeoJsonInfo{};
  return Reader(json, options, out).run();
}

Pslg read_geojson(const std::string& path, const GeoJsonReadOptions& options, GeoJsonInfo* info) {
  const std::string text = io::read_whole_file(path);
  return parse_geojson(text, path, options, info);
}

}  // namespace deltamesh
