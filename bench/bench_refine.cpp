// Refinement benchmark: the unit square with the square hole [0.4,0.6]^2 at
// -q30 with an area bound (about 4·10^6 triangles by default), deltamesh's
// refine() against CGAL's refine_Delaunay_mesh_2 when CGAL is available.
//
//   bench_refine [--area A] [--q Q] [--runs N] [--peer cgal] [--best|--offcenter|--circumcenter]
//   bench_refine --star N [--seed S] [--q Q] [--area A] [--runs N] [--check]
//
// --star: instead, the star polygon of deltamesh-gen (N vertices, radii
// uniform in [0.5, 1]; spikes with tiny input angles), CDT by triangulate(),
// no area bound unless --area is given (deltamesh only).
//
// Prints one line per run and a summary: triangles, wall time, µs per
// output triangle, and the process's peak resident memory per triangle
// (getrusage; run one configuration per process for a clean figure).
// The domain is built without the CDT: every segment of this input is a
// Delaunay edge of its vertices, so Delaunay + constrained edges + hole
// removal gives the carved CDT.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"
#include "deltamesh/refine.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

#ifdef DELTAMESH_HAVE_CGAL
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

namespace dm = deltamesh;
using Clock = std::chrono::steady_clock;

namespace {

// CPU time of this thread: steadier than wall time on a busy machine.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double peak_rss_bytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) * 1024.0;
}

// The carved CDT of square_with_hole(8): 8 vertices, 8 segments, one hole.
dm::Mesh square_hole_domain() {
  const dm::Pslg g = dm::gen::square_with_hole(8);
  dm::Mesh mesh = dm::delaunay(g.points, {.keep_ghosts = true});
  for (const dm::Segment& s : g.segments) {
    const dm::HalfEdgeId e = mesh.find_edge(s.a, s.b);
    if (e == dm::kNone) {
      std::fprintf(stderr, "bench_refine: segment %u-%u is not a Delaunay edge\n", s.a, s.b);
      std::exit(1);
    }
    mesh.constrain_edge(e, 1);
  }
  std::vector<dm::TriId> stack;
  const dm::Location loc = mesh.locate(g.holes[0]);
  stack.push_back(loc.tri);
  std::vector<char> gone(mesh.num_triangle_slots(), 0);
  while (!stack.empty()) {
    const dm::TriId t = stack.back();
    stack.pop_back();
    if (gone[t] || mesh.is_ghost(t)) continue;
    gone[t] = 1;
    for (int i = 0; i < 3; ++i) {
      const dm::HalfEdgeId e = 3 * t + i;
      if (!mesh.is_constrained(e)) stack.push_back(dm::tri_of(mesh.twin(e)));
    }
  }
  for (dm::TriId t = 0; t < gone.size(); ++t)
    if (gone[t]) mesh.remove_triangle(t);
  mesh.compact();
  return mesh;
}

#ifdef DELTAMESH_HAVE_CGAL
std::size_t run_cgal(double q, double area, double& seconds) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_2<K>;
  using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
  using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
  using P = CDT::Point;
  const auto t0 = Clock::now();
  CDT cdt;
  auto ring = [&](double lo, double hi) {
    auto a = cdt.insert(P(lo, lo)), b = cdt.insert(P(hi, lo)), c = cdt.insert(P(hi, hi)), d = cdt.insert(P(lo, hi));
    cdt.insert_constraint(a, b);
    cdt.insert_constraint(b, c);
    cdt.insert_constraint(c, d);
    cdt.insert_constraint(d, a);
  };
  ring(0, 1);
  ring(0.4, 0.6);
  std::vector<P> seeds{P(0.5, 0.5)};
  // Shape bound B = sin^2(min angle); size bound = the edge of an
  // equilateral triangle of the area bound.
  const double s = std::sin(q * M_PI / 180.0);
  const double edge = std::sqrt(4.0 * area / std::sqrt(3.0));
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(s * s, edge));
  std::size_t n = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->is_in_domain()) ++n;
  seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return n;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  double area = 4.2e-7, q = 30;
  int runs = 1;
  bool cgal = false, check = false, area_set = false;
  std::size_t star = 0;
  std::uint64_t seed = 1;
  dm::RefineOptions opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_refine: %s needs a value\n", a.c_str());
        std::exit(1);
      }
      return argv[++i];
    };
    if (a == "--area") area = std::atof(next()), area_set = true;
    else if (a == "--star") star = std::strtoull(next(), nullptr, 10);
    else if (a == "--seed") seed = std::strtoull(next(), nullptr, 10);
    else if (a == "--q") q = std::atof(next());
    else if (a == "--runs") runs = std::atoi(next());
    else if (a == "--peer" && std::string(next()) == "cgal") cgal = true;
    else if (a == "--circumcenter") opt.steiner = dm::SteinerRule::Circumcenter;
    else if (a == "--offcenter") opt.steiner = dm::SteinerRule::Offcenter;
    else if (a == "--best") opt.steiner = dm::SteinerRule::Best;
    else if (a == "--check") check = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_refine [--area A] [--q Q] [--runs N] [--peer cgal] [--circumcenter] [--check]\n"
                   "       bench_refine --star N [--seed S] [--q Q] [--area A] [--runs N] [--check]\n");
      return 1;
    }
  }
  if (star > 0 && star < 3) {
    std::fprintf(stderr, "bench_refine: --star needs N >= 3\n");
    return 1;
  }
  if (star > 0 && cgal) {
    std::fprintf(stderr, "bench_refine: --star runs deltamesh only\n");
    return 1;
  }
  if (star > 0 && !area_set) area = 0;
  std::vector<double> times, cpu;
  std::size_t tris = 0;
  if (cgal) {
#ifdef DELTAMESH_HAVE_CGAL
    for (int r = 0; r < runs; ++r) {
      double s = 0;
      const double c0 = cpu_seconds();
      tris = run_cgal(q, area, s);
      cpu.push_back(cpu_seconds() - c0);
      times.push_back(s);
      std::printf("cgal run %d: %zu triangles, %.3f s, %.3f us/triangle\n", r, tris, s, 1e6 * s / double(tris));
    }
#else
    std::fprintf(stderr, "bench_refine: built without CGAL\n");
    return 1;
#endif
  } else {
    opt.min_angle_deg = q;
    opt.max_area = area;
    for (int r = 0; r < runs; ++r) {
      dm::Mesh mesh = star > 0 ? dm::triangulate(dm::gen::star_polygon(star, seed)) : square_hole_domain();
      const auto t0 = Clock::now();
      const double c0 = cpu_seconds();
      const dm::RefineStats st = dm::refine(mesh, opt);
      cpu.push_back(cpu_seconds() - c0);
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      tris = mesh.num_triangles();
      times.push_back(s);
      std::printf("deltamesh run %d: %zu triangles, %.3f s, %.3f us/triangle; %s\n", r, tris, s,
                  1e6 * s / double(tris), st.summary().c_str());
      if (check) {
        const dm::CheckReport rep = dm::check(mesh, {.convex_hull = false});
        std::printf("check: %s\n", rep.summary().c_str());
      }
    }
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  const double med = times[times.size() / 2];
  const double med_cpu = cpu[cpu.size() / 2];
  double load = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0;
    std::fclose(f);
  }
  if (star > 0) std::printf("star %zu seed %llu, ", star, static_cast<unsigned long long>(seed));
  std::printf(
      "%s q%g a%g: %zu triangles, median %.3f s (cpu %.3f s), %.3f us/triangle (cpu %.3f), peak RSS %.1f "
      "B/triangle (load %.2f)\n",
      cgal ? "cgal" : "deltamesh", q, area, tris, med, med_cpu, 1e6 * med / double(tris), 1e6 * med_cpu / double(tris),
      peak_rss_bytes() / double(tris), load);
  return 0;
}
