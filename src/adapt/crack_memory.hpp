#pragma once
// What a change of the node set (refinement, coarsening) must carry over to the new bond
// families: short crack facets (2D segments, 3D squares) standing for the broken bonds of the
// nodes that vanish, so that new bonds crossing them start broken. (Broken bonds between
// surviving nodes are read from the old families by rebuild_families itself.)
#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "model/model.hpp"

namespace periadapt {

// A short piece of crack standing for one broken bond: a segment across it in the xy-plane (2D)
// or a small square across it (3D), centred on the bond's midpoint.
struct Facet {
  Vec3 a, b;                   // 2D segment
  std::array<Vec3, 4> quad{};  // 3D square
  bool in3d = false;
  Vec3 centre() const {
    return in3d ? scale(add(quad[0], quad[2]), 0.5) : scale(add(a, b), 0.5);
  }
  double reach() const {  // farthest point from the centre
    return in3d ? norm(sub(quad[0], centre())) : 0.5 * norm(sub(b, a));
  }
  bool crossed_by(const Vec3& p, const Vec3& q) const {
    return in3d ? bond_crosses_quad<true>(p, q, quad) : bond_crosses_segment<true>(p, q, a, b);
  }
};

struct CrackMemory {
  std::vector<Facet> facets;
};

// `vanishing[i]`: node i is deactivated by the change (ids of the current node set); its broken
// bonds become facets. `refined` (optional): nodes that stay but get new nodes around them
// (method A); their broken bonds also become facets for the new nodes' bonds. Cost: the rows of
// those nodes only.
CrackMemory remember_cracks(const Model& m, const std::vector<char>& vanishing,
                            const std::vector<char>* refined = nullptr);

// New families for the changed node set (surface correction and pre-cracks reapplied); bonds
// between nodes that existed before (id < n_before) keep their broken state, new bonds crossing a
// facet start broken; unbreakable flags and damage weights are refreshed. `changed` flags the
// nodes that appeared, vanished or changed horizon: only the families within reach of them are
// searched again (a local window), the others are copied (not with surface correction, whose
// factors are not local: then everything is rebuilt).
// `appended_only`: the event only switched nodes off and appended new ones (method B), so the
// rows of unchanged nodes in the window are patched rather than searched (same rows).
// Returns the nodes whose rows were searched again.
std::vector<std::uint32_t> rebuild_families(Model& m, const CrackMemory& memory,
                                            std::size_t n_before, const std::vector<char>& changed,
                                            bool appended_only = false);

}  // namespace periadapt
