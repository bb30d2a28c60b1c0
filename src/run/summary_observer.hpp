#pragma once
// summary.json: the run's status, counts, time step, timings, memory, material and grid, with
// what the other observers added to it; written last, atomically.
#include <nlohmann/json.hpp>

#include "parallel/row_partition.hpp"
#include "run/observer.hpp"

namespace periadapt {

// summary.json's `ranks` of a distributed run: rank count, partition method, partitions made,
// events that kept the partition, the rebalance threshold and the final work imbalance; with
// `owned_evaluations` (this rank's; collective) also how evenly the ranks shared the bond
// evaluations over the run.
nlohmann::json ranks_json(const RowPartition& p, double owned_evaluations = -1);

class SummaryObserver : public RunObserver {
 public:
  explicit SummaryObserver(const RunView& view);
  bool wants_state(const RunView&, long) const override { return false; }
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  // Keep it last in the observer list: it writes the file the others filled in.
  void finish(RunView& view, RunResult& result) override;

 private:
  std::size_t initial_nodes_;
};

}  // namespace periadapt
