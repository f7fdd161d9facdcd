#include "montecarlo_ranks.h"

#include <cstdlib>
#include <stdexcept>

#ifdef PLATEBALL_WITH_MPI
#include <mpi.h>
#endif

namespace plateball::tools {
namespace {

#ifdef PLATEBALL_WITH_MPI
// A record on the wire: 10 doubles (integers below 2^53 are exact).
constexpr int kRecordDoubles = 10;

bool LaunchedByMpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

void Pack(const TrialRecord& r, double* d) {
  d[0] = r.n;
  d[1] = r.scenario;
  d[2] = static_cast<double>(static_cast<int>(r.strategy));
  d[3] = static_cast<double>(r.trial);
  d[4] = static_cast<double>(static_cast<int>(r.status));
  d[5] = r.position_error;
  d[6] = r.orientation_error;
  d[7] = r.max_pass_miss;
  d[8] = r.total_time;
  d[9] = r.missed_pass_points;
}

TrialRecord Unpack(const double* d) {
  TrialRecord r;
  r.n = static_cast<int>(d[0]);
  r.scenario = static_cast<int>(d[1]);
  r.strategy = static_cast<ExecutionStrategy>(static_cast<int>(d[2]));
  r.trial = static_cast<std::int64_t>(d[3]);
  r.status = static_cast<ExecutionStatus>(static_cast<int>(d[4]));
  r.position_error = d[5];
  r.orientation_error = d[6];
  r.max_pass_miss = d[7];
  r.total_time = d[8];
  r.missed_pass_points = static_cast<int>(d[9]);
  return r;
}
#endif

}  // namespace

Ranks::Ranks() {
#ifdef PLATEBALL_WITH_MPI
  if (!LaunchedByMpi()) return;
  MPI_Init(nullptr, nullptr);
  initialized_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#endif
}

Ranks::~Ranks() {
#ifdef PLATEBALL_WITH_MPI
  if (initialized_) MPI_Finalize();
#endif
}

std::string Ranks::Transport() {
#ifdef PLATEBALL_WITH_MPI
  return "MPI";
#else
  return "threads";
#endif
}

std::pair<long long, long long> Ranks::Share(long long total) const {
  return {total * rank_ / size_, total * (rank_ + 1) / size_};
}

std::vector<TrialRecord> Ranks::Gather(const std::vector<TrialRecord>& local) const {
  if (size_ == 1) return local;
#ifdef PLATEBALL_WITH_MPI
  const int mine = static_cast<int>(local.size()) * kRecordDoubles;
  std::vector<double> send(static_cast<std::size_t>(mine));
  for (std::size_t i = 0; i < local.size(); ++i) Pack(local[i], &send[i * kRecordDoubles]);
  std::vector<int> counts(static_cast<std::size_t>(size_)), displs(counts.size());
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  long long total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    displs[r] = static_cast<int>(total);
    total += counts[r];
  }
  if (total > 2'000'000'000LL) throw std::runtime_error("MPI gather: too many records for one message");
  std::vector<double> all(rank_ == 0 ? static_cast<std::size_t>(total) : 0);
  MPI_Gatherv(send.data(), mine, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  std::vector<TrialRecord> out;
  for (std::size_t i = 0; i < all.size(); i += kRecordDoubles) out.push_back(Unpack(&all[i]));
  return out;
#else
  return local;
#endif
}

}  // namespace plateball::tools
