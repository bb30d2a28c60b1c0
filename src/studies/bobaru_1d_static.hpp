#pragma once
// The static 1D bar of Bobaru, Yang, Alves, Silling, Askari, Xu (2009), sections 2-5: E = A = 1,
// two self-equilibrated unit point loads at x = +-a, linear bond-based peridynamics solved with the
// sparse static solver, composite midpoint quadrature with each node's cell (Voronoi, clipped to
// the bar) intersected with the source horizon. Refined zones scale the horizon with the spacing
// (m fixed) and bonds take the micromodulus of their source node (Eq. 36), sudden transition.
#include <string>
#include <vector>

#include "material/micromodulus.hpp"
#include "solver/linear_static.hpp"

namespace periadapt {

struct BarZone {
  double lo, hi;  // refined interval; its nodes have spacing dx / factor
};

struct BarSpec {
  double length = 4.0;        // bar from -length/2 to length/2
  double a = 1.0;             // load points at +-a
  double dx = 0.02;           // coarse spacing
  double m = 10.0;            // horizon / spacing, the same on every level
  int factor = 1;             // refinement factor inside the zones
  std::vector<BarZone> zones; // refined zones (empty: uniform)
  InfluenceShape shape = InfluenceShape::Constant;
  double probe = 0.5;         // where the displacement error is measured
  BondPairing pairing = BondPairing::DualHorizon;  // Bobaru Eq. 41: equal and opposite bond forces
};

struct BarSolution {
  std::vector<double> x, u, horizon, cell;  // per node, sorted by x
  double u_probe = 0;          // numerical u at the probe (linear interpolation)
  double relative_error = 0;   // |u - x/E| / |x/E| at the probe
  double nodes_in_horizon_coarse = 0, nodes_in_horizon_fine = 0;
};

BarSolution solve_bobaru_bar(const BarSpec& spec);

// Bobaru 2.3: 7 nodes, dx = 1, delta = 2, constant micromodulus, loads -1 at node 3 and +1 at
// node 5. Returns the printed system's form: -2 K (row-major 7x7) and -2 b.
void bobaru_seven_node_system(std::vector<double>& matrix, std::vector<double>& rhs);

// Prints Tables I and II beside the published values and fitted rates; writes CSVs to `out_dir`
// when not empty. Returns 0.
int run_bobaru_1d_study(const std::string& out_dir);

}  // namespace periadapt
