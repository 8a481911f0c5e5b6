// Anisotropic mesh adaptation: meshes whose edges have unit length in a
// metric tensor field M(x) (src/algo/adapt/metric*.cpp, anisotropic.cpp;
// docs/adapt.md).
//
//   // A metric from a P1 field: Hessian recovery, scaled to ~2000 vertices.
//   std::vector<double> u = ...;  // one value per vertex of mesh
//   auto m = deltamesh::metric_from_hessian(mesh, deltamesh::recover_hessian(mesh, u), {.complexity = 2000});
//   deltamesh::gradate_metric(mesh, m, 1.5);
//   deltamesh::adapt_to_metric(mesh, deltamesh::metric_field_from_vertices(mesh, m));
#pragma once
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"

namespace deltamesh {

// A symmetric 2x2 matrix [[m11, m12], [m12, m22]]: a metric tensor (then
// positive definite: the length of a vector e is sqrt(e^T M e)), or a
// Hessian. A metric with eigenvalues l1, l2 asks for edge lengths
// 1/sqrt(l1) and 1/sqrt(l2) along its eigenvectors; h^-2 * I is the
// isotropic size h.
struct Metric {
  double m11 = 1, m12 = 0, m22 = 1;
};

inline Metric isotropic_metric(double h) { return {1 / (h * h), 0, 1 / (h * h)}; }

// Positive definite with finite entries, and not so close to singular that
// its eigenvalues cannot be told apart from 0 (smallest/largest > 1e-24,
// i.e. aspect ratio below 1e12).
bool is_metric(const Metric& m);
// Why m is not a metric ("" when it is): for error messages.
std::string metric_problem(const Metric& m);

// Eigen-decomposition: eigenvalues l1 <= l2 and the unit eigenvector (c, s)
// of l1 (the one of l2 is (-s, c)).
struct Eigen2 {
  double l1, l2, c, s;
};
Eigen2 eigen(const Metric& m);
Metric from_eigen(double l1, double l2, double c, double s);

// Length of the vector (dx, dy) in m.
double metric_length(const Metric& m, double dx, double dy);

// Log-Euclidean mean (Arsigny et al., "Log-Euclidean metrics for fast and
// simple calculus on diffusion tensors", MRM 56(2), 2006): exp(sum w_i log
// M_i). The interpolation rule of every metric field in deltamesh: it stays
// positive definite, interpolates determinants geometrically and does not
// swell as the arithmetic mean does between differently oriented tensors.
Metric log_euclidean_mean(std::span<const Metric> m, std::span<const double> w);

// Intersection of two metrics (simultaneous reduction; Frey & George, "Mesh
// Generation", 2nd ed., §10.6): the largest metric whose unit ball lies in
// both unit balls: it asks for the smaller size in every direction.
Metric intersect(const Metric& a, const Metric& b);

// A metric at every point. Callers evaluate it at vertices.
using MetricField = std::function<Metric(double x, double y)>;

// Metrics at the vertices of a background mesh, interpolated with the
// log-Euclidean rule over the background triangle containing the point (as
// size_field_from_vertices: outside, the nearest vertex's). Throws
// InputError naming the first vertex whose tensor is not a metric.
MetricField metric_field_from_vertices(const Mesh& background, std::span<const Metric> metrics);

// ---- metrics from a solution ------------------------------------------------

// Recovered Hessian of a P1 field (one value per vertex; vertices in no
// triangle get a zero Hessian): at each vertex, a least-squares fit of a
// quadratic to the values on its one-ring when that has at least 7 points
// and determines a quadratic, else on the two-ring (up to four rings), in
// coordinates centred at the vertex along the patch's principal axes, each
// scaled by the patch's extent (stretched patches stay well conditioned).
// This is the patch fit of polynomial-preserving
// recovery (Zhang & Naga, "A new finite element gradient recovery method:
// superconvergence property", SIAM J. Sci. Comput. 26(4), 2005) taken to
// second derivatives; exact for quadratics.
std::vector<Metric> recover_hessian(const Mesh& mesh, std::span<const double> values);

struct MetricScaling {
  // Lp norm of the interpolation error the metric minimises (Loseille &
  // Alauzet, "Continuous mesh framework, part II", SIAM J. Numer. Anal.
  // 49(1), 2011): M = D det|H|^(-1/(2p+2)) |H|. p <= 0 means L-infinity
  // (M proportional to |H|).
  double p = 2;
  // Target complexity N = integral of sqrt(det M) (about the number of
  // vertices; triangles ~ 2N). Used when > 0.
  double complexity = 0;
  // Else: target L-infinity interpolation error eps, M = c/eps |H| with
  // c = 2/9 (Frey & Alauzet, "Anisotropic mesh adaptation for CFD
  // computations", CMAME 194, 2005). Used when complexity <= 0.
  double tolerance = 0.01;
  // Bounds on the sizes (eigenvalues clamped to [1/h_max^2, 1/h_min^2])
  // and on the aspect ratio (the smaller eigenvalue raised to at least
  // largest / max_aspect^2).
  double h_min = 1e-6, h_max = 1e6, max_aspect = 1e4;
};

// Metrics at the vertices from Hessians (their absolute values: |H| has
// H's eigenvectors and the eigenvalues' magnitudes, floored by the h_max
// bound), scaled as above. Needs a mesh with triangles (for the integral).
std::vector<Metric> metric_from_hessian(const Mesh& mesh, std::span<const Metric> hessians,
                                        const MetricScaling& scaling = {});

// Gradation control (Alauzet, "Size gradation control of anisotropic
// meshes", Finite Elem. Anal. Des. 46, 2010, the metric-space variant):
// along every edge pq, M_p is intersected with M_q grown by
// (1 + l_q(pq) ln beta)^-2, l_q the edge's length in M_q, until no metric
// changes (at most 50 sweeps). Sizes then grow by at most a factor of about
// beta per unit of metric length. Returns the number of sweeps.
int gradate_metric(const Mesh& mesh, std::vector<Metric>& metrics, double beta = 1.5);

// ---- adaptation ---------------------------------------------------------------

struct MetricAdaptOptions {
  // Outer iterations of split, collapse, swap, smooth. Stops early when an
  // iteration changes less than 0.5% of the vertices.
  int iterations = 12;
  // Vertices with ids below this are never removed nor moved.
  std::size_t protect_first = 0;
  // Split constrained edges (segments) too; false keeps the boundary's
  // vertices as they are (Triangle's -Y).
  bool split_segments = true;
  // Smoothing sweeps per iteration (0: none).
  int smooth_passes = 2;
  // At most this many vertices (0: no limit): splits stop there.
  std::size_t max_vertices = 0;
  // Optional: called after every pass ("split", "collapse", "swap",
  // "smooth") with the mesh compacted, e.g. to run the validator in tests.
  std::function<void(const Mesh&, const char* pass)> after_pass;
};

struct MetricAdaptStats {
  std::size_t splits = 0, collapses = 0, swaps = 0, moves = 0;
  std::size_t iterations = 0;
  std::size_t triangles = 0;
  bool vertex_budget_hit = false;
  double seconds = 0.0;
  std::string summary() const;
};

// Adapts a mesh to a metric field: edges longer than sqrt 2 in the metric
// are split at their midpoint, vertices at edges shorter than 1/sqrt 2
// collapse onto the edge's other end, edges are swapped where that raises
// the two triangles' worse anisotropic quality, free vertices move towards
// the metric-weighted centre of their neighbours. Every topological
// decision is an exact orient2d test (a collapse or a move is taken only if
// every new triangle is counter-clockwise; a swap only in a strictly convex
// quadrilateral). Segments and their markers stay: constrained edges are
// never swapped, vertices on them move never and collapse only along a
// straight chain with one marker (the rules of coarsen()); protected
// vertices, vertices with a marker of their own and those where chains end
// or bend stay; triangle attributes and area bounds stay with their slots,
// so regions separated by segments keep theirs; new vertices get
// interpolated vertex attributes and their segment's marker. The mesh is
// compacted and its unused vertices dropped on return, the rest renumbered
// in order (as coarsen()): protected vertices keep their ids when every
// vertex before them is in a triangle. Throws InputError when the field
// gives a tensor that is not a metric (naming the point); the mesh is then
// a valid triangulation, partly adapted and not compacted.
MetricAdaptStats adapt_to_metric(Mesh& mesh, const MetricField& metric, const MetricAdaptOptions& options = {});

// How well a mesh fits a metric field.
struct MetricFit {
  std::size_t edges = 0;
  double within = 0;  // share of edges with metric length in [1/sqrt 2, sqrt 2]
  double min_length = 0, max_length = 0, mean_length = 0;
  // Anisotropic quality of a triangle: 4 sqrt 3 area_M / sum of squared
  // metric edge lengths, in the log-Euclidean mean of its vertices'
  // metrics (1 for an equilateral triangle in the metric, 0 for a flat one).
  double min_quality = 0, mean_quality = 0;
  std::string summary() const;
};
MetricFit metric_fit(const Mesh& mesh, const MetricField& metric);

// Length of edge pq in a metric field, given the metrics at p and q: the
// logarithmic mean of the lengths in M_p and M_q, exact when the length
// density varies geometrically along the edge (as between the sizes of a
// graded mesh).
double edge_length_in_metrics(const Point& p, const Point& q, const Metric& mp, const Metric& mq);
// Anisotropic quality of triangle abc (see MetricFit) in metric m.
double metric_quality(const Point& a, const Point& b, const Point& c, const Metric& m);

}  // namespace deltamesh
