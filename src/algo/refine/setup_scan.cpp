// The passes of Refiner::setup() over every half-edge, on scan_threads_
// threads (refine_in_parts' last pass, which starts from the whole stitched
// mesh: on one thread these passes were a fifth of its serial time). Each
// gives exactly what the sequential loop in driver.cpp / small_angle.cpp
// gives: the work is cut into chunks of consecutive half-edges, and what a
// chunk finds is applied in chunk order.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include "algo/refine/refiner.hpp"
#include "core/parallel.hpp"

namespace deltamesh::refinement {

namespace {

// Chunks of [0, n) for `threads` threads; a fixed multiple of them, so that
// a slow thread does not hold the others.
std::size_t chunk_count(unsigned threads) { return 4 * std::size_t{threads}; }

template <class F>
void for_chunks(std::size_t n, unsigned threads, F&& f) {
  const std::size_t chunks = chunk_count(threads);
  detail::run_tasks(chunks, threads, [&](std::size_t i) { f(i, n * i / chunks, n * (i + 1) / chunks); });
}

}  // namespace

// Boundary edges made segments, the input segments collected in half-edge
// order, and the out-edges from scratch (driver.cpp's setup() on one thread).
void Refiner::scan_edges_in_parallel() {
  const std::size_t ne = tv_.size(), chunks = chunk_count(scan_threads_);
  std::vector<std::vector<std::pair<std::array<VertexId, 2>, std::uint8_t>>> found(chunks);
  std::vector<std::vector<HalfEdgeId>> constrained(chunks);
  if (fl_.size() < ne) fl_.resize(ne, 0);  // a mesh without flags yet (set_edge_flags() makes them)
  // Out-edges in the same pass: a boundary vertex's last boundary out-edge,
  // else a vertex's first out-edge, as the sequential loop leaves them. A
  // compare-and-swap to the largest by that order (boundary ones above the
  // others, the larger of two boundary ones, the smaller of two others):
  // the same result in any interleaving.
  std::fill(ve_.begin(), ve_.end(), kNone);
  for_chunks(ne, scan_threads_, [&](std::size_t i, std::size_t lo, std::size_t hi) {
    for (std::size_t e = lo; e < hi; ++e) {
      if (tw_[e] == kNone) {
        detail::atomic_replace_while(ve_[tv_[e]], static_cast<HalfEdgeId>(e), [&, e](HalfEdgeId cur) {
          return cur == kNone || tw_[cur] != kNone || cur < e;
        });
      } else {
        detail::atomic_replace_while(ve_[tv_[e]], static_cast<HalfEdgeId>(e), [&, e](HalfEdgeId cur) {
          return cur == kNone || (cur > e && tw_[cur] != kNone);
        });
      }
      if (tw_[e] == kNone && !(fl_[e] & kConstrained)) fl_[e] = static_cast<std::uint8_t>(fl_[e] | kConstrained);
      if (!(fl_[e] & kConstrained)) continue;
      constrained[i].push_back(static_cast<HalfEdgeId>(e));
      if (tw_[e] != kNone && tw_[e] < e) continue;
      found[i].push_back({{tv_[e], tv_[next_edge(static_cast<HalfEdgeId>(e))]},
                          static_cast<std::uint8_t>(tw_[e] == kNone ? kBoundarySeg : 0)});
    }
  });
  has_markers_ = m_.has_edge_markers();
  // The later passes of setup() look only at constrained half-edges (few:
  // the segments), and none becomes or stops being one before they run.
  constrained_.clear();
  for (const auto& list : constrained) constrained_.insert(constrained_.end(), list.begin(), list.end());
  adj_start_.assign(n_input_ + 1, 0);
  for (const auto& list : found)
    for (const auto& [s, spike] : list) {
      segs_.push_back(s);
      seg_spike_.push_back(spike);
      ++adj_start_[s[0] + 1];
      ++adj_start_[s[1] + 1];
    }
}

// The sectors of find_small_angles(), measured concurrently, in half-edge order.
void Refiner::sectors_in_parallel(std::vector<Sector>& out) const {
  const std::size_t chunks = chunk_count(scan_threads_);
  std::vector<std::vector<Sector>> found(chunks);
  for_chunks(constrained_.size(), scan_threads_, [&](std::size_t i, std::size_t lo, std::size_t hi) {
    for (std::size_t k = lo; k < hi; ++k) {  // (sector_at() is false for the others)
      Sector s{constrained_[k], kNone, 0};
      if (sector_at(s)) found[i].push_back(s);
    }
  });
  out.clear();
  for (const auto& list : found) out.insert(out.end(), list.begin(), list.end());
}

// queue_encroached()'s subsegments, found concurrently, pushed in half-edge order.
void Refiner::queue_encroached_in_parallel() {
  const std::size_t chunks = chunk_count(scan_threads_);
  std::vector<std::vector<SubsegmentRef>> found(chunks);
  // The constrained half-edges listed at setup, while the list holds (run()'s
  // call); go_beyond()'s, after refinement, scans every half-edge.
  const bool listed = !constrained_.empty();
  for_chunks(listed ? constrained_.size() : tv_.size(), scan_threads_, [&](std::size_t i, std::size_t lo, std::size_t hi) {
    for (std::size_t k = lo; k < hi; ++k) {
      const HalfEdgeId e = listed ? constrained_[k] : static_cast<HalfEdgeId>(k);
      if ((fl_[e] & kConstrained) && (tw_[e] == kNone || tw_[e] > e) && encroached(e) && splittable(e))
        found[i].push_back({tv_[e], tv_[next_edge(e)], e});
    }
  });
  for (const auto& list : found) encroached_.insert(encroached_.end(), list.begin(), list.end());
  constrained_ = {};  // refinement changes the mesh from here on
}

// measure_apex_feature_sizes()' distances, found concurrently, noted in
// half-edge order.
void Refiner::apex_feature_sizes_in_parallel() {
  // A hub has three segments or more: without one among their ends, the
  // scan below would note nothing.
  if (std::none_of(segs_.begin(), segs_.end(), [&](const auto& s) { return shelled_hub(s[0]) || shelled_hub(s[1]); }))
    return;
  const std::size_t chunks = chunk_count(scan_threads_);
  std::vector<std::vector<std::pair<VertexId, double>>> found(chunks);
  for_chunks(tv_.size(), scan_threads_, [&](std::size_t i, std::size_t lo, std::size_t hi) {
    double d2;
    for (std::size_t e = lo; e < hi; ++e)
      if (shelled_hub(tv_[e]) && apex_distance(static_cast<HalfEdgeId>(e), d2)) found[i].push_back({tv_[e], d2});
  });
  for (const auto& list : found)
    for (const auto& [v, d2] : list) note_apex_distance(v, d2);
}

// reserve_for_area_bounds()'s estimate, summed by chunks.
double Refiner::area_estimate_in_parallel(bool global) const {
  const std::size_t nt = tv_.size() / 3, chunks = chunk_count(scan_threads_);
  std::vector<double> part(chunks, 0.0);
  for_chunks(nt, scan_threads_, [&](std::size_t i, std::size_t lo, std::size_t hi) {
    double sum = 0;
    for (std::size_t t = lo; t < hi; ++t) sum += area_ratio(static_cast<TriId>(t), global);
    part[i] = sum;
  });
  double estimate = 0;
  for (double p : part) estimate += p;
  return estimate;
}

}  // namespace deltamesh::refinement
