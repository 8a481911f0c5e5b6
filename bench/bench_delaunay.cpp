// Delaunay triangulation benchmarks: deltamesh::delaunay() and, when CGAL is
// found at configure time, CGAL::Delaunay_triangulation_2 on the same points.
//
// Counters (medians over the repetitions):
//   us_per_pt  wall microseconds per input point
//   tris       triangles in the result
//   B_per_tri  peak heap bytes allocated by the call (including its result)
//              per triangle, measured by the counting operator new below
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "deltamesh-gen/generators.hpp"
#include "deltamesh/delaunay.hpp"

#ifdef DELTAMESH_HAVE_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

// ---- heap accounting ----------------------------------------------------------
// Every operator new/delete of the binary goes through here. Sizes are the
// allocator's usable sizes, so allocation and release always agree.
namespace heap {
std::atomic<std::int64_t> current{0};
std::atomic<std::int64_t> peak{0};

inline void on_alloc(void* p) {
  const auto sz = static_cast<std::int64_t>(malloc_usable_size(p));
  const std::int64_t now = current.fetch_add(sz, std::memory_order_relaxed) + sz;
  std::int64_t old = peak.load(std::memory_order_relaxed);
  while (now > old && !peak.compare_exchange_weak(old, now, std::memory_order_relaxed)) {
  }
}
inline void on_free(void* p) {
  if (p) current.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(p)), std::memory_order_relaxed);
}
// Starts a measurement: returns the baseline and resets the peak to it.
inline std::int64_t start() {
  const std::int64_t now = current.load(std::memory_order_relaxed);
  peak.store(now, std::memory_order_relaxed);
  return now;
}

void* allocate(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  on_alloc(p);
  return p;
}
void* allocate(std::size_t n, std::align_val_t al) {
  const auto a = static_cast<std::size_t>(al);
  void* p = std::aligned_alloc(a, ((n ? n : 1) + a - 1) / a * a);
  if (!p) throw std::bad_alloc();
  on_alloc(p);
  return p;
}
void release(void* p) {
  on_free(p);
  std::free(p);
}
}  // namespace heap

void* operator new(std::size_t n) { return heap::allocate(n); }
void* operator new[](std::size_t n) { return heap::allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return heap::allocate(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return heap::allocate(n, a); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return heap::allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { heap::release(p); }
void operator delete[](void* p) noexcept { heap::release(p); }
void operator delete(void* p, std::size_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::size_t) noexcept { heap::release(p); }
void operator delete(void* p, std::align_val_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { heap::release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { heap::release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { heap::release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { heap::release(p); }

// ---- inputs -----------------------------------------------------------------------
namespace {

namespace gen = deltamesh::gen;
using deltamesh::Point;

struct Case {
  const char* name;
  gen::Kind kind;
  std::size_t n;
  std::uint64_t seed;
  int repetitions;
};

const Case kCases[] = {
    {"uniform_1e5", gen::Kind::Uniform, 100'000, 101, 5},
    {"uniform_1e6", gen::Kind::Uniform, 1'000'000, 102, 5},
    {"uniform_4e6", gen::Kind::Uniform, 4'000'000, 103, 3},
    {"grid_1000x1000", gen::Kind::Grid, 1'000'000, 0, 5},
    {"gaussian_1e6", gen::Kind::Gaussian, 1'000'000, 104, 5},
};

// Generated once per case and kept for the whole run.
const std::vector<Point>& input(const Case& c) {
  static std::map<std::string, std::vector<Point>> cache;
  auto it = cache.find(c.name);
  if (it == cache.end()) it = cache.emplace(c.name, gen::generate(c.kind, c.n, c.seed).points).first;
  return it->second;
}

using Clock = std::chrono::steady_clock;

// Common loop: `run` triangulates once and returns the triangle count.
template <class Run>
void measure(benchmark::State& state, std::size_t n, Run&& run) {
  double total_us = 0.0;
  std::int64_t peak_bytes = 0;
  std::size_t tris = 0;
  for (auto _ : state) {
    const std::int64_t base = heap::start();
    const auto t0 = Clock::now();
    tris = run(base, peak_bytes);
    total_us += std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    if (tris == 0) break;  // run() called SkipWithError
  }
  if (tris == 0) return;
  state.counters["us_per_pt"] = benchmark::Counter(total_us / static_cast<double>(n), benchmark::Counter::kAvgIterations);
  state.counters["tris"] = static_cast<double>(tris);
  state.counters["B_per_tri"] = static_cast<double>(peak_bytes) / static_cast<double>(tris);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}

void bm_deltamesh(benchmark::State& state, const Case* c) {
  const std::vector<Point>& pts = input(*c);
  measure(state, pts.size(), [&](std::int64_t base, std::int64_t& peak_bytes) -> std::size_t {
    try {
      deltamesh::Mesh mesh = deltamesh::delaunay(pts);
      peak_bytes = heap::peak.load() - base;
      benchmark::DoNotOptimize(mesh);
      if (mesh.num_triangles() == 0) state.SkipWithError("no triangles");
      return mesh.num_triangles();
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      return 0;
    }
  });
}

#ifdef DELTAMESH_HAVE_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Cgal_dt = CGAL::Delaunay_triangulation_2<K>;

const std::vector<K::Point_2>& cgal_input(const Case& c) {
  static std::map<std::string, std::vector<K::Point_2>> cache;
  auto it = cache.find(c.name);
  if (it == cache.end()) {
    std::vector<K::Point_2> v;
    v.reserve(c.n);
    for (const Point& p : input(c)) v.emplace_back(p.x, p.y);
    it = cache.emplace(c.name, std::move(v)).first;
  }
  return it->second;
}

void bm_cgal(benchmark::State& state, const Case* c) {
  const std::vector<K::Point_2>& pts = cgal_input(*c);
  measure(state, pts.size(), [&](std::int64_t base, std::int64_t& peak_bytes) {
    Cgal_dt dt;
    dt.insert(pts.begin(), pts.end());  // range insert: spatial sort first
    peak_bytes = heap::peak.load() - base;
    benchmark::DoNotOptimize(dt);
    return dt.number_of_faces();
  });
}
#endif

void register_all() {
  for (const Case& c : kCases) {
    auto setup = [&c](benchmark::internal::Benchmark* b) {
      b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(c.repetitions)->ReportAggregatesOnly(true);
    };
    setup(benchmark::RegisterBenchmark((std::string("delaunay/deltamesh/") + c.name).c_str(), bm_deltamesh, &c));
#ifdef DELTAMESH_HAVE_CGAL
    setup(benchmark::RegisterBenchmark((std::string("delaunay/cgal/") + c.name).c_str(), bm_cgal, &c));
#endif
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
#ifdef DELTAMESH_HAVE_CGAL
  benchmark::AddCustomContext("cgal", "CGAL " CGAL_VERSION_STR " Delaunay_triangulation_2<Epick>, range insert");
#else
  benchmark::AddCustomContext("cgal", "not built (CGAL not found at configure time)");
#endif
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
