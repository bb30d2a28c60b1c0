#pragma once
// Checkpoint of what a run changes in a model: nodes (refinement adds them), bond families and
// their broken bonds, which nodes the loads and prescribed motions act on, and the per-node
// values the next step's kernels and triggers read. The rest (material, regions, load histories,
// pre-cracks) is rebuilt from the deck. Nodes are stored in global order, independent of
// threads or how a run is split.
#include "core/binary_archive.hpp"
#include "model/model.hpp"

namespace periadapt {

void save_model_state(ArchiveWriter& w, const Model& m);
// Restores into a model built from the same deck; throws ArchiveError when the checkpoint does
// not fit it (dimension, loads, motions).
void restore_model_state(ArchiveReader& r, Model& m);

}  // namespace periadapt
