#include "io/atomic_output.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/temporary_files.hpp"

namespace periadapt {

namespace {

std::string reason() { return std::strerror(errno); }

void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw OutputError("cannot write " + path + ": " + reason());
  const bool ok = ::fsync(fd) == 0;
  const std::string why = ok ? "" : reason();
  ::close(fd);
  if (!ok) throw OutputError("cannot write " + path + ": " + why);
}

// Where the content of `path` goes: a symbolic link is written through (its target gets the
// file, the link stays); a name that is not a regular file (a device, a FIFO, a folder) is
// refused, since a rename over it would replace it.
std::string output_target(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string target = path;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path resolved = fs::weakly_canonical(path, ec);
    if (ec) throw OutputError("cannot write " + path + ": the link cannot be followed: " + ec.message());
    target = resolved.string();
  }
  const fs::file_status st = fs::status(target, ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw OutputError("cannot write " + path + ": it exists and is not a regular file (" +
                      (fs::is_directory(st) ? std::string("a folder") : std::string("a device, FIFO or socket")) +
                      "); name a file");
  return target;
}

}  // namespace

void commit_file(const std::string& tmp, const std::string& path) {
  try {
    const std::string target = output_target(path);
    sync_file(tmp);
    std::error_code ec;
    if (target != path) {
      // The link's target may lie on another file system: a copy beside it, then a rename.
      const std::string near = target + ".tmp";
      const TemporaryFileGuard near_guard(near);
      std::filesystem::copy_file(tmp, near, std::filesystem::copy_options::overwrite_existing, ec);
      if (!ec) {
        std::error_code ignore;
        try {
          sync_file(near);
        } catch (...) {
          std::filesystem::remove(near, ignore);
          throw;
        }
        std::filesystem::rename(near, target, ec);
        if (ec) std::filesystem::remove(near, ignore);
      }
      if (ec) throw OutputError("cannot write " + path + " (through its link to " + target + "): " + ec.message());
      std::error_code ignore;
      std::filesystem::remove(tmp, ignore);
      return;
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw OutputError("cannot write " + path + ": " + ec.message());
  } catch (...) {
    std::error_code ignore;
    std::filesystem::remove(tmp, ignore);
    throw;
  }
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill,
                           bool binary) {
  output_target(path);  // refused before anything is written
  const std::string tmp = path + ".tmp";
  const TemporaryFileGuard guard(tmp);
  {
    std::ofstream out(tmp, binary ? std::ios::binary : std::ios::out);
    if (!out) throw OutputError("cannot write " + path + ": " + reason());
    fill(out);
    out.flush();
    const bool ok = static_cast<bool>(out);
    out.close();
    if (!ok || out.fail()) {
      const std::string why = reason();
      std::error_code ignore;
      std::filesystem::remove(tmp, ignore);
      throw OutputError("cannot write " + path + ": " + why + " (disk full?)");
    }
  }
  commit_file(tmp, path);
}

StreamedOutput::StreamedOutput(std::string path)
    : path_(std::move(path)), part_(path_ + ".part"), out_(part_) {
  if (!out_) throw OutputError("cannot write " + part_ + ": " + reason());
}

StreamedOutput& StreamedOutput::operator<<(const std::string& text) {
  out_ << text;
  if (!out_) throw OutputError("cannot write " + part_ + ": " + reason() + " (disk full?)");
  return *this;
}

std::string StreamedOutput::text_so_far() {
  out_.flush();
  if (!out_) throw OutputError("cannot write " + part_ + ": " + reason() + " (disk full?)");
  std::ifstream in(part_, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw OutputError("cannot read back " + part_ + ": " + reason());
  return text;
}

void StreamedOutput::finish() {
  if (!out_.is_open()) return;
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail())
    throw OutputError("cannot write " + part_ + ": " + reason() + " (disk full?)");
  commit_file(part_, path_);
}

OutputFolderLock::OutputFolderLock(const std::string& dir) {
  const std::string path = dir + "/.periadapt.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw OutputError("cannot write into " + dir + ": " + reason());
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw OutputError("another run is writing into " + dir +
                      "; give this one its own folder with --out");
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace periadapt
