#pragma once
// The precomputation's parallel loops (OpenMP, dynamic schedule), their progress reports
// and cancellation, and the time each stage took.
#include "ParallelErrors.hpp"
#include "Precompute.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <type_traits>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace umbra::atmosphere::stages {


class Runner {
public:
  Runner(const PrecomputeProgress& progress, int threads, double begin, double end)
      : progress_(progress), threads_(threads), begin_(begin), end_(end) {}

  void setStages(double totalWeight) { total_ = totalWeight; }

  /// f(i) for i in [0, n), OpenMP dynamic schedule, reported in chunks. The threads call a
  /// copy of f on cache lines of its own: f's captures are read on every access, and f
  /// itself may sit right above the stack that the calling thread, one of the workers,
  /// writes (a shared line costs the density stage up to 20 % with 2 threads).
  template <class F>
  void run(const std::string& stage, double weight, int n, F&& fIn) {
    run(stage, weight, n, std::forward<F>(fIn), 0, {});
  }
  /// The same in steps of `stepTasks` tasks (0: the chunks of progress), each finished
  /// before the next starts; between(done) before each step and after the last, every task
  /// below `done` finished and none above started (so that the tables' spilled slices
  /// behind the work can go, and those ahead come in).
  template <class F>
  void run(const std::string& stage, double weight, int n, F&& fIn, int stepTasks,
           const std::function<void(int done)>& between) {
    struct alignas(128) Isolated {
      std::decay_t<F> f;
      char pad[128];
    };
    const Isolated isolated{fIn, {}};
    const auto& f = isolated.f;
    const auto t0 = std::chrono::steady_clock::now();
    const int nt = threadCount();
    // Up to 16 reports, each chunk at least 4 tasks per thread: a stage of few tasks would
    // otherwise run one task at a time.
    const int chunks = stepTasks > 0 ? (n + stepTasks - 1) / stepTasks : std::max(1, std::min(n / (4 * nt), 16));
    for (int k = 0; k < chunks; ++k) {
      const int lo = stepTasks > 0 ? k * stepTasks : static_cast<int>(static_cast<long long>(n) * k / chunks);
      const int hi = stepTasks > 0 ? std::min(n, lo + stepTasks)
                                   : static_cast<int>(static_cast<long long>(n) * (k + 1) / chunks);
      if (between) between(lo);
      ParallelErrors errors;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
#endif
      for (int i = lo; i < hi; ++i) errors.run([&] { f(i); });
      errors.rethrow();
      report(stage, done_ + weight * (k + 1) / chunks);
    }
    if (between) between(n);
    done_ += weight;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    timings[stage] += s;
    if (std::find(order.begin(), order.end(), stage) == order.end()) order.push_back(stage);
  }

  /// The threads run() uses.
  int threadCount() const {
#ifdef _OPENMP
    return threads_ > 0 ? threads_ : omp_get_max_threads();
#else
    return 1;
#endif
  }

  std::map<std::string, double> timings;
  std::vector<std::string> order;

private:
  void report(const std::string& stage, double done) {
    if (!progress_) return;
    const double f = begin_ + (end_ - begin_) * std::clamp(total_ > 0 ? done / total_ : 1.0, 0.0, 1.0);
    if (!progress_(f, stage)) throw PrecomputeCancelled();
  }
  const PrecomputeProgress& progress_;
  int threads_;
  double begin_, end_, total_ = 1.0, done_ = 0.0;
};

}  // namespace umbra::atmosphere::stages
