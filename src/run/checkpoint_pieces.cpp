#include "run/checkpoint_pieces.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>

#include "input/deck_error.hpp"
#include "io/atomic_output.hpp"
#include "parallel/mpi_env.hpp"

namespace periadapt {

namespace {
constexpr char kPiecePrefix[] = "checkpoint.rows.";
constexpr char kPieceSuffix[] = ".bin";

std::string piece_name(long step, int rank, int ranks) {
  return fmt::format("{}{}.{}-of-{}{}", kPiecePrefix, step, rank, ranks, kPieceSuffix);
}
}  // namespace

bool is_checkpoint_piece(const std::string& f) {
  const std::size_t p = sizeof(kPiecePrefix) - 1, s = sizeof(kPieceSuffix) - 1;
  return f.size() > p + s && f.compare(0, p, kPiecePrefix) == 0 &&
         f.compare(f.size() - s, s, kPieceSuffix) == 0;
}

BondPieces write_bond_pieces(const std::string& dir, const CheckpointInfo& info, const Model& m) {
  const std::string path = dir + "/" + piece_name(info.step, mpi::rank(), mpi::size());
  std::string error;
  std::uint64_t sum = 0;
  try {
    sum = write_checkpoint_parts(path, info,
                                 [&](const ArchiveSink& out) { write_bond_rows_piece(m, out); });
  } catch (const OutputError& e) {
    error = e.what();
  }
  // Every rank stops when one could not write, with its error (rank 0 records it in the
  // summary); the pieces written belong to no checkpoint and go.
  error = mpi::first_text(error);
  if (!error.empty()) {
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw OutputError(error);
  }
  BondPieces b;
  b.sums = mpi::gather_to_root(std::vector<std::uint64_t>{sum});
  if (mpi::rank() == 0)
    for (int r = 0; r < mpi::size(); ++r) b.files.push_back(piece_name(info.step, r, mpi::size()));
  return b;
}

void remove_stale_pieces(const std::string& dir, const BondPieces& named) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    if (is_checkpoint_piece(f) &&
        std::find(named.files.begin(), named.files.end(), f) == named.files.end())
      fs::remove(e.path(), ec);
  }
}

PieceReader piece_reader(const std::string& checkpoint_path, const Deck& dk) {
  const std::string dir = std::filesystem::path(checkpoint_path).parent_path().string();
  return [dir, &dk, checkpoint_path](const std::string& file, std::uint64_t sum,
                                     const std::function<void(ArchiveStream&)>& parse) {
    // Names from the checkpoint: plain piece names in its folder, nothing else.
    if (!is_checkpoint_piece(file) || file.find('/') != std::string::npos)
      throw DeckError(checkpoint_path, 0, 0, "--restart",
                      "names a bond piece '" + file + "' that is no piece's name (corrupt)");
    read_checkpoint_piece((dir.empty() ? std::string(".") : dir) + "/" + file, dk, sum, parse);
  };
}

}  // namespace periadapt
