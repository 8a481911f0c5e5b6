// Mesh adaptation: coarsening and refining a constrained Delaunay mesh to a
// size field (src/algo/adapt/; docs/internals.md maps the code).
//
//   deltamesh::SizeField h = [](double x, double) { return 0.01 + 0.19 * x; };
//   deltamesh::AdaptStats st = deltamesh::adapt(mesh, h, {.refine = {.min_angle_deg = 30}});
//   // st.removed vertices went where the mesh was finer than h, st.inserted
//   // came where it was coarser; the mesh is a quality CDT again.
#pragma once
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "deltamesh/mesh.hpp"
#include "deltamesh/refine.hpp"

namespace deltamesh {

// Target edge length h(x, y) at a point, in the units of the coordinates
// (an edge of length h is "right"). Values <= 0 or NaN mean "no target
// here": no vertex is removed and nothing is refined for size there.
using SizeField = std::function<double(double x, double y)>;

// A size field given by sizes at the vertices of a background mesh (one per
// vertex, e.g. the sizes of a TetGen .mtr file): linear interpolation over
// the background triangle containing the point, found by a walk from the
// nearest background vertex (a bucket grid); a point outside the background
// mesh (or behind a hole the walk cannot cross) takes the size of the
// nearest background vertex. The background mesh is copied; the function
// has no mutable state, so it may be called from several threads. Throws
// InputError unless there is one positive finite size per vertex.
SizeField size_field_from_vertices(const Mesh& background, std::span<const double> sizes);

struct CoarsenOptions {
  // A removable vertex v goes when its shortest incident edge is shorter
  // than ratio * h(v): the links it leaves are then about 2 * ratio * h at
  // most, so ratio = 0.7 (~1/sqrt 2) leaves edges that refinement to h
  // seldom has to split again.
  double ratio = 0.7;
  // ... and when its longest incident edge is shorter than max_spoke * h(v):
  // the edges its removal leaves are at most about twice its spokes.
  double max_spoke = 1.5;
  // Vertices with ids below this are never removed (e.g. the input PSLG's
  // vertices, to keep every input vertex even where segments are straight).
  std::size_t protect_first = 0;
  // At most this many removals (0: no limit).
  std::size_t max_removals = 0;
  // Drop the removed vertices and renumber the rest in order (as
  // Mesh::remove_unused_vertices, which also drops vertices that were in no
  // triangle before). false: they stay as vertices in no triangle.
  bool renumber = true;
};

struct CoarsenStats {
  std::size_t vertices_before = 0;   // vertices in triangles before
  std::size_t vertices_after = 0;    // ... after
  std::size_t removed = 0;           // vertices removed
  std::size_t removed_on_segments = 0;  // ... of them inside straight segment chains (subsegments merged)
  std::size_t refused = 0;           // candidates whose star could not be emptied by flips (kept)
  std::size_t flips = 0;             // degree-reducing and Delaunay flips
  double seconds = 0.0;
  // With renumber: old vertex id -> new id (kNone for removed vertices).
  std::vector<VertexId> new_id;
  std::string summary() const;
};

// Removes vertices where the mesh is finer than h (see CoarsenOptions::ratio)
// from a constrained Delaunay triangulation (compacted or not; ghost-free),
// keeping it one: the same domain, holes and segments (as chains of
// constrained edges). Removable: interior vertices with no constrained edge,
// and vertices inside a straight segment chain (exactly two constrained
// edges, same marker, collinear: exactly, or within 1e-11 of the line
// through the two neighbours relative to their distance, since split points
// of slanted segments are rounded off the line, with a turn of sine below
// 1e-6 there, so a corner beside a tiny edge stays), whose subsegments merge.
// Vertices where segments end or bend, or where markers change, stay, and
// so do vertices with a marker of their own (not 0, not their segments').
// Candidates go smallest shortest-edge/h first (a heap, re-keyed as stars
// change), which grades the result. Each removal flips the vertex's degree
// down to 3 (interior) or 2 per side (segment), choosing Devillers' ear of
// least power first, removes it, and restores the CDT with constrained
// Lawson flips around its old star. The mesh is compacted on return.
CoarsenStats coarsen(Mesh& mesh, const SizeField& h, const CoarsenOptions& options = {});

// Where smooth() tries to move a vertex (docs/adapt.md compares them: on
// -q30 meshes the Laplacian target raises the mean smallest angle more).
enum class SmoothTarget {
  // The centroid of the neighbours.
  Laplacian,
  // Optimal Delaunay triangulation (Chen & Xu): the mean of the incident
  // triangles' circumcentres weighted by their areas (times h^-4 at their
  // centroids with a size field, the density whose optimal mesh has edges
  // ~h).
  Odt,
};

struct SmoothOptions {
  // Sweeps over the vertices (in id order, each move seen by the next), each
  // followed by constrained Lawson flips. Stops early after a sweep that
  // moves nothing.
  int passes = 3;
  SmoothTarget target = SmoothTarget::Laplacian;
  // Optional: a move must not make its star's worst (longest edge / h at the
  // triangle's centroid) exceed max(1, what it was).
  SizeField h;
  // Optional (> 0): likewise for the worst (area / max_area).
  double max_area = 0.0;
  // The smallest angle of a vertex's star never decreases by a move when
  // this is < 0 (the default). When >= 0, a move may lower it while it stays
  // at least min(this, what it was): room for the average to improve above
  // an angle bound that must hold (e.g. refine's min_angle_deg).
  double min_angle_deg = -1.0;
  // Vertices with ids below this never move (as CoarsenOptions).
  std::size_t protect_first = 0;
};

struct SmoothStats {
  std::size_t moved = 0;     // accepted moves (a vertex counts once per pass)
  std::size_t rejected = 0;  // vertex visits where neither the full nor the half step passed the guards
  std::size_t flips = 0;     // constrained Lawson flips after the passes
  std::size_t passes = 0;    // passes run
  double min_angle_before = 0.0, min_angle_after = 0.0;    // degrees, over all triangles
  double mean_min_angle_before = 0.0, mean_min_angle_after = 0.0;  // mean over triangles of their smallest angle
  double seconds = 0.0;
  std::string summary() const;
};

// Moves free vertices of a constrained Delaunay triangulation (interior, no
// constrained edge, no vertex marker of their own, id >= protect_first)
// towards options.target, then restores the constrained Delaunay property
// by flips. A move is taken only if every triangle of the star stays
// counter-clockwise (exact orient2d), its smallest angle does not decrease
// (see min_angle_deg) and the size guards hold; else half the step is tried,
// else the vertex stays. So the mesh's smallest angle never decreases and
// vertices on segments, the boundary and protected ones keep their exact
// coordinates. Topology changes only by flips. Triangle attributes and area
// bounds stay with their slots (as coarsen()); vertex attributes are not
// re-interpolated.
SmoothStats smooth(Mesh& mesh, const SmoothOptions& options = {});

// Smooths a mesh that refine(mesh, refine_options) left with `refined`, and
// when that refinement was complete, refines again the few triangles
// smoothing left outside its bounds (a flip may lengthen an edge; a move
// keeps only its star's smallest angle, which may be below the bound at an
// input angle). The second refinement gets what the first left of the
// Steiner budget and time limit, and its counts are added to `refined`;
// `resplit` (when given) receives the points it inserted.
SmoothStats smooth_refined(Mesh& mesh, const SmoothOptions& options, const RefineOptions& refine_options,
                           RefineStats& refined, std::size_t* resplit = nullptr);

struct AdaptOptions {
  CoarsenOptions coarsen;
  // Refinement after coarsening: its max_edge_at is set to h (a triangle's
  // longest edge at most h at its centroid), the rest is used as given
  // (angle bound, budgets, time limit).
  RefineOptions refine;
  // Smoothing passes after refinement (0: none; none either with
  // refine.conforming_delaunay, whose promise a move could break), with h
  // and refine's max_area as guards and vertices below
  // coarsen.protect_first protected.
  // Refinement runs again afterwards for triangles left outside its bounds
  // (a flip may lengthen an edge; a star whose smallest angle was already
  // below the angle bound may get another triangle below it): seldom, a few
  // points.
  int smooth_passes = 2;
};

struct AdaptStats {
  CoarsenStats coarsen;
  RefineStats refine;
  SmoothStats smooth;          // with smooth_passes > 0
  std::size_t resplit = 0;     // points the refinement after smoothing inserted
  std::size_t removed = 0;    // vertices removed by coarsening
  std::size_t inserted = 0;   // Steiner points inserted by refinement
  std::size_t triangles = 0;  // final triangles
  // refine's: false when a budget stopped it or triangles were left larger
  // than h. The mesh is a valid CDT either way.
  bool complete = true;
  double seconds = 0.0;
  std::string summary() const;
};

// Coarsens where the mesh is finer than h, then refines where it is coarser
// (and to the angle bound). Ends: coarsening removes each vertex at most
// once, and refinement has its budgets.
AdaptStats adapt(Mesh& mesh, const SizeField& h, const AdaptOptions& options = {});

}  // namespace deltamesh
