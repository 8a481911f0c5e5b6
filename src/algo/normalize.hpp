// Exact normalisation of the input into the predicates' safe range
// (internal; docs/robustness.md "Any finite coordinates").
//
// Every coordinate is multiplied by 2^k, k chosen so the largest magnitude
// lies in [1/2, 1) (or, when the smallest nonzero one would then fall below
// the predicates' 2^-200, so that the smallest and largest are as far from
// 2^-200 as from 2^200). Multiplying a double by a power of two is exact unless
// the result leaves the normal range, so the mesh is built on exactly the
// input scaled, and scaling back returns the input's vertices bit for bit.
// Lengths scale by 2^k and areas by 2^2k. No translation: adding an offset
// back to a Steiner point would round it, and a mesh valid in the
// normalised frame could fold in the user's.
#pragma once
#include <functional>
#include <span>
#include <vector>

#include "deltamesh/geometry.hpp"
#include "deltamesh/mesh.hpp"
#include "deltamesh/pslg.hpp"
#include "deltamesh/refine.hpp"

namespace deltamesh::detail {

struct Frame {
  int k = 0;  // normalised = original * 2^k

  bool identity() const { return k == 0; }
  // A positive area / length bound in the normalised frame (<= 0 and NaN
  // pass through: "no bound" stays "no bound"); a positive bound never
  // becomes 0, an overflow is +inf (no bound).
  double area_to(double a) const;
  double length_to(double h) const;
  double area_from(double a) const;
  // Callbacks in the user's frame, called with normalised coordinates.
  std::function<double(double, double)> area_field_to(std::function<double(double, double)> f) const;
  std::function<double(double, double)> length_field_to(std::function<double(double, double)> f) const;
};

// The frame for these vertices. Throws InputError (naming the point) for a
// NaN or infinite coordinate. `threads` (0 = every hardware thread) scan
// parts of the points; the frame and the error do not depend on it.
Frame frame_for(std::span<const Point> points, unsigned threads = 1);

// The vertices scaled into the frame. Throws InputError (naming the point)
// for a nonzero coordinate below kMinCoordinate once scaled: one about
// 2^400 times smaller than the largest, beyond what the exact predicates
// resolve next to it. `threads` as for frame_for.
void scale_vertices(const Frame& f, std::vector<Point>& points, unsigned threads = 1);
// Hole and region seeds: scaled, clamped to +-2^100 (they stay outside the
// vertices' box) and flushed to 0 below kMinCoordinate.
void scale_seeds(const Frame& f, std::vector<Point>& points);

// Whether these points need a frame before the exact predicates see them: a
// finite nonzero coordinate outside [kMinCoordinate, kMaxCoordinate] in
// magnitude. NaN and infinities answer false (the callers' own checks name
// them). The library's lower-level entry points (delaunay(), triangulate(),
// refine()) mesh in a frame only then, so in-range calls are unchanged.
bool needs_frame(std::span<const Point> points);
// Whether every coordinate is finite and in the predicates' range (what
// check_coordinates() accepts), in one branch-free scan on up to `threads`
// threads; check_coordinates() names the culprit when it is not.
bool in_predicate_range(std::span<const Point> points, unsigned threads);
// A PSLG (points, holes, region seeds and their area bounds) scaled into f.
Pslg scaled_pslg(const Frame& f, Pslg pslg);
// Refinement's area and length bounds (global, callbacks) scaled into f.
void scale_options(const Frame& f, RefineOptions& options);
// A mesh's vertices and per-triangle area bounds into the frame (the
// inverse of restore below).
void scale_mesh(const Frame& f, Mesh& mesh);

// Back to the user's frame: every vertex and per-triangle area bound.
void restore(const Frame& f, Mesh& mesh);
// The lengths and places in refinement statistics.
void restore(const Frame& f, RefineStats& st);

}  // namespace deltamesh::detail
