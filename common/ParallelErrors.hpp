#pragma once
// Exceptions in OpenMP parallel regions. An exception that leaves an iteration of a
// `#pragma omp parallel for` cannot leave the region: the program ends in std::terminate.
// Each iteration's body runs through ParallelErrors::run, which keeps the first exception
// and skips the iterations after it; after the region, rethrow() throws it on the calling
// thread, where the caller's error handling sees it as it would a serial loop's.
//
//   ParallelErrors errors;
//   #pragma omp parallel for
//   for (int k = 0; k < n; ++k) errors.run([&] { body(k); });
//   errors.rethrow();
#include <atomic>
#include <exception>
#include <mutex>

namespace umbra {

class ParallelErrors {
 public:
  template <class Body>
  void run(Body&& body) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      body();
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!first_) first_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }
  /// True once an iteration has thrown (the later ones are skipped).
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  /// Throws the first exception, if any; call after the parallel region.
  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr first_;
};

}  // namespace umbra
