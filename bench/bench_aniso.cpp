// Anisotropic against isotropic adaptation on functions with sharp layers
// (docs/adapt.md): for each target complexity N, iterate solve-free
// adaptation on the unit square (interpolate u at the vertices, recover
// the Hessian, build the L2-optimal metric scaled to N with gradation 2,
// adapt_to_metric) and report the interpolation error of the P1 interpolant
// (L2 by a composite degree-5 rule, L-infinity at its points) against the triangle count. "iso" uses the same pipeline with each
// Hessian replaced by its largest eigenvalue times I (the optimal isotropic
// metric); "aniso" the Hessian itself. With --gmsh DIR, Gmsh's BAMG
// (Mesh.Algorithm 7) meshes the square to the last aniso metric of each run
// (a tensor view as background mesh) for comparison.
//
//   bench_aniso [--functions front,layer,cross] [--n 250,500,...] [--methods iso,aniso] [--iterations 5]
//               [--svg DIR] [--svg-n N] [--gmsh DIR] [--gradation BETA] [--quadrature K]
//               [--trace 1] [--hessian exact] [--bands 1] [--dump FILE]
//
// --svg: pictures of the meshes at N = --svg-n (default 2000). --gradation:
// gradate_metric's beta for both methods (default 2). --quadrature: K x K
// sub-triangles per triangle for the error (default 4; the L2 error agrees
// to 6 digits with K = 16 on the front at N = 250). Diagnostics: --trace 1
// prints, per iteration, the metric's complexity before and after
// gradation, the mesh's error and adapt_to_metric's summary on stderr;
// --hessian exact replaces the
// recovered Hessian by central differences of the function itself;
// --bands 1 (front only) prints, for the last mesh, triangles and squared
// error by distance of the centroid to the front's centre line (< 0.02,
// 0.02-0.05, beyond) and x decile, and per band the triangles against the
// metric's own count (area in the metric over that of a unit equilateral
// triangle) and the mean metric edge length, and triangles and error share
// in bands of 0.004; --dump FILE writes, for the last metric computed (the
// last run's last iteration), each vertex's recovered Hessian and metric
// before and after gradation (CSV).
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

// Error of the P1 interpolant. L2: each triangle is cut into k x k similar
// sub-triangles with Dunavant's 7-point degree-5 rule on each (the squared
// error is smooth inside a sub-triangle once it is small against the
// layer); L-infinity: the maximum over those points and the vertices of the
// sub-triangles.
int quadrature_k = 4;
bool trace = false;
bool bands = false;
bool exact_hessian = false;
std::string dump_path;

Error interpolation_error(const dm::Mesh& m, const Function& fn) {
  const std::vector<double> u = values(m, fn);
  const int k = quadrature_k;
  // Dunavant (IJNME 21, 1985), degree 5: barycentric (a, b, b) and its
  // permutations, weights summing to 1.
  struct Rule {
    double a, b, w;
    int perms;
  };
  static constexpr Rule rule[] = {{1.0 / 3, 1.0 / 3, 0.225, 1},
                                  {0.059715871789770, 0.470142064105115, 0.132394152788506, 3},
                                  {0.797426985353087, 0.101286507323456, 0.125939180544827, 3}};
  Error e;
  double sq = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    // Error at barycentric (s, r) of the whole triangle (weights of b, c).
    auto err = [&](double s, double r) {
      const double x = a.x + s * (b.x - a.x) + r * (c.x - a.x), y = a.y + s * (b.y - a.y) + r * (c.y - a.y);
      return fn.f(x, y) - ((1 - s - r) * u[v[0]] + s * u[v[1]] + r * u[v[2]]);
    };
    double s = 0;
    auto sub = [&](double s0, double r0, double s1, double r1, double s2, double r2) {
      for (const Rule& q : rule)
        for (int p = 0; p < q.perms; ++p) {
          const double w0 = p == 0 ? q.a : q.b, w1 = p == 1 ? q.a : q.b, w2 = p == 2 ? q.a : q.b;
          const double d = err(w0 * s0 + w1 * s1 + w2 * s2, w0 * r0 + w1 * r1 + w2 * r2);
          e.linf = std::max(e.linf, std::fabs(d));
          s += q.w * d * d;
        }
    };
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        e.linf = std::max(e.linf, std::fabs(err(double(i) / k, double(j) / k)));
        if (i + j < k) sub(double(i) / k, double(j) / k, double(i + 1) / k, double(j) / k, double(i) / k, double(j + 1) / k);
        if (i + j < k - 1)
          sub(double(i + 1) / k, double(j) / k, double(i + 1) / k, double(j + 1) / k, double(i) / k, double(j + 1) / k);
      }
    sq += area * s / (k * k);
  }
  e.l2 = std::sqrt(sq);
  return e;
}

// The front's distance band (0: within 0.02 of y = 0.5 + 0.25 sin 2 pi x,
// vertically; 1: within 0.05; 2: beyond) of a triangle's centroid.
int front_band(const dm::Point& c) {
  const double d = std::fabs(c.y - 0.5 - 0.25 * std::sin(2 * M_PI * c.x));
  return d < 0.02 ? 0 : d < 0.05 ? 1 : 2;
}

// Squared interpolation error of triangle t by the midpoint rule on k x k
// sub-triangles (a band's share, not the reported L2 error).
double squared_error(const dm::Mesh& m, const std::vector<double>& u, const Function& fn, dm::TriId t, int k) {
  const auto v = m.triangle(t);
  const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
  double sq = 0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j)
      for (int up = 0; up < (i + j < k - 1 ? 2 : 1); ++up) {
        const double s = (i + (up ? 2.0 / 3 : 1.0 / 3)) / k, r = (j + (up ? 2.0 / 3 : 1.0 / 3)) / k;
        const double x = a.x + s * (b.x - a.x) + r * (c.x - a.x), y = a.y + s * (b.y - a.y) + r * (c.y - a.y);
        const double d = fn.f(x, y) - ((1 - s - r) * u[v[0]] + s * u[v[1]] + r * u[v[2]]);
        sq += d * d;
      }
  const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  return sq * area / (k * k);
}

// --bands: where the triangles and the squared error of the front's mesh
// are, and how closely each band's mesh follows its metric.
void print_bands(const dm::Mesh& m, const Function& fn, const dm::MetricField& field) {
  const std::vector<double> u = values(m, fn);
  double err[10][3] = {}, ideal[3] = {}, len[3] = {}, total = 0;
  int count[10][3] = {}, per_band[3] = {};
  const int k = quadrature_k;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
    const dm::Point g{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
    const double area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    const double sq = squared_error(m, u, fn, t, k);
    const int band = front_band(g), dec = std::clamp(int(g.x * 10), 0, 9);
    err[dec][band] += sq;
    ++count[dec][band];
    ++per_band[band];
    total += sq;
    const dm::Metric mg = field(g.x, g.y);
    ideal[band] += area * std::sqrt(mg.m11 * mg.m22 - mg.m12 * mg.m12) / (std::sqrt(3.0) / 4);
    for (int i = 0; i < 3; ++i) {
      const dm::Point &p = m.point(v[i]), &q = m.point(v[(i + 1) % 3]);
      len[band] += dm::edge_length_in_metrics(p, q, field(p.x, p.y), field(q.x, q.y)) / 3;
    }
  }
  {
    // Finer distance bands (vertical distance, in units of 0.004).
    double fe[13] = {}, fn_[13] = {};
    for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
      if (!m.is_real(t)) continue;
      const auto v = m.triangle(t);
      const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &c = m.point(v[2]);
      const dm::Point g{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
      const double sq = squared_error(m, u, fn, t, k);
      const int bi = std::min(12, int(std::fabs(g.y - 0.5 - 0.25 * std::sin(2 * M_PI * g.x)) / 0.004));
      fe[bi] += sq;
      fn_[bi] += 1;
    }
    double tot = 0;
    for (double x : fe) tot += x;
    std::fprintf(stderr, "  fine bands (0.004):");
    for (int i = 0; i < 13; ++i) std::fprintf(stderr, " %d/%.1f", int(fn_[i]), 100 * fe[i] / tot);
    std::fprintf(stderr, "\n");
  }
  std::fprintf(stderr, "  triangles / %% of squared error by x decile, bands < 0.02 | 0.02-0.05 | beyond:\n");
  for (int i = 0; i < 10; ++i) {
    std::fprintf(stderr, "   x %.1f:", i / 10.0);
    for (int j = 0; j < 3; ++j) std::fprintf(stderr, " %5d / %5.1f", count[i][j], 100 * err[i][j] / total);
    std::fprintf(stderr, "\n");
  }
  for (int j = 0; j < 3; ++j) {
    double e = 0;
    for (int i = 0; i < 10; ++i) e += err[i][j];
    std::fprintf(stderr, "  band %d: %d triangles (%.2f per unit of metric area), %.1f%% of the error, mean length %.3f\n",
                 j, per_band[j], per_band[j] / ideal[j], 100 * e / total, len[j] / per_band[j]);
  }
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

double complexity(const dm::Mesh& m, const std::vector<dm::Metric>& met) {
  double c = 0;
  for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
    if (!m.is_real(t)) continue;
    const auto v = m.triangle(t);
    const dm::Point &a = m.point(v[0]), &b = m.point(v[1]), &cc = m.point(v[2]);
    const double area = 0.5 * std::fabs((b.x - a.x) * (cc.y - a.y) - (b.y - a.y) * (cc.x - a.x));
    double d = 0;
    for (int i = 0; i < 3; ++i) d += std::sqrt(met[v[i]].m11 * met[v[i]].m22 - met[v[i]].m12 * met[v[i]].m12) / 3;
    c += area * d;
  }
  return c;
}

std::vector<dm::Metric> metric_for(const dm::Mesh& m, const Function& fn, bool aniso, double n, double gradation) {
  std::vector<dm::Metric> h = dm::recover_hessian(m, values(m, fn));
  if (exact_hessian) {  // diagnostic: central differences of f
    const double d = 1e-4;
    for (dm::VertexId v = 0; v < m.num_vertices(); ++v) {
      const double x = m.point(v).x, y = m.point(v).y, c = fn.f(x, y);
      h[v].m11 = (fn.f(x + d, y) - 2 * c + fn.f(x - d, y)) / (d * d);
      h[v].m22 = (fn.f(x, y + d) - 2 * c + fn.f(x, y - d)) / (d * d);
      h[v].m12 = (fn.f(x + d, y + d) - fn.f(x + d, y - d) - fn.f(x - d, y + d) + fn.f(x - d, y - d)) / (4 * d * d);
    }
  }
  if (!aniso)
    for (dm::Metric& x : h) x = isotropic_part(x);
  dm::MetricScaling sc;
  sc.p = 2;
  sc.complexity = n;
  sc.h_min = 1e-5;
  sc.h_max = 0.25;
  sc.max_aspect = 1e4;
  std::vector<dm::Metric> met = dm::metric_from_hessian(m, h, sc);
  const double c0 = complexity(m, met);
  const std::vector<dm::Metric> ungraded = met;
  dm::gradate_metric(m, met, gradation);
  if (!dump_path.empty()) {
    std::ofstream d(dump_path);
    d.precision(9);
    d << "x,y,h11,h12,h22,m11,m12,m22,g11,g12,g22\n";
    for (dm::VertexId v = 0; v < m.num_vertices(); ++v)
      d << m.point(v).x << "," << m.point(v).y << "," << h[v].m11 << "," << h[v].m12 << "," << h[v].m22 << ","
        << ungraded[v].m11 << "," << ungraded[v].m12 << "," << ungraded[v].m22 << "," << met[v].m11 << ","
        << met[v].m12 << "," << met[v].m22 << "\n";
  }
  if (trace) std::fprintf(stderr, "  complexity %.1f -> graded %.1f\n", c0, complexity(m, met));
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
    else if (a == "--quadrature") quadrature_k = std::atoi(v.c_str());
    else if (a == "--trace") trace = v == "1";
    else if (a == "--hessian") exact_hessian = v == "exact";
    else if (a == "--bands") bands = v == "1";
    else if (a == "--dump") dump_path = v;
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
          const dm::MetricAdaptStats ast = dm::adapt_to_metric(m, field);
          seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          validate(m, fn.name + " " + method + " N=" + std::to_string(int(n)) + " iteration " + std::to_string(it));
          fit = dm::metric_fit(m, field);
          if (trace) {
            // Metric lengths of the edges, in fifths of sqrt 2 ... 
            int hist[8] = {0};
            for (dm::TriId t = 0; t < m.num_triangle_slots(); ++t) {
              if (!m.is_real(t)) continue;
              const auto v = m.triangle(t);
              for (int i = 0; i < 3; ++i) {
                const dm::Point &p = m.point(v[i]), &q = m.point(v[(i + 1) % 3]);
                const double l = dm::edge_length_in_metrics(p, q, field(p.x, p.y), field(q.x, q.y));
                ++hist[std::min(7, int(l / 0.25))];
              }
            }
            std::fprintf(stderr, "  half-edge lengths by 0.25:");
            for (int h : hist) std::fprintf(stderr, " %d", h);
            std::fprintf(stderr, "\n");
            const Error ie = interpolation_error(m, fn);
            std::fprintf(stderr, "%s %s N=%d it %d: %zu triangles, l2 %.4g, within %.3f; adapt_to_metric: %s\n",
                         fn.name.c_str(), method, int(n), it, m.num_triangles(), ie.l2, fit.within, ast.summary().c_str());
          }
        }
        if (bands && fn.name == "front") {
          std::fprintf(stderr, "%s %s N=%d:\n", fn.name.c_str(), method, int(n));
          print_bands(m, fn, dm::metric_field_from_vertices(bg, met));
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
