// libFuzzer target: random bytes -> a small PSLG -> triangulate (carved or
// with its convex hull, maybe with a hole; a CDT or a Ct triangulation) ->
// insert_segments with a few more segments (vertex id pairs) -> check;
// then maybe make_constrained_delaunay and a small refinement -> check again.
//
// A bug is: a crash or sanitizer report; an exception that is not one of the
// library's typed errors, or an InternalError (a broken invariant);
// after a successful insertion, a mesh the validator rejects, an input
// vertex moved, a given segment or an edge constrained before not present as
// a chain of constrained edges, an edge that is not locally Delaunay (the
// input is a CDT, which the header says stays one), a boundary that stopped
// being convex when it was, stats that do not add up; after a SegmentError
// or InputError, a mesh that changed (the header: "nothing is changed").
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/insert_segments.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"
#include "fuzz_util.hpp"
#include "pslg_bytes.hpp"

namespace dm = deltamesh;
namespace fz = deltamesh::fuzz;

namespace {

constexpr std::size_t kMaxPoints = 24;
constexpr std::size_t kMaxSegments = 12;
constexpr std::size_t kMaxNewSegments = 6;

// Everything insert_segments may change.
struct Snapshot {
  std::vector<dm::Point> points;
  std::vector<dm::VertexId> tri_v;
  std::vector<std::uint8_t> flags;
  std::vector<int> markers;
  std::size_t triangles = 0;

  explicit Snapshot(const dm::Mesh& m)
      : points(m.points().begin(), m.points().end()),
        tri_v(m.triangle_vertices().begin(), m.triangle_vertices().end()),
        triangles(m.num_triangles()) {
    for (dm::HalfEdgeId e = 0; e < 3 * m.num_triangle_slots(); ++e) {
      flags.push_back(m.edge_flags(e));
      markers.push_back(m.edge_marker(e));
    }
  }
  bool operator==(const Snapshot&) const = default;
};

std::string seg_list(const std::vector<dm::Segment>& s) {
  std::string r;
  for (const dm::Segment& x : s) r += " " + std::to_string(x.a) + "-" + std::to_string(x.b);
  return r;
}

void check(const dm::Mesh& mesh, const dm::Pslg& must_have, bool delaunay, bool convex, const Snapshot& before,
           const std::string& stage) {
  dm::CheckOptions co;
  co.delaunay = delaunay;
  co.convex_hull = convex;
  co.pslg = &must_have;
  const dm::CheckReport rep = dm::check(mesh, co);
  if (!rep.ok()) fz::fail(stage + ": the validator rejects the mesh (segments" + seg_list(must_have.segments) + "): " +
                          rep.summary());
  DELTAMESH_FUZZ_CHECK(mesh.num_vertices() >= before.points.size(), stage);
  for (std::size_t i = 0; i < before.points.size(); ++i)
    DELTAMESH_FUZZ_CHECK(mesh.point(static_cast<dm::VertexId>(i)) == before.points[i],
                         stage + ": vertex " + std::to_string(i) + " moved");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::uint8_t f1 = in.ConsumeIntegral<std::uint8_t>();
  const std::uint8_t f2 = in.ConsumeIntegral<std::uint8_t>();
  fz::Coords cm;
  cm.init(in);

  dm::Pslg g;
  const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(3, kMaxPoints);
  const std::size_t m = in.ConsumeIntegralInRange<std::size_t>(0, kMaxSegments);
  const std::size_t k = in.ConsumeIntegralInRange<std::size_t>(1, kMaxNewSegments);
  // The first segments close the polygon 0-1-...-(c-1), so that carving
  // keeps something; the rest join random vertices.
  fz::read_pslg(in, cm, n, m, (f1 & 1) != 0, (f1 & 2) != 0, g);

  static const bool verbose = std::getenv("DELTAMESH_FUZZ_VERBOSE") != nullptr;
  if (verbose)  // the PSLG as a .poly (a regression input by copying it)
    std::fprintf(stderr, "--- input.poly:\n%s--- end\n", fz::to_poly(g).c_str());
  dm::TriangulateOptions topt;
  topt.domain.keep_convex_hull = (f1 & 4) != 0;
  // Ct: a constrained triangulation that need not be Delaunay, like a mesh
  // read from files (the header allows any valid mesh).
  const bool input_cdt = (f1 & 64) == 0;
  if (!input_cdt) topt.method = dm::CdtMethod::Ct;
  dm::Mesh mesh;
  if (!fz::triangulate_or_stop(g, topt, mesh)) return 0;
  // -c without a hole: the mesh is its convex hull, and stays so.
  const bool convex = topt.domain.keep_convex_hull && g.holes.empty();

  // New segments: vertex ids of the mesh, sometimes one past the end.
  const auto nv = static_cast<dm::VertexId>(mesh.num_vertices());
  std::vector<dm::Segment> extra;
  for (std::size_t i = 0; i < k; ++i) {
    dm::Segment s;
    s.a = in.ConsumeIntegralInRange<dm::VertexId>(0, nv);
    s.b = in.ConsumeIntegralInRange<dm::VertexId>(0, nv - 1);
    s.marker = in.ConsumeIntegralInRange<int>(0, 5);
    extra.push_back(s);
  }

  dm::InsertSegmentsOptions iopt;
  static constexpr dm::CdtMethod kMethods[] = {dm::CdtMethod::Fast, dm::CdtMethod::Ct, dm::CdtMethod::Lawson,
                                               dm::CdtMethod::Lifting};
  iopt.method = kMethods[f2 & 3];
  iopt.strict = (f2 & 4) != 0;
  iopt.delaunay = (f2 & 8) == 0;

  // What must be there afterwards: the edges constrained before (chains, if
  // a crossing split them) and the new segments.
  dm::Pslg must;
  for (dm::TriId t = 0; t < mesh.num_triangle_slots(); ++t) {
    if (!mesh.is_real(t)) continue;
    for (dm::HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e)
      if (mesh.is_constrained(e) && mesh.origin(e) < mesh.dest(e)) must.segments.push_back({mesh.origin(e), mesh.dest(e), 0});
  }
  for (const dm::Segment& s : extra) must.segments.push_back(s);

  if (verbose) {
    std::fprintf(stderr, "--- mesh: %zu vertices, %zu triangles; insert%s method=%s strict=%d delaunay=%d\n",
                 mesh.num_vertices(), mesh.num_triangles(), seg_list(extra).c_str(),
                 std::string(dm::to_string(iopt.method)).c_str(), iopt.strict, iopt.delaunay);
    for (dm::VertexId v = 0; v < nv; ++v)
      std::fprintf(stderr, "  v%u %.17g %.17g\n", static_cast<unsigned>(v), mesh.point(v).x, mesh.point(v).y);
  }

  const Snapshot before(mesh);
  {
    // The input itself (triangulate is fuzz_mesh's business, but a bug there
    // must not be blamed on insert_segments).
    dm::Pslg none;
    check(mesh, none, input_cdt, convex, before, "triangulate");
  }
  dm::InsertSegmentsStats st;
  try {
    dm::insert_segments(mesh, extra, iopt, &st);
  } catch (const dm::InputError& e) {  // SegmentError, IntersectingSegments among them
    if (verbose) std::fprintf(stderr, "--- insert_segments threw: %s\n", e.what());
    if (!(Snapshot(mesh) == before))
      fz::fail(std::string("insert_segments threw '") + e.what() + "' but changed the mesh (segments" +
               seg_list(extra) + ")");
    return 0;
  } catch (...) {
    fz::unexpected_exception("insert_segments");
  }
  if (verbose)
    std::fprintf(stderr, "--- inserted: already=%zu inserted=%zu zero=%zu added=%zu flips=%zu\n", st.already_present,
                 st.inserted, st.zero_length, st.vertices_added, st.flips);

  must.points.assign(mesh.points().begin(), mesh.points().end());
  // A CDT stays one with or without the final flips (header), unless the
  // recovery is Ct, which is not always Delaunay.
  const bool delaunay = iopt.delaunay || (input_cdt && iopt.method != dm::CdtMethod::Ct);
  check(mesh, must, delaunay, convex, before, "insert_segments");
  DELTAMESH_FUZZ_CHECK(st.segments == extra.size(), "stats.segments");
  DELTAMESH_FUZZ_CHECK(st.zero_length + st.already_present + st.inserted <= st.segments, "stats add up");
  DELTAMESH_FUZZ_CHECK(mesh.num_vertices() == before.points.size() + st.vertices_added, "stats.vertices_added");
  DELTAMESH_FUZZ_CHECK(!iopt.strict || st.vertices_added == 0, "strict insertion added vertices");

  const std::size_t flips = dm::make_constrained_delaunay(mesh);
  DELTAMESH_FUZZ_CHECK(!delaunay || flips == 0, "make_constrained_delaunay flipped a CDT: " + std::to_string(flips));
  check(mesh, must, true, convex, before, "make_constrained_delaunay");

  if (f1 & 8) {
    dm::RefineOptions ropt;
    ropt.min_angle_deg = (f1 & 16) ? 25.0 : 0.0;
    if (f1 & 32) {  // a fraction of the bounding box: the budget may stop it
      double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
      for (const dm::Point& p : g.points) {
        lox = std::min(lox, p.x), hix = std::max(hix, p.x);
        loy = std::min(loy, p.y), hiy = std::max(hiy, p.y);
      }
      ropt.max_area = (hix - lox) * (hiy - loy) / 32.0;
    }
    ropt.max_steiner = 40;
    ropt.time_limit_seconds = 1.0;
    try {
      dm::refine(mesh, ropt);
    } catch (...) {
      fz::unexpected_exception("refine");
    }
    must.points.assign(mesh.points().begin(), mesh.points().end());
    check(mesh, must, true, false, before, "refine");
  }
  return 0;
}
