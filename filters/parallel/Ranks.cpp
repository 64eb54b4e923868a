#include "Ranks.hpp"

#include <vtkCommunicator.h>
#include <vtkMPIController.h>
#include <vtkMultiProcessController.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <stdexcept>

namespace umbra::parallel {

Ranks* Ranks::world_ = nullptr;

namespace {

vtkMPIController* controllerOf(void* c) { return static_cast<vtkMPIController*>(c); }

/// Adds the seconds from its making to its end to `total`.
class Timed {
public:
  explicit Timed(double& total) : total(total), start(std::chrono::steady_clock::now()) {}
  ~Timed() { total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }

private:
  double& total;
  std::chrono::steady_clock::time_point start;
};

}  // namespace

std::pair<std::size_t, std::size_t> share(std::size_t count, int rank, int size) {
  if (size < 1 || rank < 0 || rank >= size) throw std::invalid_argument("share: rank outside 0..size-1");
  const std::size_t n = static_cast<std::size_t>(size), r = static_cast<std::size_t>(rank);
  const std::size_t base = count / n, extra = count % n;
  const std::size_t begin = r * base + std::min(r, extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}

bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (const char* v = std::getenv(name); v && *v) return true;
  return false;
}

Ranks::Ranks() = default;

Ranks::Ranks(int* argc, char*** argv) {
  if (world_) throw std::logic_error("umbra::parallel::Ranks: made twice");
  if (launchedByMpi()) {
    auto* c = vtkMPIController::New();
    c->Initialize(argc, argv);
    vtkMultiProcessController::SetGlobalController(c);
    controller_ = c;
    rank_ = c->GetLocalProcessId();
    size_ = c->GetNumberOfProcesses();
  }
  world_ = this;
}

Ranks::~Ranks() {
  if (controller_) {
    vtkMultiProcessController::SetGlobalController(nullptr);
    controllerOf(controller_)->Finalize();
    controllerOf(controller_)->Delete();
  }
  if (world_ == this) world_ = nullptr;
}

Ranks& Ranks::world() {
  if (world_) return *world_;
  static Ranks one;  // a process whose main() made none (a test): one rank
  return one;
}

void Ranks::barrier() {
  if (!controller_) return;
  const Timed t(collectiveSeconds_);
  controllerOf(controller_)->Barrier();
}

template <class T>
std::vector<T> Ranks::gatherValues(const std::vector<T>& values) {
  if (!controller_) return values;
  const Timed t(collectiveSeconds_);
  vtkMPIController* c = controllerOf(controller_);
  const vtkIdType length = static_cast<vtkIdType>(values.size());
  std::vector<vtkIdType> lengths(root() ? size_ : 1);
  c->Gather(&length, lengths.data(), 1, 0);
  std::vector<vtkIdType> counts, offsets;
  vtkIdType total = 0;
  if (root())
    for (vtkIdType l : lengths) {
      counts.push_back(l);
      offsets.push_back(total);
      total += l;
    }
  std::vector<T> all(root() ? total : 0);
  c->GatherV(values.data(), all.data(), length, counts.data(), offsets.data(), 0);
  return all;
}

std::vector<float> Ranks::gather(const std::vector<float>& values) { return gatherValues(values); }

std::vector<float> Ranks::allGather(const std::vector<float>& values) {
  if (!controller_) return values;
  const Timed t(collectiveSeconds_);
  vtkMPIController* c = controllerOf(controller_);
  const vtkIdType length = static_cast<vtkIdType>(values.size());
  std::vector<vtkIdType> lengths(size_), offsets(size_);
  c->AllGather(&length, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < size_; ++r) {
    offsets[r] = total;
    total += lengths[r];
  }
  std::vector<float> all(static_cast<std::size_t>(total));
  c->AllGatherV(values.data(), all.data(), length, lengths.data(), offsets.data());
  return all;
}
std::vector<double> Ranks::gather(const std::vector<double>& values) { return gatherValues(values); }

std::vector<std::string> Ranks::gather(const std::string& message) {
  if (!controller_) return {message};
  // The messages with their lengths in front: one gather of characters.
  std::vector<char> mine(message.begin(), message.end());
  const std::vector<char> all = gatherValues(mine);
  const vtkIdType length = static_cast<vtkIdType>(message.size());
  std::vector<vtkIdType> lengths(root() ? size_ : 1);
  {
    const Timed t(collectiveSeconds_);
    controllerOf(controller_)->Gather(&length, lengths.data(), 1, 0);
  }
  std::vector<std::string> out;
  if (!root()) return out;
  std::size_t at = 0;
  for (vtkIdType l : lengths) {
    out.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(at), all.begin() + static_cast<std::ptrdiff_t>(at + l));
    at += static_cast<std::size_t>(l);
  }
  return out;
}

bool Ranks::all(bool mine) {
  if (!controller_) return mine;
  const Timed t(collectiveSeconds_);
  const int in = mine ? 1 : 0;
  int out = 0;
  controllerOf(controller_)->AllReduce(&in, &out, 1, vtkCommunicator::MIN_OP);
  return out == 1;
}

std::string Ranks::broadcast(const std::string& value) {
  if (!controller_) return value;
  const Timed t(collectiveSeconds_);
  vtkMPIController* c = controllerOf(controller_);
  vtkIdType length = root() ? static_cast<vtkIdType>(value.size()) : 0;
  c->Broadcast(&length, 1, 0);
  std::string out = root() ? value : std::string(static_cast<std::size_t>(length), '\0');
  if (length > 0) c->Broadcast(out.data(), length, 0);
  return out;
}

std::string Ranks::finish(const std::string& error) {
  const std::vector<std::string> errors = gather(error);
  std::string joined;
  for (std::size_t r = 0; r < errors.size(); ++r) {
    if (errors[r].empty()) continue;
    if (!joined.empty()) joined += "; ";
    joined += size_ > 1 ? "rank " + std::to_string(r) + ": " + errors[r] : errors[r];
  }
  joined = broadcast(joined);
  // After the broadcast, where a rank that finished early has waited for rank 0 (a gather
  // does not wait: its small messages go out at once).
  const std::vector<double> waits = gather(std::vector<double>{collectiveSeconds_});
  for (double w : waits) mostCollectiveSeconds_ = std::max(mostCollectiveSeconds_, w);
  return joined;
}

}  // namespace umbra::parallel
