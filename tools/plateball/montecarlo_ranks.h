// `plateball montecarlo` over MPI (optional): when the tool is built with MPI
// (PLATEBALL_WITH_MPI, CMake finds Open MPI) and started by mpirun or srun, the trials are split
// over the ranks and gathered on rank 0, which writes the outputs; otherwise one rank runs them
// all (on threads). The records are pure functions of their task index, so the gathered summary
// is byte-identical for any number of ranks.
#pragma once

#include <string>
#include <vector>

#include "plateball/monte_carlo.h"

namespace plateball::tools {

class Ranks {
 public:
  /// Initialises MPI when built with it and launched by an MPI starter (the environment has
  /// OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK); else a single rank.
  Ranks();
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// "MPI" or "threads": how this build splits trials across processes.
  static std::string Transport();
  /// This rank's share [begin, end) of `total` tasks (contiguous blocks).
  std::pair<long long, long long> Share(long long total) const;
  /// Every rank's records in rank order, on rank 0 (other ranks get an empty vector).
  std::vector<TrialRecord> Gather(const std::vector<TrialRecord>& local) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool initialized_ = false;
};

}  // namespace plateball::tools
