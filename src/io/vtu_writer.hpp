#pragma once
// ParaView output: one VTU (unstructured grid of vertex cells, appended raw binary, optionally
// zlib-compressed as VTK's vtkZLibDataCompressor reads it) per snapshot
// and a PVD collection that indexes them by time. A distributed run writes one piece per rank
// under a PVTU instead. The PVD is rewritten after every snapshot, so
// a run that stops early still leaves a valid series.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/node_set.hpp"

namespace periadapt {

struct PointField {
  std::string name;
  int components;             // 1, 3 or 9 (a row-major tensor)
  std::vector<double> data;   // n * components
};

class VtuSeries {
 public:
  VtuSeries(std::string directory, std::string basename, bool zlib = false);
  // Writes the active nodes' positions (reference configuration) and fields; returns the path.
  std::string write(double time, const NodeSet& nodes, const std::vector<PointField>& fields);
  // Distributed runs: writes this rank's piece of the next snapshot, the nodes `ids` (fields
  // indexed by node id as in write), and counts the snapshot. The caller makes sure every piece
  // is on disk before one rank calls write_parallel_index for it.
  std::string write_piece(double time, const NodeSet& nodes, const std::vector<std::uint32_t>& ids,
                          const std::vector<PointField>& fields, int rank);
  // The PVTU naming the `pieces` pieces of the snapshot write_piece counted last, and the PVD.
  void write_parallel_index(const std::vector<PointField>& fields, int pieces);
  const std::string& pvd_path() const { return pvd_; }
  // The snapshots written so far (time, file name); a restart continues the series after them.
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  // With `remove_later`, the folder's snapshot files after them go (those of a run that went on
  // past the checkpoint, which the continued series replaces, perhaps with other rank counts).
  void resume(std::vector<std::pair<double, std::string>> entries, bool remove_later);

 private:
  void write_pvd() const;
  void write_vtu(const std::string& path, const NodeSet& ns, const std::vector<std::uint32_t>& ids,
                 const std::vector<PointField>& fields) const;
  std::string snapshot_stem() const;
  std::string dir_, base_, pvd_;
  bool compress_ = false;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace periadapt
