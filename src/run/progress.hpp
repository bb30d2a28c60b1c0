#pragma once
// Progress report: a redrawn bar with ETA on a terminal, plain periodic lines otherwise.
#include <chrono>
#include <cstdio>
#include <string>

namespace periadapt {

class Progress {
 public:
  Progress(long total, bool quiet);
  void update(long done, const std::string& note = "");
  void finish();

 private:
  long total_;
  bool quiet_, tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace periadapt
