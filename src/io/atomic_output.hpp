#pragma once
// Output files that never leave a corrupt file in place of a good one. Content goes to a
// temporary name in the same folder; it is flushed, synced to disk and closed, each step checked,
// and only then renamed over the final name. On any failure the temporary is removed, the final
// name keeps what it had, and OutputError says which file and why.
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

namespace periadapt {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `path` from what `fill` puts into the stream.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill,
                           bool binary = false);

// Moves a finished temporary file over `path` (after syncing it); throws OutputError.
void commit_file(const std::string& tmp, const std::string& path);

// A file written row by row during a run (history.csv, refinement.csv): rows go to PATH.part,
// every write is checked, and finish() moves it over PATH. Until then PATH keeps what an earlier
// run left there.
class StreamedOutput {
 public:
  StreamedOutput() = default;
  explicit StreamedOutput(std::string path);
  bool is_open() const { return out_.is_open(); }
  // Everything written so far (a checkpoint keeps it; a restart writes it first).
  std::string text_so_far();
  StreamedOutput& operator<<(const std::string& text);
  void finish();
  const std::string& path() const { return path_; }

 private:
  std::string path_, part_;
  std::ofstream out_;
};

// Takes the output folder for this process: a second run into the same folder is refused while
// the first holds it (the lock goes with the process, also when it is killed). Throws
// OutputError naming the folder.
class OutputFolderLock {
 public:
  explicit OutputFolderLock(const std::string& dir);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace periadapt
