#pragma once
// Stewart & Jeon 2019, section 3.3 (Figs. 9-10): crack bifurcation in the cooled clamped disk of
// examples/pdro_disk_2d.yaml. Runs a native reference on the grid dx / 2 (no overlay), the deck's
// own grid without overlay, and the deck's grid with the overlay at n = 2, 2.5, 3, all to the
// paper's snapshot time, and compares with the reference: total damage (sum of node damage, Fig.
// 9a; for a fixed m a crack of length l damages about l m / dx worth of nodes, so sum(phi) dx is
// what compares across grids) and the crack pattern (cells dx wide holding a node with damage
// > 0.35; mismatch = the fraction of cracked cells, both runs counted, with no cracked cell of the
// other run within one horizon).
// Also the overlay's cost: wall time against the plain run on the same grid, and the fraction of
// bond evaluations it re-checked.
#include <string>
#include <vector>

namespace periadapt {

struct PdroDiskOptions {
  std::string deck = "examples/pdro_disk_2d.yaml";
  std::vector<double> overlay_n{2.0, 2.5, 3.0};
  double snapshot_time = 24e-6;
  bool pim = false;
  bool gaussian = false;  // PDDO weight: Gaussian instead of uniform
  bool whole_bond = false;  // overlay sub-pairs over the whole bond instead of the paper's three
};

int run_pdro_disk_study(const std::string& out_dir, const PdroDiskOptions& opt);

}  // namespace periadapt
