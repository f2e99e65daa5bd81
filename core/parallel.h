// Runs fn(begin, end) over [0, count) in chunks on `threads` threads (0: all
// cores); the first exception thrown by any chunk stops the rest and is
// rethrown on the caller's thread.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace vgi {

inline int resolveThreads(int threads) {
  return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

template <class Fn>
void parallelFor(size_t count, size_t chunk, int threads, Fn&& fn) {
  chunk = std::max<size_t>(1, chunk);
  const size_t chunks = (count + chunk - 1) / chunk;
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto work = [&] {
    for (size_t c; (c = next.fetch_add(1)) < chunks;) {
      try {
        fn(c * chunk, std::min(count, (c + 1) * chunk));
      } catch (...) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (!error) error = std::current_exception();
        next = chunks;
      }
    }
  };
  const int n = std::min<int>(resolveThreads(threads), int(std::max<size_t>(1, chunks)));
  if (n <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (int i = 0; i < n; ++i) pool.emplace_back(work);
    for (auto& th : pool) th.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace vgi
