// Refinement in parts: a domain decomposition in the spirit of PCDM
// (Chernikov & Chrisochoides, "Parallel guaranteed quality Delaunay uniform
// mesh refinement", SIAM J. Sci. Comput. 28, 2006), simplified for shared
// memory: the cuts between parts are frozen while the parts are refined
// (no Steiner point on them, as Triangle's -Y), so the parts never need to
// exchange split points; a last sequential refinement over the stitched mesh
// finishes what the frozen cuts held back, which keeps every guarantee of
// the sequential algorithm.
#include "algo/refine_parallel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "algo/refine/strip.hpp"
#include "core/parallel.hpp"
#include "mesh/canonical.hpp"
#include "mesh/editor.hpp"
#include "deltamesh/errors.hpp"
#include "mesh/legalize.hpp"

namespace deltamesh::detail {

namespace {

// The most triangles the first part's arrays are reserved for (2^27: 1.6 GB
// of address space each for their vertices and twins).
constexpr double kMaxStitchReserve = 134217728.0;

double domain_area(const Mesh& m) {
  double area = 0;
  for (TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto [a, b, c] = m.triangle(t);
    const Point &p = m.point(a), &q = m.point(b), &r = m.point(c);
    area += 0.5 * std::abs((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
  }
  return area;
}

// The parts back in one mesh: the whole mesh's vertices keep their ids, the
// parts' new vertices follow part by part; boundary half-edges are paired by
// their vertices, and the temporary segments become ordinary edges again.
// Every vertex gets its out-edge from a part (the cut vertices' may be an
// inner edge of the whole, at its boundary: the strip turns them), and
// `bad` lists the slots a part left bad, and those of segments along a cut.
Mesh stitch(const Mesh& whole, std::vector<Part>& parts, unsigned threads, std::vector<HalfEdgeId>& cut_edges,
           std::vector<std::uint8_t>& first_look, std::vector<TriId>& bad) {
  const std::size_t n0 = whole.num_vertices(), na = whole.num_vertex_attributes(),
                    ta = whole.num_triangle_attributes();
  std::vector<std::size_t> vbase(parts.size() + 1, n0), tbase(parts.size() + 1, 0);
  for (std::size_t j = 0; j < parts.size(); ++j) {
    vbase[j + 1] = vbase[j] + parts[j].mesh.num_vertices() - parts[j].global.size();
    tbase[j + 1] = tbase[j] + parts[j].mesh.num_triangle_slots();
  }
  const std::size_t nv = vbase.back(), nt = tbase.back();
  if (nt >= kNone / 3 || nv >= kInfinite) throw InputError("too many triangles: at most 1431655764 are supported");
  const bool bounds = std::any_of(parts.begin(), parts.end(), [](const Part& p) { return p.mesh.has_triangle_area_bounds(); });
  const bool markers = !whole.vertex_markers().empty() ||
                       std::any_of(parts.begin(), parts.end(), [](const Part& p) { return !p.mesh.vertex_markers().empty(); });
  Mesh out;
  MeshEditor(out).points().assign(whole.points().begin(), whole.points().end());
  MeshEditor(out).points().resize(nv);
  MeshEditor(out).out_edges().assign(nv, kNone);
  if (markers) {
    out.vertex_markers() = whole.vertex_markers();
    out.vertex_markers().resize(nv, 0);
  }
  out.set_num_vertex_attributes(na);
  out.vertex_attributes() = whole.vertex_attributes();
  out.vertex_attributes().resize(nv * na, 0.0);
  out.set_num_triangle_attributes(ta);
  out.triangle_attributes().resize(nt * ta);
  std::vector<VertexId>& tv = MeshEditor(out).triangle_vertices();
  std::vector<HalfEdgeId>& tw = MeshEditor(out).twins();
  std::vector<std::uint8_t>& fl = MeshEditor(out).edge_flags();
  std::vector<int>& mk = MeshEditor(out).edge_markers();
  const bool looks = std::all_of(parts.begin(), parts.end(), [](const Part& p) {
    return p.stage.final_bad.size() == p.mesh.num_triangle_slots();
  });
  // The first part's triangle arrays become the result's (refine_in_parts
  // reserved them for the whole mesh): its slots keep their place, only its
  // vertex ids change, and the other parts are copied behind it. A copy of
  // them cost a pass over half the mesh, and as much fresh memory.
  Mesh& first = parts[0].mesh;
  const std::size_t slots0 = tbase[1];
  const bool edge_markers = whole.has_edge_markers();  // (the parts have them when the whole has)
  const bool in_place = MeshEditor(first).edge_flags().size() == 3 * slots0 &&
                        MeshEditor(first).edge_markers().size() == (edge_markers ? 3 * slots0 : 0);
  if (in_place) {
    tv.swap(MeshEditor(first).triangle_vertices());
    tw.swap(MeshEditor(first).twins());
    fl.swap(MeshEditor(first).edge_flags());
    mk.swap(MeshEditor(first).edge_markers());
  }
  // Room for the last refinement, which adds a few percent.
  const std::size_t room = 3 * (nt + nt / 16);
  tv.reserve(room);
  tw.reserve(room);
  fl.reserve(room);
  if (edge_markers) mk.reserve(room);
  MeshEditor(out).points().reserve(nv + nv / 16);
  MeshEditor(out).out_edges().reserve(nv + nv / 16);
  // The arrays grow to the whole mesh (std::vector zero-fills what it
  // grows, and the copies overwrite all of it). With two parts, in place:
  // on the second part's thread, within the room reserved above (no
  // reallocation), while the first part's task rewrites only its own slots.
  auto grow = [&] {
    tv.resize(3 * nt);
    tw.resize(3 * nt);
    fl.resize(3 * nt, 0);
    if (edge_markers) mk.resize(3 * nt, 0);
  };
  const bool grow_in_task = in_place && parts.size() == 2;
  if (!grow_in_task) grow();
  std::vector<double> area_bounds(bounds ? nt : 0, -1.0);
  first_look.assign(looks ? nt : 0, 0);
  std::vector<std::vector<HalfEdgeId>> open(parts.size());
  std::vector<std::vector<TriId>> bad_in(parts.size());
  run_tasks(parts.size(), threads, [&](std::size_t j) {
    if (grow_in_task && j == 1) grow();
    Mesh& m = parts[j].mesh;
    const std::vector<VertexId>& global = parts[j].global;
    auto id = [&](VertexId v) {
      return v < global.size() ? global[v] : static_cast<VertexId>(vbase[j] + (v - global.size()));
    };
    for (VertexId v = static_cast<VertexId>(global.size()); v < m.num_vertices(); ++v) {
      const VertexId g = id(v);
      MeshEditor(out).points()[g] = m.point(v);
      if (const HalfEdgeId e = m.out_edge(v); e != kNone) out.set_out_edge(g, static_cast<HalfEdgeId>(3 * tbase[j] + e));
      if (markers && v < m.vertex_markers().size()) out.vertex_markers()[g] = m.vertex_markers()[v];
      if (std::size_t{v} * na + na <= m.vertex_attributes().size())
        for (std::size_t k = 0; k < na; ++k)
          out.vertex_attributes()[std::size_t{g} * na + k] = m.vertex_attributes()[std::size_t{v} * na + k];
    }
    const std::size_t base = 3 * tbase[j], slots = tbase[j + 1] - tbase[j];
    // Raw pointers and hoisted bounds: through the vectors' references the
    // compiler reloaded every one after each store (a third of this pass).
    const VertexId first_new = static_cast<VertexId>(global.size());
    const VertexId shift = static_cast<VertexId>(vbase[j] - global.size());
    const VertexId* to_global = global.data();
    VertexId* out_v = tv.data() + base;
    HalfEdgeId* out_w = tw.data() + base;
    std::vector<HalfEdgeId>& open_j = open[j];
    if (j == 0 && in_place) {
      for (HalfEdgeId e = 0; e < 3 * slots; ++e) {
        const VertexId v = out_v[e];
        out_v[e] = v < first_new ? to_global[v] : v + shift;
        if (out_w[e] == kNone) open_j.push_back(e);
      }
    } else {
      const VertexId* in_v = MeshEditor(m).triangle_vertices().data();
      const HalfEdgeId* in_w = MeshEditor(m).twins().data();
      const auto b = static_cast<HalfEdgeId>(base);
      for (HalfEdgeId e = 0; e < 3 * slots; ++e) {
        const VertexId v = in_v[e];
        out_v[e] = v < first_new ? to_global[v] : v + shift;
        if (in_w[e] == kNone) {
          out_w[e] = kNone;
          open_j.push_back(b + e);
        } else {
          out_w[e] = b + in_w[e];
        }
      }
      // (flags and markers: empty arrays read as zeros)
      if (MeshEditor(m).edge_flags().size() >= 3 * slots)
        std::copy_n(MeshEditor(m).edge_flags().data(), 3 * slots, fl.data() + base);
      if (edge_markers && MeshEditor(m).edge_markers().size() >= 3 * slots)
        std::copy_n(MeshEditor(m).edge_markers().data(), 3 * slots, mk.data() + base);
    }
    for (std::size_t k = 0; k < slots * ta; ++k)
      out.triangle_attributes()[tbase[j] * ta + k] = m.triangle_attributes()[k];
    if (bounds)
      for (TriId t = 0; t < slots; ++t) area_bounds[tbase[j] + t] = m.triangle_area_bound(static_cast<TriId>(t));
    if (looks) {
      const std::vector<std::uint8_t>& fb = parts[j].stage.final_bad;
      std::copy(fb.begin(), fb.end(), first_look.begin() + tbase[j]);
      for (TriId t = 0; t < fb.size(); ++t)
        if (fb[t]) bad_in[j].push_back(static_cast<TriId>(tbase[j] + t));
    }
  });
  // The vertices the parts started with, some in several parts: in part order.
  for (std::size_t j = 0; j < parts.size(); ++j) {
    const Mesh& m = parts[j].mesh;
    for (VertexId v = 0; v < parts[j].global.size(); ++v)
      if (const HalfEdgeId e = m.out_edge(v); e != kNone)
        out.set_out_edge(parts[j].global[v], static_cast<HalfEdgeId>(3 * tbase[j] + e));
  }
  for (const auto& list : bad_in) bad.insert(bad.end(), list.begin(), list.end());
  std::unordered_set<std::uint64_t> cuts;
  std::unordered_map<std::uint64_t, HalfEdgeId> by_vertices;
  for (const Part& p : parts) cuts.insert(p.cuts.begin(), p.cuts.end());
  for (const auto& list : open)
    for (HalfEdgeId h : list) by_vertices.emplace(directed_key(tv[h], tv[next_edge(h)]), h);
  for (const auto& list : open)
    for (HalfEdgeId h : list) {
      const VertexId a = tv[h], b = tv[next_edge(h)];
      const auto it = by_vertices.find(directed_key(b, a));
      if (it == by_vertices.end()) {
        if (cuts.count(directed_key(a, b)) || cuts.count(directed_key(b, a)))
          throw InternalError("refine_in_parts", "a cut lost its other side");
        continue;
      }
      tw[h] = it->second;
      fl[h] &= static_cast<std::uint8_t>(~kFrozenEdge);
      if (cuts.count(directed_key(a, b)) || cuts.count(directed_key(b, a))) {
        fl[h] &= static_cast<std::uint8_t>(~kConstrained);
        if (edge_markers) mk[h] = 0;
        cut_edges.push_back(h);
      } else if (looks) {
        bad.push_back(tri_of(h));  // a segment along a cut, frozen in both parts: maybe encroached across it
      }
    }
  for (Part& p : parts) p.mesh = Mesh{};
  if (bounds)
    for (TriId t = 0; t < nt; ++t) out.set_triangle_area_bound(t, area_bounds[t]);
  // The parts are compacted (no dead or ghost slot), so is their union, once
  // the strip has turned the cut vertices' out-edges (the whole-mesh pass
  // sets them all from scratch; Mesh::compact() here cost a whole-mesh pass
  // on one thread).
  MeshEditor(out).set_live_real(nt);
  MeshEditor(out).set_compacted();
  return out;
}

}  // namespace

std::optional<RefineStats> refine_in_parts(Mesh& mesh, const RefineOptions& options, unsigned parts,
                                           LastPassReport* report) {
  const unsigned threads = resolve_threads(options.threads);
  if (threads < 2 || !(options.max_area > 0) || options.max_area_at || options.max_edge_at ||
      options.max_steiner != kAutomaticBudget || options.time_limit_seconds > 0 || options.conforming_delaunay ||
      options.min_angle_deg > kAutomaticBudgetAngle || mesh.num_triangles() == 0 || mesh.trace() != nullptr)  // traced: the sequential run
    return std::nullopt;
  const auto t0 = std::chrono::steady_clock::now();
  if (!mesh.compacted()) mesh.compact();
  // The coarse stage starts, as refine() does, from slots in an order of
  // the triangulation's own, so that scaling the input by 10^k gives the
  // same mesh; the later stages inherit their order from it.
  canonical_triangle_order(mesh);
  // A refined mesh's triangles average about half the area bound.
  const double expected = domain_area(mesh) / (0.5 * options.max_area);
  if (parts == 0)
    parts = static_cast<unsigned>(std::min<double>(threads, std::floor(expected / double(kMinTrianglesPerPart))));
  if (parts < 2) return std::nullopt;
  const std::size_t input_vertices = mesh.num_vertices();

  RefineOptions one = options;
  one.threads = 1;
  one.progress = {};
  RefineOptions coarse = one;
  coarse.max_area = options.max_area * kCoarseAreaFactor;
  // The area bound alone: the cut needs small triangles, not good ones. With
  // the angle bound the coarse stage did the grading along fine boundaries,
  // most of the work there (2.5 of 5 s on the smooth 100k-gon at q33), on one
  // thread; the parts grade them concurrently instead. (A coarse stage at 20
  // degrees left 3-4% more triangles at q33 next to fine boundaries.)
  coarse.min_angle_deg = 0;
  RefineStats total = refine_scanning(mesh, coarse, threads);
  const bool cut = total.complete;  // else the coarse stage met a limit: finish sequentially
  RefineStage last_stage;

  if (cut) {
    // Slabs by centroid x, at quantiles of the triangles' centroids.
    const std::size_t slots = mesh.num_triangle_slots();
    std::vector<double> cx(slots);
    for (TriId t = 0; t < slots; ++t) {
      const auto [a, b, c] = mesh.triangle(t);
      cx[t] = (mesh.point(a).x + mesh.point(b).x + mesh.point(c).x) / 3;
    }
    std::vector<double> sorted = cx;
    std::vector<double> bounds;
    for (unsigned j = 1; j < parts; ++j) {
      const std::size_t k = j * slots / parts;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
      bounds.push_back(sorted[k]);
    }
    std::sort(bounds.begin(), bounds.end());
    std::vector<std::uint32_t> slab(slots);
    std::vector<TriId> index(slots);
    std::vector<TriId> count(parts, 0);
    for (TriId t = 0; t < slots; ++t) {
      slab[t] = static_cast<std::uint32_t>(std::upper_bound(bounds.begin(), bounds.end(), cx[t]) - bounds.begin());
      index[t] = count[slab[t]]++;
    }
    std::vector<Part> pieces(parts);
    run_tasks(parts, threads, [&](std::size_t j) {
      std::vector<TriId> tris;
      for (TriId t = 0; t < slots; ++t)
        if (slab[t] == j) tris.push_back(t);
      cut_part(mesh, tris, [&](TriId t) { return slab[t] == j ? index[t] : kNone; }, pieces[j]);
      Part& p = pieces[j];
      if (p.mesh.num_triangles() == 0) return;
      // refine() on one thread (the part is compact and within the
      // predicates' range, as the whole is), keeping its final verdicts.
      canonical_triangle_order(p.mesh);
      if (j == 0) {  // its arrays become the stitched mesh's: room for all (address space, not memory, until used)
        // At most kMaxStitchReserve triangles: beyond, the stitch grows the
        // arrays (a copy, as before). Without the room (no address space)
        // it does the same.
        const double want = std::min(1.5 * expected, kMaxStitchReserve) + double(mesh.num_triangle_slots()) + 1024;
        const auto all = 3 * static_cast<std::size_t>(want);
        try {
          MeshEditor(p.mesh).triangle_vertices().reserve(all);
          MeshEditor(p.mesh).twins().reserve(all);
          MeshEditor(p.mesh).edge_flags().reserve(all);
          if (mesh.has_edge_markers()) MeshEditor(p.mesh).edge_markers().reserve(all);
        } catch (const std::bad_alloc&) {  // (the part refines as it would have, without the room)
        }
      }
      p.stage.keep_final_bad = true;
      p.stats = refine_scanning(p.mesh, one, 1, &p.stage);
    });
    bool strip = true;  // the last pass on a strip around the cuts (strip.cpp), unless a part was stopped
    for (const Part& p : pieces) {
      add_counts(total, p.stats);
      strip = strip && !p.stats.budget_exhausted && !p.stats.time_exhausted && !p.stats.stalled;
    }
    std::vector<HalfEdgeId> cut_edges;
    std::vector<TriId> seeds;  // the parts' bad triangles, the cuts' and the flipped ones
    mesh = stitch(mesh, pieces, threads, cut_edges, last_stage.first_look, seeds);
    for (HalfEdgeId h : cut_edges) {
      seeds.push_back(tri_of(h));
      seeds.push_back(tri_of(mesh.twin(h)));
    }
    // Each part is a constrained Delaunay triangulation: only edges whose
    // triangles come from different parts (the cuts) can fail the
    // empty-circle test, and then the edges their flips make.
    const std::size_t flips_from = seeds.size();
    NotingTopology topo(mesh, seeds);
    constrained_lawson(topo, cut_edges);
    if (!last_stage.first_look.empty())
      for (std::size_t i = flips_from; i < seeds.size(); ++i) last_stage.first_look[seeds[i]] = kLookAgain;
    last_stage.reserve = false;  // the stitch has
    // (Without the parts' verdicts, the strip would not know their bad triangles.)
    if (report && report->strip == LastPassReport::Strip::Never) strip = false;
    if (strip && !last_stage.first_look.empty()) {
      RefineStats on_strip;
      std::size_t strip_triangles = 0;
      const bool refuse = report && report->strip == LastPassReport::Strip::Refuse;
      const bool kept = refine_strip(mesh, one, seeds, last_stage.first_look, on_strip, strip_triangles, refuse);
      if (report) {
        report->strip_kept = kept;
        report->strip_triangles = strip_triangles;
      }
      if (kept) {
        add_counts(on_strip, total);
        on_strip.input_vertices = input_vertices;
        on_strip.steiner_points = mesh.num_vertices() - input_vertices;
        on_strip.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return on_strip;
      }
      add_counts(total, on_strip);
    }
  }
  one.progress = options.progress;
  RefineStats last = refine_scanning(mesh, one, threads, &last_stage);
  add_counts(last, total);
  last.input_vertices = input_vertices;
  last.steiner_points = mesh.num_vertices() - input_vertices;
  last.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return last;
}

}  // namespace deltamesh::detail
