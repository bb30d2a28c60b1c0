#pragma once
// The bond pieces of a distributed checkpoint (model/model_state.hpp: BondPieces), as files beside
// checkpoint.bin: each rank writes its own rows under a name that carries the step and the rank
// count, so the pieces of the checkpoint in place stay untouched until the new checkpoint.bin
// has replaced it; then the pieces it does not name are removed.
#include <string>

#include "input/deck.hpp"
#include "model/model_state.hpp"
#include "run/checkpoint_file.hpp"

namespace periadapt {

// Whether a file name is a checkpoint piece's (a fresh run clears them with the old outputs).
bool is_checkpoint_piece(const std::string& file_name);

// Every rank writes its piece into `dir` (collective); rank 0 gets the pieces' names and
// checksums, the other ranks an empty list. A piece that cannot be written stops every rank with
// OutputError.
BondPieces write_bond_pieces(const std::string& dir, const CheckpointInfo& info, const Model& m);

// After checkpoint.bin is in place: removes the pieces in `dir` it does not name.
void remove_stale_pieces(const std::string& dir, const BondPieces& named);

// Reads the pieces a checkpoint at `checkpoint_path` names, from its folder.
PieceReader piece_reader(const std::string& checkpoint_path, const Deck& dk);

}  // namespace periadapt
