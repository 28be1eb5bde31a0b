// Work spread over threads with results in a fixed order, so a result never depends on how many
// threads ran it: the derivation evaluates candidate units side by side with it.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace shadesim {

// `requested` threads, or the hardware's where it is 0 (at least 1).
inline int thread_count(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// f(i) for every i in [0, n), on up to `threads` threads (0: the hardware's); result i at index
// i. Where calls throw, the exception of the lowest index is rethrown after every call ended.
template <class T, class F>
std::vector<T> parallel_map(size_t n, int threads, F f) {
  std::vector<T> out(n);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t i = next++; i < n; i = next++) {
      try {
        out[i] = f(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const size_t helpers = std::min(n, static_cast<size_t>(thread_count(threads))) - (n > 0 ? 1 : 0);
  std::vector<std::thread> pool;
  for (size_t t = 0; t < helpers; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  for (auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return out;
}

}  // namespace shadesim
