#pragma once
// The temporary names that atomic writes (io/atomic_output.hpp, io/png_file.cpp) have open: a
// process ended by a second signal removes them on its way out, so that an interrupted write
// leaves neither a corrupt file in place of a good one nor a stray FILE.tmp beside it.
#include <string>

namespace periadapt {

// Marks `path` as a temporary being written until the guard goes (renamed or removed by then).
class TemporaryFileGuard {
 public:
  explicit TemporaryFileGuard(const std::string& path);
  ~TemporaryFileGuard();
  TemporaryFileGuard(const TemporaryFileGuard&) = delete;
  TemporaryFileGuard& operator=(const TemporaryFileGuard&) = delete;

 private:
  int slot_ = -1;  // -1: the path did not fit the table and is not tracked
};

// Unlinks every marked temporary. Async-signal-safe: only unlink(2) on preset buffers.
void remove_temporary_files_now() noexcept;

}  // namespace periadapt
