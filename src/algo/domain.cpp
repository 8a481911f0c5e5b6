// The meshing domain, decided per segment-bounded region.
//
// The real triangles of a closed constrained triangulation fall into regions:
// the connected pieces left when every constrained edge is cut. Every rule
// here is a rule about regions, so they are labelled once (O(n)) and then:
//  - Holes: a region is removed when it touches the outside of the convex
//    hull across an unconstrained hull edge (unless -c), or when a hole point
//    lies in it. This is Triangle's flood fill from the exterior and from the
//    hole points, stopping at segments.
//  - EvenOdd: a region's depth is the fewest segments crossed on a way from
//    outside the hull (a breadth-first search over the region graph); odd
//    depth is kept.
//  - Region seeds: the last seed lying in a region gives it its attribute and
//    area bound, which is what Triangle's successive floods amount to.
// The common case (Holes, no region seeds) skips the labels: one flood from
// the exterior and the hole points visits only the triangles removed.
#include "deltamesh/domain.hpp"
#include "core/plural.hpp"

#include <algorithm>
#include <cstdio>
#include <chrono>
#include <string>
#include <vector>

#include "deltamesh/predicates.hpp"
#include "mesh/trace_hooks.hpp"

namespace deltamesh {

namespace {

constexpr std::uint32_t kNoRegion = kNone;

// Regions of the real triangles: label per triangle slot (kNoRegion for
// ghost and dead slots) and the number of regions.
struct Regions {
  std::vector<std::uint32_t> label;
  std::uint32_t count = 0;
};

Regions label_regions(const Mesh& mesh) {
  Regions r;
  const std::size_t slots = mesh.num_triangle_slots();
  r.label.assign(slots, kNoRegion);
  std::vector<TriId> stack;
  for (TriId s = 0; s < slots; ++s) {
    if (r.label[s] != kNoRegion || !mesh.is_real(s)) continue;
    const std::uint32_t id = r.count++;
    r.label[s] = id;
    stack.push_back(s);
    while (!stack.empty()) {
      const TriId t = stack.back();
      stack.pop_back();
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        if (mesh.is_constrained(e)) continue;
        const HalfEdgeId f = mesh.twin(e);
        if (f == kNone) continue;
        const TriId u = tri_of(f);
        if (r.label[u] != kNoRegion || !mesh.is_real(u)) continue;
        r.label[u] = id;
        stack.push_back(u);
      }
    }
  }
  return r;
}

// The real half-edge of a ghost triangle's finite edge, seen from the real
// triangle inside the hull (kNone if the ghost is malformed).
HalfEdgeId hull_half_edge(const Mesh& mesh, TriId ghost) {
  for (HalfEdgeId e = 3 * ghost; e < 3 * ghost + 3; ++e) {
    if (mesh.origin(e) == kInfinite || mesh.dest(e) == kInfinite) continue;
    const HalfEdgeId f = mesh.twin(e);
    if (f != kNone && mesh.is_real(tri_of(f))) return f;
  }
  return kNone;
}

// The real triangle whose segment-bounded region a point selects, or kNone
// when the point lies outside the hull, on a vertex or on a segment. `hint`
// carries the last located triangle.
TriId seed_triangle(const Mesh& mesh, const Point& p, TriId& hint) {
  if (mesh.num_triangles() == 0) return kNone;
  const Location loc = mesh.locate(p, hint);
  switch (loc.kind) {
    case Location::Kind::InTriangle:
      hint = loc.tri;
      return loc.tri;
    case Location::Kind::OnEdge: {
      hint = loc.tri;
      if (mesh.is_constrained(loc.edge)) return kNone;
      // Both sides of an unconstrained edge are one region (or the far side
      // is outside the hull).
      const TriId t = tri_of(loc.edge);
      if (mesh.is_real(t)) return t;
      const HalfEdgeId f = mesh.twin(loc.edge);
      return f != kNone && mesh.is_real(tri_of(f)) ? tri_of(f) : kNone;
    }
    case Location::Kind::OnVertex:
      hint = loc.tri;
      return kNone;
    case Location::Kind::Outside:
      return kNone;
  }
  return kNone;
}

// Calls f(h) for the real half-edge h of every hull edge.
template <class F>
void for_each_hull_edge(const Mesh& mesh, F&& f) {
  const std::size_t slots = mesh.num_triangle_slots();
  for (TriId g = 0; g < slots; ++g) {
    if (mesh.is_dead(g) || !mesh.is_ghost(g)) continue;
    const HalfEdgeId h = hull_half_edge(mesh, g);
    if (h != kNone) f(h);
  }
}

// Nesting depth of every region: the fewest segments crossed from outside
// the convex hull. Regions meeting an unconstrained hull edge have depth 0,
// regions behind a constrained hull edge at most 1; each constrained edge
// between two regions adds one.
std::vector<std::uint32_t> region_depths(const Mesh& mesh, const Regions& regions) {
  constexpr std::uint32_t kUnset = kNone;
  std::vector<std::uint32_t> depth(regions.count, kUnset);
  // Constrained edges between different regions: the region graph.
  std::vector<std::uint32_t> degree(regions.count + 1, 0);
  const std::size_t slots = mesh.num_triangle_slots();
  auto neighbour_region = [&](HalfEdgeId e) -> std::uint32_t {
    const HalfEdgeId f = mesh.twin(e);
    if (f == kNone) return kNoRegion;
    return regions.label[tri_of(f)];
  };
  for (TriId t = 0; t < slots; ++t) {
    const std::uint32_t a = regions.label[t];
    if (a == kNoRegion) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (!mesh.is_constrained(e)) continue;
      const std::uint32_t b = neighbour_region(e);
      if (b != kNoRegion && b != a) ++degree[a + 1];
    }
  }
  for (std::uint32_t i = 0; i < regions.count; ++i) degree[i + 1] += degree[i];
  std::vector<std::uint32_t> adj(degree[regions.count]);
  std::vector<std::uint32_t> fill(degree.begin(), degree.end() - 1);
  for (TriId t = 0; t < slots; ++t) {
    const std::uint32_t a = regions.label[t];
    if (a == kNoRegion) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      if (!mesh.is_constrained(e)) continue;
      const std::uint32_t b = neighbour_region(e);
      if (b != kNoRegion && b != a) adj[fill[a]++] = b;
    }
  }
  // Depth 0 behind an unconstrained hull edge, else 1 behind a constrained
  // one; every later step costs one, so a FIFO queue holding the depth-0
  // regions before the depth-1 ones finds the fewest crossings.
  std::vector<std::uint32_t> queue;
  queue.reserve(regions.count);
  for (int pass = 0; pass < 2; ++pass) {
    for (TriId g = 0; g < slots; ++g) {
      if (mesh.is_dead(g) || !mesh.is_ghost(g)) continue;
      const HalfEdgeId h = hull_half_edge(mesh, g);
      if (h == kNone || mesh.is_constrained(h) != (pass == 1)) continue;
      const std::uint32_t r = regions.label[tri_of(h)];
      if (depth[r] != kUnset) continue;
      depth[r] = static_cast<std::uint32_t>(pass);
      queue.push_back(r);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t r = queue[head];
    for (std::uint32_t k = degree[r]; k < degree[r + 1]; ++k) {
      const std::uint32_t s = adj[k];
      if (depth[s] != kUnset) continue;
      depth[s] = depth[r] + 1;
      queue.push_back(s);
    }
  }
  // Regions no path reaches (impossible in a connected triangulation) count
  // as outside.
  for (std::uint32_t& d : depth)
    if (d == kUnset) d = 0;
  return depth;
}

}  // namespace

void carve_domain(Mesh& mesh, const Pslg& pslg, const DomainOptions& options, DomainStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  DomainStats local;
  DomainStats& st = stats ? *stats : local;
  st = DomainStats{};
  const std::size_t slots = mesh.num_triangle_slots();

  // -c: the hull edges become segments (before anything is removed, while
  // the ghost triangles still name them).
  if (options.keep_convex_hull) {
    for_each_hull_edge(mesh, [&](HalfEdgeId h) {
      if (mesh.is_constrained(h)) return;
      mesh.constrain_edge(h, 0);
      ++st.hull_segments_added;
    });
  }

  // Every point is located before the mesh changes.
  TriId hint = kNone;
  std::vector<TriId> hole_tris;
  if (!options.ignore_holes) {
    for (std::size_t i = 0; i < pslg.holes.size(); ++i) {
      const TriId t = seed_triangle(mesh, pslg.holes[i], hint);
      if (t == kNone) {
        ++st.holes_ignored;
        st.ignored_holes.push_back(i);
        continue;
      }
      ++st.holes_used;
      hole_tris.push_back(t);
    }
  }
  const bool use_seeds = options.regional_attributes || options.regional_area_bounds;
  std::vector<TriId> seed_tris;
  if (use_seeds)
    for (const RegionSeed& r : pslg.regions) seed_tris.push_back(seed_triangle(mesh, r.p, hint));

  // removed[t] for every triangle slot (ghost and dead slots stay 0), and
  // per triangle the region seed that applies to it (kNone: none).
  std::vector<char> removed(slots, 0);
  std::vector<std::uint32_t> seed_of_tri;
  if (options.fill == FillRule::Holes && !use_seeds) {
    // The common case needs no region labels: flood from the exterior and
    // the hole points, over unconstrained edges, touching only what goes.
    std::vector<TriId> stack;
    auto seed = [&](TriId t) {
      if (!removed[t]) {
        removed[t] = 1;
        stack.push_back(t);
      }
    };
    if (!options.keep_convex_hull)
      for_each_hull_edge(mesh, [&](HalfEdgeId h) {
        if (!mesh.is_constrained(h)) seed(tri_of(h));
      });
    for (TriId t : hole_tris) seed(t);
    while (!stack.empty()) {
      const TriId t = stack.back();
      stack.pop_back();
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        if (mesh.is_constrained(e)) continue;
        const HalfEdgeId f = mesh.twin(e);
        if (f == kNone) continue;
        const TriId u = tri_of(f);
        if (!removed[u] && mesh.is_real(u)) seed(u);
      }
    }
  } else {
    const Regions regions = label_regions(mesh);
    std::vector<char> region_removed(regions.count, 0);
    for (TriId t : hole_tris) region_removed[regions.label[t]] = 1;
    if (options.fill == FillRule::Holes) {
      if (!options.keep_convex_hull)
        for_each_hull_edge(mesh, [&](HalfEdgeId h) {
          if (!mesh.is_constrained(h)) region_removed[regions.label[tri_of(h)]] = 1;
        });
    } else {
      const std::vector<std::uint32_t> depth = region_depths(mesh, regions);
      for (std::uint32_t r = 0; r < regions.count; ++r) {
        const bool keep = depth[r] % 2 == 1 || (options.keep_convex_hull && depth[r] == 0);
        if (!keep) region_removed[r] = 1;
      }
    }
    std::vector<std::uint32_t> region_seed(regions.count, kNone);  // the last seed in each region
    for (std::size_t i = 0; i < seed_tris.size(); ++i) {
      const TriId t = seed_tris[i];
      if (t == kNone || region_removed[regions.label[t]]) {
        ++st.regions_ignored;
        st.ignored_regions.push_back(i);
        continue;
      }
      ++st.regions_used;
      region_seed[regions.label[t]] = static_cast<std::uint32_t>(i);
    }
    if (use_seeds) seed_of_tri.assign(slots, kNone);
    for (TriId t = 0; t < slots; ++t) {
      const std::uint32_t r = regions.label[t];
      if (r == kNoRegion) continue;
      removed[t] = region_removed[r];
      if (use_seeds) seed_of_tri[t] = region_seed[r];
    }
  }

  // Regional attributes are appended after any attributes the triangles
  // already carry.
  std::size_t attr_index = 0, na = 0;
  if (options.regional_attributes) {
    const std::size_t old_na = mesh.num_triangle_attributes();
    na = old_na + 1;
    attr_index = old_na;
    std::vector<double>& attrs = mesh.triangle_attributes();
    std::vector<double> wider(slots * na, 0.0);
    for (std::size_t t = 0; t < slots; ++t)
      for (std::size_t k = 0; k < old_na && t * old_na + k < attrs.size(); ++k) wider[t * na + k] = attrs[t * old_na + k];
    attrs = std::move(wider);
    mesh.set_num_triangle_attributes(na);
  }

  std::vector<TriId> carved;  // for the trace
  for (TriId t = 0; t < slots; ++t) {
    if (removed[t]) {
      mesh.remove_triangle(t);
      if (mesh.trace()) carved.push_back(t);
      ++st.triangles_removed;
      continue;
    }
    if (!use_seeds || !mesh.is_real(t) || seed_of_tri[t] == kNone) continue;
    const RegionSeed& s = pslg.regions[seed_of_tri[t]];
    if (options.regional_attributes) mesh.triangle_attributes()[std::size_t{t} * na + attr_index] = s.attribute;
    if (options.regional_area_bounds && s.max_area > 0) mesh.set_triangle_area_bound(t, s.max_area);
  }
  if (mesh.trace()) detail::trace_carved(mesh, carved);
  mesh.compact();
  st.triangles_kept = mesh.num_triangles();
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void carve_mesh(Mesh& mesh, const Pslg& pslg, const DomainOptions& options, DomainStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  DomainStats local;
  DomainStats& st = stats ? *stats : local;
  st = DomainStats{};
  if (!mesh.compacted()) mesh.compact();
  const std::size_t slots = mesh.num_triangle_slots();

  // The points to locate: holes, then region seeds.
  const bool use_seeds = options.regional_attributes || options.regional_area_bounds;
  std::vector<Point> points;
  if (!options.ignore_holes) points = pslg.holes;
  const std::size_t num_holes = points.size();
  if (use_seeds)
    for (const RegionSeed& r : pslg.regions) points.push_back(r.p);
  if (points.empty()) return;
  // Per point the triangle whose region it selects; kNone in no triangle,
  // kInfinite on a vertex or a segment.
  std::vector<TriId> where(points.size(), kNone);
  std::vector<std::uint32_t> by_x(points.size());
  for (std::uint32_t i = 0; i < by_x.size(); ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) { return points[a].x < points[b].x; });
  for (TriId t = 0; t < slots; ++t) {
    const auto v = mesh.triangle(t);
    const Point& a = mesh.point(v[0]);
    const Point& b = mesh.point(v[1]);
    const Point& c = mesh.point(v[2]);
    const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
    const double y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
    auto lo = std::lower_bound(by_x.begin(), by_x.end(), x0, [&](std::uint32_t i, double x) { return points[i].x < x; });
    for (auto it = lo; it != by_x.end() && points[*it].x <= x1; ++it) {
      const Point& p = points[*it];
      if (p.y < y0 || p.y > y1 || where[*it] != kNone) continue;
      const double o[3] = {orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p)};
      if (o[0] < 0 || o[1] < 0 || o[2] < 0) continue;
      const int zeros = (o[0] == 0) + (o[1] == 0) + (o[2] == 0);
      if (zeros == 0) {
        where[*it] = t;
      } else if (zeros >= 2) {
        where[*it] = kInfinite;  // on a vertex
      } else {
        const HalfEdgeId e = 3 * t + (o[0] == 0 ? 0 : o[1] == 0 ? 1 : 2);
        where[*it] = mesh.is_constrained(e) ? kInfinite : t;
      }
    }
  }

  // Regions, removal and seeds.
  const Regions regions = label_regions(mesh);
  std::vector<char> region_removed(regions.count, 0);
  for (std::size_t i = 0; i < num_holes; ++i) {
    if (where[i] == kNone) {
      ++st.holes_outside;
    } else if (where[i] == kInfinite) {
      ++st.holes_ignored;
      st.ignored_holes.push_back(i);
    } else {
      ++st.holes_used;
      region_removed[regions.label[where[i]]] = 1;
    }
  }
  std::vector<std::uint32_t> region_seed(regions.count, kNone);  // the last seed in each region
  for (std::size_t i = num_holes; i < points.size(); ++i) {
    const TriId t = where[i];
    if (t == kNone || t == kInfinite || region_removed[regions.label[t]]) {
      ++st.regions_ignored;
      st.ignored_regions.push_back(i - num_holes);
      continue;
    }
    ++st.regions_used;
    region_seed[regions.label[t]] = static_cast<std::uint32_t>(i - num_holes);
  }
  if (options.regional_attributes && mesh.num_triangle_attributes() == 0 && st.regions_used > 0) {
    mesh.set_num_triangle_attributes(1);
    mesh.triangle_attributes().assign(slots, 0.0);
  }
  const std::size_t na = mesh.num_triangle_attributes();
  std::vector<TriId> carved;  // for the trace
  for (TriId t = 0; t < slots; ++t) {
    const std::uint32_t r = regions.label[t];
    if (region_removed[r]) {
      mesh.remove_triangle(t);
      if (mesh.trace()) carved.push_back(t);
      ++st.triangles_removed;
      continue;
    }
    if (region_seed[r] == kNone) continue;
    const RegionSeed& s = pslg.regions[region_seed[r]];
    if (options.regional_attributes) mesh.triangle_attributes()[std::size_t{t} * na] = s.attribute;
    if (options.regional_area_bounds && s.max_area > 0) mesh.set_triangle_area_bound(t, s.max_area);
  }
  if (mesh.trace()) detail::trace_carved(mesh, carved);
  if (st.triangles_removed > 0) mesh.compact();
  st.triangles_kept = mesh.num_triangles();
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::string> check_domain_boundary(const Mesh& mesh, std::size_t max_problems) {
  std::vector<std::string> problems;
  const std::size_t slots = mesh.num_triangle_slots();
  for (TriId t = 0; t < slots && problems.size() < max_problems; ++t) {
    if (!mesh.is_real(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3 && problems.size() < max_problems; ++e) {
      const HalfEdgeId f = mesh.twin(e);
      if (f != kNone && mesh.is_real(tri_of(f))) continue;
      if (!mesh.is_constrained(e))
        problems.push_back("boundary edge " + std::to_string(mesh.origin(e)) + "-" + std::to_string(mesh.dest(e)) +
                           " of triangle " + std::to_string(t) + " is not a segment");
    }
  }
  return problems;
}

namespace {

// "hole point 2 at (0.5, 0.25)" (and "hole points 2 at (..), 4 at (..)"),
// numbered as the PSLG's file numbers them; at most 5 named.
std::string named_points(const char* one, const char* many, const std::vector<std::size_t>& ids,
                         const std::vector<Point>& at, std::size_t first_index) {
  std::string out = ids.size() == 1 ? one : many;
  for (std::size_t k = 0; k < ids.size() && k < 5; ++k) {
    char buf[96];
    const Point p = ids[k] < at.size() ? at[ids[k]] : Point{};
    std::snprintf(buf, sizeof buf, "%s %zu at (%.17g, %.17g)", k ? "," : "", ids[k] + first_index, p.x, p.y);
    out += buf;
  }
  if (ids.size() > 5) out += " and " + std::to_string(ids.size() - 5) + " more";
  return out;
}

}  // namespace

std::vector<std::string> domain_warnings(const DomainStats& stats, std::size_t triangles_left, bool existing_mesh,
                                         const Pslg* pslg) {
  std::vector<std::string> out;
  const bool name = pslg && stats.ignored_holes.size() == stats.holes_ignored;
  if (stats.holes_ignored)
    out.push_back((name ? named_points("hole point", "hole points", stats.ignored_holes, pslg->holes,
                                       static_cast<std::size_t>(pslg->first_index))
                        : count_of(stats.holes_ignored, "hole point", "hole points")) +
                  (existing_mesh ? " ignored (on a vertex or on a segment)"
                                 : " ignored (outside the convex hull, on a vertex or on a segment)"));
  if (stats.regions_ignored) {
    std::vector<Point> seeds;
    if (pslg)
      for (const RegionSeed& r : pslg->regions) seeds.push_back(r.p);
    const bool name_regions = pslg && stats.ignored_regions.size() == stats.regions_ignored;
    out.push_back((name_regions ? named_points("region point", "region points", stats.ignored_regions, seeds,
                                               static_cast<std::size_t>(pslg->first_index))
                                : count_of(stats.regions_ignored, "region point", "region points")) +
                  " ignored (outside the domain, on a vertex or on a segment)");
  }
  if (triangles_left == 0)
    out.push_back(existing_mesh ? "every triangle was removed: a hole point reaches everything"
                                : "every triangle was removed: the domain is empty (a hole point or the exterior "
                                  "reaches everything; are the segments closed around the region, or is -c needed?)");
  return out;
}

}  // namespace deltamesh
