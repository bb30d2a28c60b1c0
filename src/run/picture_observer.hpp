#pragma once
// Damage pictures (PNG) at output.png_times and at the end.
#include <set>

#include "run/observer.hpp"

namespace periadapt {

// A name this observer gives its pictures (damage_<t>us.png).
bool is_damage_picture(const std::string& file_name);

class PictureObserver : public RunObserver {
 public:
  explicit PictureObserver(const RunView& view, double dt);
  void on_step(RunView& view, long step, bool closing) override;
  // It draws damage at reference positions, which every rank holds current.
  bool wants_state(const RunView&, long) const override { return false; }
  void save(ArchiveWriter& w) override;
  void restore(ArchiveReader& r, RunView& view) override;
  void finish(RunView& view, RunResult& result) override;

 private:
  std::set<long> steps_;
  std::vector<std::string> written_;
};

}  // namespace periadapt
