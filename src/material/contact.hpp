#pragma once
// Short-range contact forces (the LAMMPS PERI package's form, Parks et al. 2008): any two active
// nodes i, j, bonded or not, closer than d_ij = min(distance_factor |X_j - X_i|,
// spacing_factor (h_i + h_j) / 2) in the current configuration repel each other with
//   F_ij = stiffness_factor (c_i / delta_i + c_j / delta_j) / 2 V_i V_j (d_ij - r),
// along the line between them: crack faces that close, and bodies that meet, do not pass through
// each other. The pair force is the same at both ends, so momentum is conserved to round-off; it
// derives from the pair energy stiffness_factor (c/delta)_ij V_i V_j (d_ij - r)^2 / 4 per node.
#include <cstdint>
#include <vector>

namespace periadapt {

struct NodeSet;

struct ContactSpec {
  bool enabled = false;
  double stiffness_factor = 15.0;  // LAMMPS peri: 15 c
  double distance_factor = 0.9;    // of the reference distance
  double spacing_factor = 1.35;    // of the grid spacing
};

// Adds each node's contact force density to nodes.f (for `rows` only when given), and, with W,
// its share of the pair energies to W (the same rows).
void add_contact_forces(const ContactSpec& spec, NodeSet& nodes,
                        const std::vector<std::uint32_t>* rows = nullptr,
                        std::vector<double>* W = nullptr);

// Adds each node's share of the contact energies to W (every active node).
void add_contact_energy(const ContactSpec& spec, const NodeSet& nodes, std::vector<double>& W);

// An upper bound of node i's contact stiffness sum (the Silling-Askari sum's contact part):
// stiffness_factor c_i / delta_i times the volume that fits in its contact ball.
double contact_stiffness_bound(const ContactSpec& spec, const NodeSet& nodes, std::size_t i);

}  // namespace periadapt
