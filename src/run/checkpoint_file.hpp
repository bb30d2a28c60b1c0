#pragma once
// The checkpoint file: a versioned header (magic, format, build, deck fingerprint, step) and a
// payload checked by length and checksum. Written through a temporary name, so the previous
// checkpoint stays intact until the new one is complete (a killed run restarts from it).
#include <cstdint>
#include <functional>
#include <string>

#include "core/binary_archive.hpp"

#include "input/deck.hpp"

namespace periadapt {

inline constexpr std::uint32_t kCheckpointFormat = 5;
inline constexpr const char* kCheckpointName = "checkpoint.bin";

struct CheckpointInfo {
  std::string build;  // the program that wrote it
  std::string deck;   // fingerprint of the deck's physics (Deck::physics_text)
  std::string deck_file;
  int threads = 0;
  long step = 0;
  double time = 0;
};

// This program's identity: version, commit and compiler (a different build may round
// differently, so a restart would not continue bit for bit).
std::string build_id();
std::string deck_fingerprint(const Deck& dk);

void write_checkpoint(const std::string& path, const CheckpointInfo& info, const std::string& payload);

// Reads and checks a checkpoint (a file, or a folder holding checkpoint.bin) against this build
// and deck; throws DeckError (key --restart) saying what does not match.
struct Checkpoint {
  std::string path;
  CheckpointInfo info;
  std::string payload;
};
Checkpoint read_checkpoint(const std::string& path_or_dir, const Deck& dk);

// A payload written in parts (a rank's bond rows, without a copy of them in memory): the producer
// puts the payload through the sink, and runs twice (size and checksum, then the file). Returns
// the checksum (a checkpoint records its pieces').
using PayloadProducer = std::function<void(const ArchiveSink&)>;
std::uint64_t write_checkpoint_parts(const std::string& path, const CheckpointInfo& info,
                                     const PayloadProducer& produce);

// A piece written beside a checkpoint (one rank's bond rows): checked as a checkpoint is, and
// against the checksum the checkpoint recorded for it (a piece of another checkpoint is refused
// before `parse` reads it); `parse` reads its payload in order, and the checksum of what it read
// is checked after. Throws DeckError (key --restart), or ArchiveError from `parse`.
void read_checkpoint_piece(const std::string& path, const Deck& dk, std::uint64_t sum,
                           const std::function<void(ArchiveStream&)>& parse);

}  // namespace periadapt
