#pragma once
// The ranks of a run. Under an MPI launcher (mpirun, srun: the launcher's variables in the
// environment) umbra's processes are the ranks of VTK's vtkMPIController; run directly,
// umbra is one rank and MPI is not started at all.
//
// Work is split into contiguous shares (share()); each rank does its share and reports
// how it went with finish(), a collective that every rank reaches (also after an error:
// a rank that throws catches, records the message and goes on to finish()), so that rank 0
// can name every rank's error and no rank keeps output that another's failure spoils.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace umbra::parallel {

/// The [begin, end) of `count` items that rank `rank` of `size` takes: contiguous, the
/// first count % size ranks one item more.
std::pair<std::size_t, std::size_t> share(std::size_t count, int rank, int size);

/// Whether an MPI launcher started this process (OMPI_COMM_WORLD_SIZE, PMI_SIZE or
/// PMIX_RANK in the environment).
bool launchedByMpi();

class Ranks {
public:
  /// Starts MPI when launchedByMpi() (VTK's global controller then is the MPI one); one
  /// Ranks per process, made in main() before any other use and ended with it.
  Ranks(int* argc, char*** argv);
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  /// The process's Ranks (throws std::logic_error when main() made none: a test's
  /// process is one rank, and gets a one-rank Ranks here).
  static Ranks& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool mpi() const { return controller_ != nullptr; }

  void barrier();
  /// Every rank's `message` on rank 0 (in rank order), empty elsewhere. Collective.
  std::vector<std::string> gather(const std::string& message);
  /// Whether `mine` holds on every rank, on every rank. Collective.
  bool all(bool mine);
  /// Rank 0's `value` on every rank. Collective.
  std::string broadcast(const std::string& value);
  /// Every rank's `values`, concatenated in rank order, on rank 0 (empty elsewhere).
  /// Collective; the ranks' lengths may differ.
  std::vector<float> gather(const std::vector<float>& values);
  std::vector<double> gather(const std::vector<double>& values);
  /// As gather, the result on every rank.
  std::vector<float> allGather(const std::vector<float>& values);

  /// The end of a share of work, collective: `error` is this rank's (empty: it went well).
  /// On every rank: the errors of all ranks, "rank R: message" joined by "; " (empty when
  /// every rank succeeded). Rank 0 also learns each rank's time in collectives.
  std::string finish(const std::string& error);

  /// Seconds spent so far in this rank's collectives (waiting for the other ranks
  /// included): the communication and load imbalance of a run.
  double collectiveSeconds() const { return collectiveSeconds_; }
  /// On rank 0: the most any rank had spent in collectives at the last finish() (the
  /// rank that waited longest for the others); elsewhere 0.
  double mostCollectiveSeconds() const { return mostCollectiveSeconds_; }

private:
  Ranks();  // one rank, no MPI
  template <class T>
  std::vector<T> gatherValues(const std::vector<T>& values);

  int rank_ = 0, size_ = 1;
  double collectiveSeconds_ = 0.0, mostCollectiveSeconds_ = 0.0;
  void* controller_ = nullptr;  // vtkMPIController*, when MPI runs
  static Ranks* world_;
};

}  // namespace umbra::parallel
