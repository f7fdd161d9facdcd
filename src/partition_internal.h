// MakePartition with the name of a uniform rule's n given: a command-line option or a list entry
// (e.g. "command line: --impulses", "plan.converge_n[2]") that replaced the file's n.
#pragma once

#include <string>
#include <vector>

#include "plateball/partition.h"

namespace plateball::internal {

/// plateball::MakePartition, naming the n of a single uniform rule `n_field` when it is not empty
/// (else `field`.n): an n too small for a closed path or too large for a short one is the fault of
/// the value the user gave for n, not of the partition points it produced.
std::vector<std::vector<double>> MakePartition(const Path& path,
                                               const std::vector<PartitionRule>& rules,
                                               const std::string& field,
                                               const std::string& n_field);

}  // namespace plateball::internal
