// Anisotropic against isotropic adaptation on functions with sharp layers
// (docs/adapt.md): for each target complexity N, iterate solve-free
// adaptation on the unit square (interpolate u at the vertices, recover
// the Hessian, build the L2-optimal metric scaled to N with gradation 2,
// adapt_to_metric) and report the interpolation error of the P1 interpolant
// (L2 and L-infinity, sampled on a lattice of 28 points per triangle)
// against the triangle count. "iso" uses the same pipeline with each
// Hessian replaced by its largest eigenvalue times I (the optimal isotropic
// metric); "aniso" the Hessian itself. With --gmsh DIR, Gmsh's BAMG
// (Mesh.Algorithm 7) meshes the square to the last aniso metric of each run
// (a tensor view as background mesh) for comparison.
//
//   bench_aniso [--functions front,layer,cross] [--n 250,500,...] [--methods iso,aniso] [--iterations 5]
//               [--svg DIR] [--svg-n N] [--gmsh DIR] [--gradation BETA]
//
// --svg: pictures of the meshes at N = --svg-n (default 2000). --gradation:
// gradate_metric's beta for both methods (default 2).
//
// Output: CSV on stdout, one row per (function, method, N) after the last
// iteration; every mesh of every iteration goes through check().
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/metric.hpp"
#include "deltamesh/svg.hpp"
#include "deltamesh/triangulate.hpp"
#include "deltamesh/validate.hpp"

namespace dm = deltamesh;

namespace {

struct Function {
  std::string name;
  std::function<double(double, double)> f;
};

std::vector<Function> all_functions() {
  return {
      // A curved tanh front of width ~1/50.
      {"front", [](double x, double y) { return std::tanh(50 * (y - 0.5 - 0.25 * std::sin(2 * M_PI * x))); }},
      // A boundary layer of width 0.01 along x = 0, plus a mild variation.
      {"layer", [](double x, double y) { return std::exp(-x / 0.01) + 0.1 * std::sin(M_PI * y); }},
      // Two crossing straight tanh fronts.
      {"cross",
       [](double x, double y) { return std::tanh(40 * (x + y - 1)) + std::tanh(40 * (x - y + 0.2)); }},
  };
}

dm::Mesh square(double max_area) {
  dm::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (dm::VertexId i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, int(i) + 1});
  dm::TriangulateOptions o;
  dm::RefineOptions r;
  r.min_angle_deg = 25;
  r.max_area = max_area;
  o.refine = r;
  return dm::triangulate(g, o);
}

std::vector<double> values(const dm::Mesh& m, const Function& fn) {
  std::vector<double> u(m.num_vertices());
  for (dm::VertexId v = 0; v < m.num_vertices(); ++v) u[v] = fn.f(m.point(v).x, m.point(v).y);
  return u;
}

struct Error {
  double l2 = 0, linf = 0;
};

// Error of the P1 interpolant, sampled at the points of the barycentric
// lattice with 6 subdivisions (28 points, vertices included).
Error interpolation_error(const dm::Mesh& m, const Function& fn) {
  const std::vector<double> u = values(m, fn);
  constexpr int k = 6;
  Error e;
  double sq = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    double s = 0;
    int count = 0;
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const double wa = double(i) / k, wb = double(j) / k, wc = 1 - wa - wb;
        const double x = wa * a.x + wb * b.x + wc * c.x, y = wa * a.y + wb * b.y + wc * c.y;
        const double d = fn.f(x, y) - (wa * u[v[0]] + wb * u[v[1]] + wc * u[v[2]]);
        e.linf = std::max(e.linf, std::fabs(d));
        s += d * d;
        ++count;
      }
    sq += area * s / count;
  }
  e.l2 = std::sqrt(sq);
  return e;
}

dm::Metric isotropic_part(const dm::Metric& h) {
  const dm::Eigen2 e = dm::eigen(h);
  const double l = std::max(std::fabs(e.l1), std::fabs(e.l2));
  return {l, 0, l};
}

void validate(const dm::Mesh& m, const std::string& what) {
  dm::CheckOptions c;
  c.delaunay = false;
  c.convex_hull = true;
  const dm::CheckReport r = dm::check(m, c);
  if (!r.ok()) {
    std::fprintf(stderr, "bench_aniso: %s: invalid mesh: %s\n", what.c_str(), r.summary().c_str());
    std::exit(70);
  }
}

std::vector<dm::Metric> metric_for(const dm::Mesh& m, const Function& fn, bool aniso, double n, double gradation) {
  std::vector<dm::Metric> h = dm::recover_hessian(m, values(m, fn));
  if (!aniso)
    for (dm::Metric& x : h) x = isotropic_part(x);
  dm::MetricScaling sc;
  sc.p = 2;
  sc.complexity = n;
  sc.h_min = 1e-5;
  sc.h_max = 0.25;
  sc.max_aspect = 1e4;
  std::vector<dm::Metric> met = dm::metric_from_hessian(m, h, sc);
  dm::gradate_metric(m, met, gradation);
  return met;
}

// Gmsh's BAMG on the same metric: a tensor view over the background mesh.
// Returns false when gmsh is not there or failed.
bool run_gmsh(const dm::Mesh& bg, const std::vector<dm::Metric>& met, const std::string& dir, const std::string& tag,
              dm::Mesh& out, double& seconds) {
  const std::string pos = dir + "/" + tag + ".pos", geo = dir + "/" + tag + ".geo", msh = dir + "/" + tag + ".msh";
  {
    std::ofstream p(pos);
    p.precision(17);
    p << "View \"metric\" {\n";
    for (dm::TriId t = 0; t < bg.num_triangle_slots(); ++t) {
      if (!bg.is_real(t)) continue;
      const auto v = bg.triangle(t);
      p << "TT(";
      for (int i = 0; i < 3; ++i) p << (i ? "," : "") << bg.point(v[i]).x << "," << bg.point(v[i]).y << ",0";
      p << "){";
      for (int i = 0; i < 3; ++i) {
        const dm::Metric& m = met[v[i]];
        p << (i ? "," : "") << m.m11 << "," << m.m12 << ",0," << m.m12 << "," << m.m22 << ",0,0,0,1";
      }
      p << "};\n";
    }
    p << "};\n";
    std::ofstream g(geo);
    g << "Point(1)={0,0,0,0.1};Point(2)={1,0,0,0.1};Point(3)={1,1,0,0.1};Point(4)={0,1,0,0.1};\n"
         "Line(1)={1,2};Line(2)={2,3};Line(3)={3,4};Line(4)={4,1};\n"
         "Curve Loop(1)={1,2,3,4};Plane Surface(1)={1};\n"
         "Merge \""
      << tag << ".pos\";\nBackground Mesh View[0];\n"
      << "Mesh.Algorithm=7;\nMesh.MeshSizeExtendFromBoundary=0;\nMesh.MeshSizeFromPoints=0;\n"
         "Mesh.MeshSizeFromCurvature=0;\n";
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string cmd =
      "cd '" + dir + "' && gmsh -2 -format msh2 -o '" + tag + ".msh' '" + tag + ".geo' > '" + tag + ".log' 2>&1";
  if (std::system(cmd.c_str()) != 0) return false;
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream in(msh);
  std::string line;
  dm::Pslg nodes;
  std::vector<dm::VertexId> tris;
  std::vector<long> ids;
  while (std::getline(in, line)) {
    if (line == "$Nodes") {
      std::size_t n;
      in >> n;
      long maxid = 0;
      std::vector<std::pair<long, dm::Point>> pts(n);
      for (auto& [id, p] : pts) {
        double z;
        in >> id >> p.x >> p.y >> z;
        maxid = std::max(maxid, id);
      }
      ids.assign(maxid + 1, -1);
      for (auto& [id, p] : pts) {
        ids[id] = long(nodes.points.size());
        nodes.points.push_back(p);
      }
    } else if (line == "$Elements") {
      std::size_t n;
      in >> n;
      std::getline(in, line);
      for (std::size_t i = 0; i < n; ++i) {
        std::getline(in, line);
        std::istringstream s(line);
        long id, type, ntags;
        s >> id >> type >> ntags;
        for (long k = 0; k < ntags; ++k) s >> id;
        if (type != 2) continue;
        long a, b, c;
        s >> a >> b >> c;
        // Orient counter-clockwise.
        const dm::Point &pa = nodes.points[ids[a]], &pb = nodes.points[ids[b]], &pc = nodes.points[ids[c]];
        if ((pb.x - pa.x) * (pc.y - pa.y) - (pb.y - pa.y) * (pc.x - pa.x) < 0) std::swap(b, c);
        tris.insert(tris.end(), {dm::VertexId(ids[a]), dm::VertexId(ids[b]), dm::VertexId(ids[c])});
      }
    }
  }
  if (tris.empty()) return false;
  out = dm::mesh_from_triangles(nodes, tris);
  return true;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> r;
  std::stringstream in(s);
  std::string x;
  while (std::getline(in, x, ',')) r.push_back(x);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> fnames = {"front", "layer", "cross"};
  std::vector<double> ns = {250, 500, 1000, 2000, 4000, 8000};
  int iterations = 5;
  std::string svg_dir, gmsh_dir;
  std::vector<std::string> methods = {"iso", "aniso"};
  double svg_n = 2000;
  double gradation = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--functions") fnames = split(v);
    else if (a == "--n") {
      ns.clear();
      for (const std::string& x : split(v)) ns.push_back(std::atof(x.c_str()));
    } else if (a == "--iterations") iterations = std::atoi(v.c_str());
    else if (a == "--svg") svg_dir = v;
    else if (a == "--svg-n") svg_n = std::atof(v.c_str());
    else if (a == "--methods") methods = split(v);
    else if (a == "--gmsh") gmsh_dir = v;
    else if (a == "--gradation") gradation = std::atof(v.c_str());
    else {
      std::fprintf(stderr, "bench_aniso: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  std::printf("function,method,N,triangles,vertices,l2,linf,within,mean_length,mean_quality,min_quality,seconds\n");
  for (const Function& fn : all_functions()) {
    if (std::find(fnames.begin(), fnames.end(), fn.name) == fnames.end()) continue;
    for (double n : ns) {
      for (const bool aniso : {false, true}) {
        const char* method = aniso ? "aniso" : "iso";
        if (std::find(methods.begin(), methods.end(), method) == methods.end()) continue;
        dm::Mesh m = square(0.002);
        double seconds = 0;
        dm::MetricFit fit;
        std::vector<dm::Metric> met;
        dm::Mesh bg;
        for (int it = 0; it < iterations; ++it) {
          met = metric_for(m, fn, aniso, n, gradation);
          bg = m;
          const dm::MetricField field = dm::metric_field_from_vertices(m, met);
          const auto t0 = std::chrono::steady_clock::now();
          dm::adapt_to_metric(m, field);
          seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          validate(m, fn.name + " " + method + " N=" + std::to_string(int(n)) + " iteration " + std::to_string(it));
          fit = dm::metric_fit(m, field);
        }
        const Error e = interpolation_error(m, fn);
        std::printf("%s,%s,%d,%zu,%zu,%.6g,%.6g,%.4f,%.4f,%.4f,%.4f,%.3f\n", fn.name.c_str(), method, int(n),
                    m.num_triangles(), m.num_vertices(), e.l2, e.linf, fit.within, fit.mean_length, fit.mean_quality,
                    fit.min_quality, seconds);
        std::fflush(stdout);
        if (!svg_dir.empty() && n == svg_n) {
          dm::SvgOptions so;
          so.width_px = 600;
          so.title = fn.name + " " + method + " N=" + std::to_string(int(n)) + ": " +
                     std::to_string(m.num_triangles()) + " triangles";
          dm::write_svg(m, svg_dir + "/" + fn.name + "_" + method + ".svg", so);
        }
        if (aniso && !gmsh_dir.empty()) {
          dm::Mesh g;
          double gs = 0;
          const std::string tag = fn.name + "_" + std::to_string(int(n));
          if (run_gmsh(bg, met, gmsh_dir, tag, g, gs)) {
            validate(g, "gmsh " + tag);
            const dm::MetricFit gf = dm::metric_fit(g, dm::metric_field_from_vertices(bg, met));
            const Error ge = interpolation_error(g, fn);
            std::printf("%s,gmsh-bamg,%d,%zu,%zu,%.6g,%.6g,%.4f,%.4f,%.4f,%.4f,%.3f\n", fn.name.c_str(), int(n),
                        g.num_triangles(), g.num_vertices(), ge.l2, ge.linf, gf.within, gf.mean_length,
                        gf.mean_quality, gf.min_quality, gs);
            std::fflush(stdout);
          } else {
            std::fprintf(stderr, "bench_aniso: gmsh failed on %s (see %s/%s.log)\n", tag.c_str(), gmsh_dir.c_str(),
                         tag.c_str());
          }
        }
      }
    }
  }
  return 0;
}
