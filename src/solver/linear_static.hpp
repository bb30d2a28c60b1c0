#pragma once
// Linearized bond-based equilibrium (thesis Eqs. 2.19-2.20; Bobaru et al. 2009 Eqs. 25-26):
//   sum_j C_ij (u_j - u_i) + b_i = 0,   C_ij = c_i g(|xi|/delta_i) beta_ij V_j / |xi| (e (x) e),
// with e the unit reference bond direction and c_i the micromodulus of the source node i (bonds
// take the micromodulus of their source node on scaled grids). Prescribed displacement components
// replace their rows. Solved with a sparse direct LU, or BiCGSTAB (diagonal preconditioner) for
// systems beyond `direct_limit` unknowns or when the factorization fails for lack of memory.
#include <Eigen/SparseCore>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/model.hpp"

namespace periadapt {

struct DisplacementConstraint {
  std::uint32_t node;
  int component;
  double value;
};

// How a bond between nodes with different horizons acts: only on its source node with the
// source's micromodulus (thesis Eq. 3.1b; ghost forces at interfaces), or on both ends, half from
// each direction (dual-horizon PD, thesis Eq. 3.1c; Bobaru et al. 2009 Eq. 41).
enum class BondPairing { SourceHorizon, DualHorizon };

struct StaticOptions {
  BondPairing pairing = BondPairing::SourceHorizon;
  std::size_t direct_limit = 2'000'000;  // unknowns up to which the sparse LU is used
  std::size_t cholesky_limit = 40'000;   // symmetric systems above this use preconditioned CG
  std::size_t lu_limit = 40'000;         // general systems above this use BiCGSTAB (Jacobi)
  double iterative_tolerance = 1e-12;    // relative residual of the iterative solvers
};

struct StaticResult {
  std::size_t unknowns = 0;
  std::size_t nonzeros = 0;
  bool iterative = false;
  bool symmetric = false;    // solved by sparse LDL^T (else LU or BiCGSTAB)
  int iterations = 0;
  double residual_norm = 0;  // ||K u - f||_2 over the free rows, in nodal forces (N)
  double load_norm = 0;      // ||f||_2 over the free rows
  double assemble_seconds = 0;
  double solve_seconds = 0;
};

// Raised for systems that cannot have a unique solution (rigid motion not prevented).
class SingularSystem : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Stiffness of the linearized bond-based model: rows/columns dim*i + d; the unconstrained
// operator (row sums vanish: rigid translations are in its null space).
Eigen::SparseMatrix<double, Eigen::RowMajor> assemble_bond_stiffness(const NodeSet& nodes,
                                                                     const BondFamilies& bonds,
                                                                     InfluenceShape shape,
                                                                     BondPairing pairing,
                                                                     const BlockPairs* pairs = nullptr);

// Displacement constraints of the model's prescribed-displacement regions (expressions at t = 0).
std::vector<DisplacementConstraint> model_constraints(const Model& m);

// Solves K u = b with the model's loads at full amplitude; writes nodes.u (and the packed current
// positions). Throws SingularSystem when the constraints leave rigid motion free.
StaticResult solve_linear_static(Model& m, const std::vector<DisplacementConstraint>& constraints,
                                 const StaticOptions& opt = {});

}  // namespace periadapt
