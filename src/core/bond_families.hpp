#pragma once
// Bond families in compressed sparse rows over owner nodes. Each pair is stored by both owners
// (full lists), so the force loop writes only to its own node and needs no atomics; variable and
// dual horizons need the two directions to differ anyway. Row i is [begin(i), end(i)) in the
// bond arrays: rows are contiguous and in node order after a full build; a refinement event
// writes the rows it searches again at the end of the arrays (the old entries become unused
// slack, compacted away when it grows large), so an event does not move the rest.
//
// Per bond: neighbor id (4 B), inverse reference length (8 B), quadrature fraction beta (4 B)
// = 16 B. Two flags ride on signs, so the force loop needs no extra gathers:
//  - a broken bond keeps its entry with beta negated (skipped; damage still knows its weight);
//  - an unbreakable bond (an end in a no-fail region) has its inverse length negated.
#include <cmath>
#include <cstdint>
#include <vector>

namespace periadapt {

struct BondFamilies {
  std::vector<std::uint64_t> offsets{0};  // row begins, size n+1 (offsets[n]: end of the arrays)
  // Row ends, size n, once an event has moved a row; empty while rows are contiguous (row i
  // then ends at offsets[i + 1]), so a run without refinement does not pay 8 B/node for it.
  std::vector<std::uint64_t> ends;
  std::uint64_t live = 0;                 // bonds in rows (the arrays may hold unused slack)
  std::vector<std::uint32_t> neighbor;
  std::vector<double> inv_length;  // 1/|xi|, negative when the bond cannot break
  std::vector<float> beta;

  // History laws only (material/bond_law.hpp): each bond's history value (plastic stretch,
  // largest stretch), copied by compactions; rows searched again get their surviving bonds'
  // values back by pair (adapt/crack_memory.cpp); a new bond starts at 0. Empty, and keeps_state false, for PMB and LPS.
  bool keeps_state = false;
  std::vector<double> state;

  // Dual-horizon form only: for each node, the bonds of other nodes' families that point at it
  // (the transpose): owner node and bond index. Empty otherwise.
  std::vector<std::uint64_t> t_offsets;
  std::vector<std::uint32_t> t_owner;
  std::vector<std::uint64_t> t_bond;
  // Plain LPS pairing on nodes of several horizons: a pair's force is the gradient of both ends'
  // energies, each weighing the pair with its own row's quadrature factor. Per node, where its
  // row's factors for the far ends sit in reverse_beta (kNoReverse: the same as its own, the
  // rows away from level interfaces); there, per bond slot of the row, the factor of the same
  // pair in the far end's row (0 where that row lacks it). Made when rows are built or moved
  // (index_pairs), after any correction of the factors; empty otherwise.
  static constexpr std::uint64_t kNoReverse = ~std::uint64_t{0};
  std::vector<std::uint64_t> reverse_at;
  std::vector<float> reverse_beta;
  // Dual-horizon PMB scratch: each membership's force factor from its owner's pass, gathered by
  // the other end (8 B per bond slot; empty for other forms).
  std::vector<double> dual_force;

  // Gives every bond slot a history value of 0 (with the arrays' spare room).
  void enable_state() {
    keeps_state = true;
    state.reserve(neighbor.capacity());
    state.assign(neighbor.size(), 0.0);
  }
  std::size_t num_nodes() const { return offsets.size() - 1; }
  std::size_t num_bonds() const { return live; }
  std::uint64_t begin(std::size_t i) const { return offsets[i]; }
  std::uint64_t end(std::size_t i) const { return ends.empty() ? offsets[i + 1] : ends[i]; }
  // Row ends for the hot loops, without a branch per row.
  const std::uint64_t* row_ends() const { return ends.empty() ? offsets.data() + 1 : ends.data(); }
  // After filling offsets as a contiguous prefix sum (row i ends where row i+1 begins).
  void close_contiguous() {
    ends.clear();
    live = offsets.back();
  }
  // Bytes of the row index arrays per node (for memory reports).
  std::size_t row_index_bytes_per_node() const { return ends.empty() ? 8 : 16; }
  // Bytes held per bond in the arrays, unused slack included (for memory reports).
  std::size_t bond_array_bytes() const { return neighbor.size() * bytes_per_bond(); }
  // A bond's name in every copy of the families that holds its row (ranks holding other rows,
  // arrays whose rows sit elsewhere): its row and its place in the row.
  std::uint64_t name(std::uint32_t i, std::uint64_t k) const {
    return (std::uint64_t{i} << 32) | (k - begin(i));
  }
  // The bond a name gives here; false when this copy holds no such bond (an empty row).
  bool named(std::uint64_t name, std::uint64_t& k) const {
    const auto i = static_cast<std::size_t>(name >> 32);
    const std::uint64_t at = name & 0xffffffffu;
    if (i >= num_nodes() || at >= end(i) - begin(i)) return false;
    k = begin(i) + at;
    return true;
  }
  static bool intact(float b) { return b > 0.0f; }
  double length(std::size_t k) const { return 1.0 / std::abs(inv_length[k]); }
  bool breakable(std::size_t k) const { return inv_length[k] > 0.0; }
  static constexpr std::size_t bytes_per_bond() { return 4 + 8 + 4; }
};

}  // namespace periadapt
