#include "run/checkpoint_file.hpp"

#include <fmt/core.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_output.hpp"
#include "core/binary_archive.hpp"
#include "input/deck_error.hpp"

#ifndef PERIADAPT_BUILD_ID
#define PERIADAPT_BUILD_ID "unknown"
#endif

namespace periadapt {

namespace {
constexpr char kMagic[] = "PERIADAPT CHECKPOINT\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw DeckError(path, 0, 0, "--restart", what);
}
}  // namespace

std::string build_id() { return PERIADAPT_BUILD_ID; }

std::string deck_fingerprint(const Deck& dk) { return fmt::format("{:016x}", fnv1a(dk.physics_text)); }

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const std::string& payload) {
  ArchiveWriter head;
  head.put(info.build);
  head.put(info.deck);
  head.put(info.deck_file);
  head.put(info.threads);
  head.put(info.step);
  head.put(info.time);
  write_file_atomically(path, [&](std::ostream& o) {
    o.write(kMagic, kMagicSize);
    const std::uint32_t format = kCheckpointFormat;
    const std::uint64_t hsize = head.bytes().size(), psize = payload.size(), sum = fnv1a(payload);
    o.write(reinterpret_cast<const char*>(&format), sizeof format);
    o.write(reinterpret_cast<const char*>(&hsize), sizeof hsize);
    o << head.bytes();
    o.write(reinterpret_cast<const char*>(&psize), sizeof psize);
    o.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    o << payload;
  }, true);
}

namespace {
// The checks every checkpoint file passes: header, format, length, checksum, build and deck.
Checkpoint read_checked(const std::string& path, const Deck& dk) {
  Checkpoint c;
  c.path = path;
  std::ifstream in(c.path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (size < 0) refuse(c.path, "cannot read the file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), size)) refuse(c.path, "cannot read the file");
  if (bytes.size() < kMagicSize || bytes.compare(0, kMagicSize, kMagic) != 0)
    refuse(c.path, "not a PeriAdapt checkpoint (no header)");
  try {
    // The header's fields after the magic: format, header, payload size, checksum, payload.
    // (The file's bytes become the payload in place: a restart holds one copy of it.)
    std::string rest = std::move(bytes);
    rest.erase(0, kMagicSize);
    ArchiveReader r(rest, c.path);
    const auto format = r.get<std::uint32_t>();
    if (format != kCheckpointFormat)
      refuse(c.path, fmt::format("checkpoint format {}; this build reads format {}", format,
                                 kCheckpointFormat));
    std::string head;
    r.get(head);
    ArchiveReader h(head, c.path);
    h.get(c.info.build);
    h.get(c.info.deck);
    h.get(c.info.deck_file);
    h.get(c.info.threads);
    h.get(c.info.step);
    h.get(c.info.time);
    const auto sum = [&] {
      std::uint64_t size = 0, s = 0;
      r.get(size);
      r.get(s);
      if (rest.size() - r.position() != size)
        refuse(c.path, fmt::format("the payload holds {} bytes, the header says {} (truncated "
                                   "or corrupt)", rest.size() - r.position(), size));
      return s;
    }();
    rest.erase(0, r.position());
    c.payload = std::move(rest);
    if (fnv1a(c.payload) != sum) refuse(c.path, "checksum mismatch: the file is corrupt");
  } catch (const ArchiveError& e) {
    refuse(c.path, e.what());
  }
  if (c.info.build != build_id())
    refuse(c.path, fmt::format("written by build '{}', this is '{}': a restart continues bit for "
                               "bit only with the program that wrote it",
                               c.info.build, build_id()));
  if (c.info.deck != deck_fingerprint(dk))
    refuse(c.path, fmt::format("written for another deck ({}); only output settings, "
                               "solver.end_time and solver.steps may change on a restart",
                               c.info.deck_file));
  return c;
}
}  // namespace

Checkpoint read_checkpoint(const std::string& path_or_dir, const Deck& dk) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string path =
      fs::is_directory(path_or_dir, ec) ? path_or_dir + "/" + kCheckpointName : path_or_dir;
  if (!fs::is_regular_file(path, ec))
    refuse(path, "no checkpoint here (a run writes checkpoint.bin into its output folder every "
                 "output.checkpoint_every steps and when stopped by SIGINT or SIGTERM)");
  return read_checked(path, dk);
}

std::uint64_t checkpoint_checksum(const std::string& payload) { return fnv1a(payload); }

std::string read_checkpoint_piece(const std::string& path, const Deck& dk, std::uint64_t sum) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    refuse(path, "missing: the checkpoint keeps each rank's bond rows in a piece beside it, and "
                 "a restart reads those with its rows (copy the pieces with checkpoint.bin)");
  Checkpoint c = read_checked(path, dk);
  if (fnv1a(c.payload) != sum)
    refuse(path, "this piece belongs to another checkpoint than the one beside it");
  return std::move(c.payload);
}

}  // namespace periadapt
