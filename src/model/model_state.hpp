#pragma once
// Checkpoint of what a run changes in a model: nodes (refinement adds them), bond families and
// their broken bonds, which nodes the loads and prescribed motions act on, and the per-node
// values the next step's kernels and triggers read. The rest (material, regions, load histories,
// pre-cracks) is rebuilt from the deck. Nodes are stored in global order, independent of
// threads or how a run is split.
#include <functional>
#include <string>
#include <vector>

#include "core/binary_archive.hpp"
#include "model/model.hpp"

namespace periadapt {

// A distributed run whose ranks hold their own bond rows (parallel/held_rows.hpp) checkpoints
// them in pieces, one per rank, beside the checkpoint, which names each piece and its checksum:
// no rank assembles the whole bond arrays, and a restart on any rank count reads the rows it
// holds from whichever pieces have them.
struct BondPieces {
  std::vector<std::string> files;
  std::vector<std::uint64_t> sums;
};
// This rank's own rows of held bond arrays: the payload of its piece, put out in parts.
void write_bond_rows_piece(const Model& m, const ArchiveSink& out);
// Opens a piece by the name and checksum the checkpoint gave and lets `parse` read its payload
// (the reader checks the checksum).
using PieceReader = std::function<void(const std::string& file, std::uint64_t sum,
                                       const std::function<void(ArchiveStream&)>& parse)>;

// With held rows, `pieces` names the pieces the ranks wrote.
void save_model_state(ArchiveWriter& w, const Model& m, const BondPieces* pieces = nullptr);
// Restores into a model built from the same deck; throws ArchiveError when the checkpoint does
// not fit it (dimension, loads, motions). A model whose rows are held (built so for this rank
// count) takes its rows from the checkpoint's arrays or pieces; any other takes the whole arrays,
// assembled from the pieces where the checkpoint has them in pieces.
void restore_model_state(ArchiveReader& r, Model& m, const PieceReader& read_piece = {});

}  // namespace periadapt
