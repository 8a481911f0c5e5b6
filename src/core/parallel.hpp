// Threads for coarse-grained work: a handful of large tasks (one per part of
// a decomposition), so plain threads and an atomic task counter are
// enough; a work-stealing scheduler (TBB) would add a dependency for nothing
// at this grain (docs/scaling.md).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace deltamesh::detail {

// The thread count an option asks for: 0 means every hardware thread.
inline unsigned resolve_threads(unsigned requested) {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
  (void)requested;
  return 1;  // the WebAssembly build has no threads
#endif
  if (requested != 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

// Runs task(i) for every i in [0, count) on up to `threads` threads, the
// calling one included; tasks are taken in index order. After all have run,
// the exception of the lowest-numbered task that threw (if any) is rethrown,
// so which error a caller sees does not depend on scheduling.
template <class Task>
void run_tasks(std::size_t count, unsigned threads, Task&& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  {
    const std::size_t helpers = std::min<std::size_t>(std::max(1u, threads), count) - (count > 0 ? 1 : 0);
    std::vector<std::thread> pool;
    // Joins on every exit, as std::jthread would (the WebAssembly build's
    // libc++ has no jthread).
    struct Join {
      std::vector<std::thread>& pool;
      ~Join() {
        for (std::thread& t : pool)
          if (t.joinable()) t.join();
      }
    } join{pool};
    pool.reserve(helpers);
    for (std::size_t k = 0; k < helpers; ++k) pool.emplace_back(worker);
    worker();
  }  // joined here
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

// Replaces `slot` by `value` while replace(current) holds, atomically
// (relaxed order): for arrays the scan threads write concurrently, where
// the result must not depend on the interleaving. std::atomic_ref where the
// standard library has it (emscripten 3.1's libc++ has not; the web build
// runs one thread), else the compiler's __atomic builtins it is made of.
template <class T, class Replace>
void atomic_replace_while(T& slot, T value, Replace replace) {
#if defined(__cpp_lib_atomic_ref)
  std::atomic_ref<T> a(slot);
  T cur = a.load(std::memory_order_relaxed);
  while (replace(cur) && !a.compare_exchange_weak(cur, value, std::memory_order_relaxed)) {
  }
#else
  T cur = __atomic_load_n(&slot, __ATOMIC_RELAXED);
  while (replace(cur) && !__atomic_compare_exchange_n(&slot, &cur, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
#endif
}

}  // namespace deltamesh::detail
