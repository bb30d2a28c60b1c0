#include "run/checkpoint_file.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <fstream>

#include "core/binary_archive.hpp"
#include "input/deck_error.hpp"
#include "io/atomic_output.hpp"

#ifndef PERIADAPT_BUILD_ID
#define PERIADAPT_BUILD_ID "unknown"
#endif

namespace periadapt {

namespace {
constexpr char kMagic[] = "PERIADAPT CHECKPOINT\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;

// FNV-1a over bytes that may arrive in parts.
struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;
  void add(const char* p, std::size_t n) {
    for (std::size_t k = 0; k < n; ++k)
      h = (h ^ static_cast<unsigned char>(p[k])) * 1099511628211ull;
  }
};
std::uint64_t fnv1a(const std::string& s) {
  Fnv1a f;
  f.add(s.data(), s.size());
  return f.h;
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw DeckError(path, 0, 0, "--restart", what);
}

// The header's fields, in file order.
template <class Archive, class Info>
void info_fields(Archive&& a, Info& info) {
  a(info.build);
  a(info.deck);
  a(info.deck_file);
  a(info.threads);
  a(info.step);
  a(info.time);
}

// A checkpoint file's header, read from the start of `in` and checked against this build and
// deck; leaves `in` at the payload.
struct Header {
  CheckpointInfo info;
  std::uint64_t payload_size = 0, sum = 0;
  Fnv1a head_sum;  // the checksum covers the header's fields too (deck, step, time)
};
Header read_header(std::istream& in, const std::string& path, const Deck& dk) {
  in.seekg(0, std::ios::end);
  const std::streamoff file_size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  in.seekg(0);
  if (file_size < 0 || !in) refuse(path, "cannot read the file");
  auto bytes = [&](std::size_t n, const char* what) {
    std::string s(n, '\0');
    if (!in.read(s.data(), static_cast<std::streamsize>(n)))
      refuse(path, fmt::format("ends inside its {} (truncated or corrupt)", what));
    return s;
  };
  auto value = [&](const char* what) {
    std::uint64_t v = 0;
    std::memcpy(&v, bytes(sizeof v, what).data(), sizeof v);
    return v;
  };
  if (file_size < static_cast<std::streamoff>(kMagicSize) || bytes(kMagicSize, "header") != kMagic)
    refuse(path, "not a PeriAdapt checkpoint (no header)");
  std::uint32_t format = 0;
  std::memcpy(&format, bytes(sizeof format, "header").data(), sizeof format);
  if (format != kCheckpointFormat)
    refuse(path, fmt::format("checkpoint format {}; this build reads format {}", format,
                             kCheckpointFormat));
  const std::uint64_t hsize = value("header");
  if (hsize > static_cast<std::uint64_t>(file_size))
    refuse(path, "header length out of range (corrupt)");
  const std::string head = bytes(hsize, "header");
  Header h;
  h.head_sum.add(head.data(), head.size());
  try {
    ArchiveReader r(head, path);
    info_fields([&](auto& v) { r.get(v); }, h.info);
  } catch (const ArchiveError& e) {
    refuse(path, e.what());
  }
  h.payload_size = value("header");
  h.sum = value("header");
  const auto left = static_cast<std::uint64_t>(file_size - static_cast<std::streamoff>(in.tellg()));
  if (left != h.payload_size)
    refuse(path, fmt::format("the payload holds {} bytes, the header says {} (truncated or "
                             "corrupt)", left, h.payload_size));
  if (h.info.build != build_id())
    refuse(path, fmt::format("written by build '{}', this is '{}': a restart continues bit for "
                             "bit only with the program that wrote it",
                             h.info.build, build_id()));
  if (h.info.deck != deck_fingerprint(dk))
    refuse(path, fmt::format("written for another deck ({}); only output settings, "
                             "solver.end_time and solver.steps may change on a restart",
                             h.info.deck_file));
  return h;
}

// A payload read from its file in order, its checksum taken on the way.
class FileStream final : public ArchiveStream {
 public:
  FileStream(std::istream& in, std::uint64_t size, std::string path, Fnv1a start)
      : in_(in), left_(size), path_(std::move(path)), sum_(start) {}
  void read(void* to, std::size_t n) override {
    if (n > left_)
      throw ArchiveError(path_ + ": ends inside its data (truncated or corrupt)");
    if (n && !in_.read(static_cast<char*>(to), static_cast<std::streamsize>(n)))
      throw ArchiveError(path_ + ": cannot read the file");
    sum_.add(static_cast<const char*>(to), n);
    left_ -= n;
  }
  void skip(std::uint64_t n) override {
    std::array<char, 1 << 16> buf;
    while (n > 0) {
      const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(n, buf.size()));
      read(buf.data(), k);
      n -= k;
    }
  }
  std::uint64_t left() const { return left_; }
  std::uint64_t sum() const { return sum_.h; }

 private:
  std::istream& in_;
  std::uint64_t left_;
  std::string path_;
  Fnv1a sum_;
};
}  // namespace

std::string build_id() { return PERIADAPT_BUILD_ID; }

std::string deck_fingerprint(const Deck& dk) { return fmt::format("{:016x}", fnv1a(dk.physics_text)); }

std::uint64_t write_checkpoint_parts(const std::string& path, const CheckpointInfo& info,
                                     const PayloadProducer& produce) {
  ArchiveWriter head;
  info_fields([&](const auto& v) { head.put(v); }, info);
  Fnv1a sum;
  sum.add(head.bytes().data(), head.bytes().size());
  std::uint64_t size = 0;
  produce([&](const char* p, std::size_t n) {
    sum.add(p, n);
    size += n;
  });
  std::uint64_t written = 0;
  write_file_atomically(path, [&](std::ostream& o) {
    o.write(kMagic, kMagicSize);
    const std::uint32_t format = kCheckpointFormat;
    const std::uint64_t hsize = head.bytes().size();
    o.write(reinterpret_cast<const char*>(&format), sizeof format);
    o.write(reinterpret_cast<const char*>(&hsize), sizeof hsize);
    o << head.bytes();
    o.write(reinterpret_cast<const char*>(&size), sizeof size);
    o.write(reinterpret_cast<const char*>(&sum.h), sizeof sum.h);
    produce([&](const char* p, std::size_t n) {
      o.write(p, static_cast<std::streamsize>(n));
      written += n;
    });
    if (written != size) throw std::logic_error("a checkpoint payload that changed while written");
  }, true);
  return sum.h;
}

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const std::string& payload) {
  write_checkpoint_parts(path, info,
                         [&](const ArchiveSink& out) { out(payload.data(), payload.size()); });
}

Checkpoint read_checkpoint(const std::string& path_or_dir, const Deck& dk) {
  namespace fs = std::filesystem;
  std::error_code ec;
  Checkpoint c;
  c.path = fs::is_directory(path_or_dir, ec) ? path_or_dir + "/" + kCheckpointName : path_or_dir;
  if (!fs::is_regular_file(c.path, ec))
    refuse(c.path, "no checkpoint here (a run writes checkpoint.bin into its output folder every "
                   "output.checkpoint_every steps and when stopped by SIGINT or SIGTERM)");
  std::ifstream in(c.path, std::ios::binary);
  const Header h = read_header(in, c.path, dk);
  c.info = h.info;
  c.payload.resize(h.payload_size);
  if (!in.read(c.payload.data(), static_cast<std::streamsize>(h.payload_size)))
    refuse(c.path, "cannot read the file");
  Fnv1a sum = h.head_sum;
  sum.add(c.payload.data(), c.payload.size());
  if (sum.h != h.sum) refuse(c.path, "checksum mismatch: the file is corrupt");
  return c;
}

void read_checkpoint_piece(const std::string& path, const Deck& dk, std::uint64_t sum,
                           const std::function<void(ArchiveStream&)>& parse) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    refuse(path, "missing: the checkpoint keeps each rank's bond rows in a piece beside it, and "
                 "a restart reads those with its rows (copy the pieces with checkpoint.bin)");
  std::ifstream in(path, std::ios::binary);
  const Header h = read_header(in, path, dk);
  if (h.sum != sum) refuse(path, "this piece belongs to another checkpoint than the one beside it");
  FileStream s(in, h.payload_size, path, h.head_sum);
  parse(s);
  if (s.left() != 0) refuse(path, "data past the piece's rows (corrupt)");
  if (s.sum() != sum) refuse(path, "checksum mismatch: the file is corrupt");
}

}  // namespace periadapt
