#include "solver/linear_static.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <Eigen/SparseCore>
#include <string>

namespace periadapt {

namespace {

using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

}  // namespace

RowMatrix assemble_bond_stiffness(const NodeSet& ns, const BondFamilies& bf, InfluenceShape shape,
                                  BondPairing pairing, const BlockPairs* pairs) {
  const int D = ns.dim;
  const std::size_t n = ns.size();
  const auto rows = static_cast<Eigen::Index>(static_cast<std::size_t>(D) * n);
  // S: off-diagonal blocks a_ij = c_i g(|xi|/delta_i) beta_ij / |xi| e e^T of the intact bonds of
  // each source node (without the neighbor volume).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(bf.num_bonds() * static_cast<std::size_t>(D * D));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) {
      if (!BondFamilies::intact(bf.beta[k])) continue;
      const std::uint32_t j = bf.neighbor[k];
      const double L = bf.length(k);
      double e[3] = {0, 0, 0};
      for (int d = 0; d < D; ++d) e[d] = (ns.x[d][j] - ns.x[d][i]) / L;
      const double w = elastic_bond_stiffness(ns, bf, shape, pairs, i, k);
      for (int a = 0; a < D; ++a)
        for (int b = 0; b < D; ++b)
          trip.emplace_back(static_cast<Eigen::Index>(D * i + a),
                            static_cast<Eigen::Index>(D * j + b), w * e[a] * e[b]);
    }
  }
  RowMatrix S(rows, rows);
  S.setFromTriplets(trip.begin(), trip.end());
  trip.clear();
  trip.shrink_to_fit();
  RowMatrix M;
  if (pairing == BondPairing::DualHorizon) {
    // Each bond acts on both ends with equal and opposite forces, half from each direction
    // (dual-horizon PD): a bond seen from one side only still has its reaction.
    RowMatrix St = S.transpose();
    M = 0.5 * (S + St);
  } else {
    M = std::move(S);
  }
  // Column scaling by the neighbor volume; the diagonal block is minus the row's block sum.
  Eigen::VectorXd vol(rows);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) vol[static_cast<Eigen::Index>(D * i + d)] = ns.volume[i];
  RowMatrix K = -(M * vol.asDiagonal());
  std::vector<Eigen::Triplet<double>> dg;
  dg.reserve(n * static_cast<std::size_t>(D * D));
  for (std::size_t i = 0; i < n; ++i) {
    double blk[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < D; ++a)
      for (RowMatrix::InnerIterator it(K, static_cast<Eigen::Index>(D * i + a)); it; ++it)
        blk[a][it.col() % D] -= it.value();
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b)
        dg.emplace_back(static_cast<Eigen::Index>(D * i + a), static_cast<Eigen::Index>(D * i + b),
                        blk[a][b]);
  }
  RowMatrix Dg(rows, rows);
  Dg.setFromTriplets(dg.begin(), dg.end());
  K += Dg;
  K.makeCompressed();
  return K;
}

std::vector<DisplacementConstraint> model_constraints(const Model& m) {
  std::vector<DisplacementConstraint> out;
  for (const PrescribedMotion& pm : m.motions) {
    if (pm.kind != PrescribedMotion::Kind::Displacement)
      throw std::invalid_argument("boundary condition '" + pm.name +
                                  "': a static solve takes displacement conditions only, not "
                                  "velocities");
    for (std::uint32_t i : pm.nodes)
      for (int d = 0; d < m.nodes.dim; ++d)
        if (pm.component[static_cast<std::size_t>(d)])
          out.push_back({i, d,
                         (*pm.component[static_cast<std::size_t>(d)])(
                             m.nodes.x[0][i], m.nodes.x[1][i], m.nodes.x[2][i], 0.0)});
  }
  return out;
}

StaticResult solve_linear_static(Model& m, const std::vector<DisplacementConstraint>& cons,
                                 const StaticOptions& opt) {
  using clock = std::chrono::steady_clock;
  NodeSet& ns = m.nodes;
  const int D = ns.dim;
  const std::size_t n = ns.size();
  const std::size_t rows = static_cast<std::size_t>(D) * n;
  StaticResult res;
  res.unknowns = rows;

  // Rigid motions must be fixed: every direction translated, and enough components on
  // distinct nodes for rotations (2D: 3 components on 2 nodes; 3D: 6 on 3 nodes).
  {
    std::set<int> dirs;
    std::set<std::uint32_t> cnodes;
    std::set<std::pair<std::uint32_t, int>> comps;
    for (const auto& c : cons) {
      dirs.insert(c.component);
      cnodes.insert(c.node);
      comps.emplace(c.node, c.component);
    }
    const std::size_t need_comp = D == 1 ? 1 : D == 2 ? 3 : 6;
    const std::size_t need_nodes = D == 1 ? 1 : D == 2 ? 2 : 3;
    if (static_cast<int>(dirs.size()) < D || comps.size() < need_comp || cnodes.size() < need_nodes)
      throw SingularSystem(
          "singular system: the displacement constraints do not prevent rigid-body motion (" +
          std::to_string(comps.size()) + " constrained components on " +
          std::to_string(cnodes.size()) + " nodes; a " + std::to_string(D) +
          "D static problem needs every direction constrained and at least " +
          std::to_string(need_comp) + " components on " + std::to_string(need_nodes) +
          " distinct nodes)");
  }

  const auto t0 = clock::now();
  RowMatrix K = assemble_bond_stiffness(ns, m.bonds, m.material.shape, opt.pairing, &m.block_pairs);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows));
  for (const BodyLoad& l : m.loads) {
    const double amp = l.amplitude(1e300);  // final value of the load history
    for (std::uint32_t i : l.nodes)
      for (int d = 0; d < D; ++d) f[D * i + d] += amp * l.density[static_cast<std::size_t>(d)];
  }
  std::vector<char> fixed(rows, 0);
  Eigen::VectorXd ufix = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows));
  for (const auto& c : cons) {
    fixed[static_cast<std::size_t>(D) * c.node + static_cast<std::size_t>(c.component)] = 1;
    ufix[D * c.node + c.component] = c.value;
  }
  // Deactivated parents (refined grids) are not part of the model: identity rows, u = 0.
  for (std::size_t i = 0; i < n; ++i)
    if (!(ns.flags[i] & kActive))
      for (int d = 0; d < D; ++d) fixed[static_cast<std::size_t>(D) * i + d] = 1;
  // Move known displacements to the right-hand side; constrained rows become identity rows.
  for (Eigen::Index r = 0; r < K.outerSize(); ++r) {
    const bool row_fixed = fixed[static_cast<std::size_t>(r)];
    bool has_diag = false;
    for (RowMatrix::InnerIterator it(K, r); it; ++it) {
      if (row_fixed) {
        it.valueRef() = it.col() == r ? 1.0 : 0.0;
      } else if (fixed[static_cast<std::size_t>(it.col())]) {
        f[r] -= it.value() * ufix[it.col()];
        it.valueRef() = 0.0;
      } else if (it.col() == r && it.value() != 0.0) {
        has_diag = true;
      }
    }
    if (row_fixed) {
      f[r] = ufix[r];
    } else if (!has_diag) {
      throw SingularSystem("singular system: node " + std::to_string(r / D) +
                           " has no intact bonds and no constraint (isolated node)");
    }
  }
  K.prune(0.0);
  // Rows in force (density x volume): the operator is then symmetric for dual-horizon pairing
  // and for uniform grids, and a sparse Cholesky (LDL^T) replaces the general LU.
  for (Eigen::Index r = 0; r < K.outerSize(); ++r) {
    if (fixed[static_cast<std::size_t>(r)]) continue;
    const double v = ns.volume[static_cast<std::size_t>(r / D)];
    for (RowMatrix::InnerIterator it(K, r); it; ++it) it.valueRef() *= v;
    f[r] *= v;
  }
  res.nonzeros = static_cast<std::size_t>(K.nonZeros());
  res.assemble_seconds = std::chrono::duration<double>(clock::now() - t0).count();

  const auto t1 = clock::now();
  Eigen::VectorXd u;
  bool solved = false;
  const RowMatrix Kt = K.transpose();
  const double asym = (K - Kt).norm();
  res.symmetric = asym <= 1e-12 * K.norm();
  if (res.symmetric && rows > opt.cholesky_limit) {
    // Large symmetric systems: Jacobi-preconditioned conjugate gradients (measured faster here
    // than incomplete Cholesky, and far faster than the simplicial factorization).
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                             Eigen::DiagonalPreconditioner<double>>
        cg;
    Eigen::SparseMatrix<double> Kc = K;
    cg.setTolerance(opt.iterative_tolerance);
    cg.setMaxIterations(static_cast<Eigen::Index>(std::max<std::size_t>(1000, 10 * rows)));
    cg.compute(Kc);
    if (cg.info() == Eigen::Success) {
      u = cg.solve(f);
      res.iterative = true;
      res.iterations = static_cast<int>(cg.iterations());
      solved = cg.info() == Eigen::Success && u.allFinite();
    }
  }
  if (!solved && rows <= opt.direct_limit && res.symmetric) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
    Eigen::SparseMatrix<double> Kc = K;
    ldlt.compute(Kc);
    if (ldlt.info() == Eigen::Success) {
      u = ldlt.solve(f);
      solved = u.allFinite();
    }
    if (!solved)
      throw SingularSystem("singular system: the sparse Cholesky factorization failed; check that "
                           "constraints prevent rigid-body motion and that no part of the body "
                           "is disconnected");
  }
  if (!solved && !res.symmetric && rows > opt.lu_limit) {
    // Large general systems: Jacobi-preconditioned BiCGSTAB (cheaper here than ILUT).
    Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::DiagonalPreconditioner<double>> it;
    Eigen::SparseMatrix<double> Kc = K;


    it.setTolerance(opt.iterative_tolerance);
    // Jacobi-BiCGSTAB needs a few thousand iterations on the grids here; a run that has not
    // converged by 5,000 will not, and the direct solver below gets the system instead.
    it.setMaxIterations(5000);
    it.compute(Kc);
    if (it.info() == Eigen::Success) {
      u = it.solve(f);
      res.iterative = true;
      res.iterations = static_cast<int>(it.iterations());
      solved = it.info() == Eigen::Success && u.allFinite();
    }
  }
  if (!solved && rows <= opt.direct_limit) {
    Eigen::SparseMatrix<double> Kc = K;
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
    lu.analyzePattern(Kc);
    lu.factorize(Kc);
    if (lu.info() == Eigen::Success) {
      u = lu.solve(f);
      solved = true;
    } else if (lu.info() == Eigen::NumericalIssue) {
      throw SingularSystem("singular system: the sparse LU factorization met a zero pivot (" +
                           lu.lastErrorMessage() +
                           "); check that constraints prevent rigid-body motion and that no "
                           "part of the body is disconnected");
    }
  }
  if (!solved) {
    Eigen::BiCGSTAB<RowMatrix, Eigen::DiagonalPreconditioner<double>> it;
    it.setTolerance(opt.iterative_tolerance);
    it.setMaxIterations(static_cast<Eigen::Index>(std::max<std::size_t>(1000, 20 * rows)));
    it.compute(K);
    u = it.solve(f);
    res.iterative = true;
    res.iterations = static_cast<int>(it.iterations());
    if (it.info() != Eigen::Success)
      throw SingularSystem("the iterative solver did not converge (relative residual " +
                           std::to_string(it.error()) + " after " +
                           std::to_string(it.iterations()) + " iterations)");
  }
  res.solve_seconds = std::chrono::duration<double>(clock::now() - t1).count();

  Eigen::VectorXd r = K * u - f;
  for (std::size_t q = 0; q < rows; ++q)
    if (fixed[q]) r[static_cast<Eigen::Index>(q)] = 0, f[static_cast<Eigen::Index>(q)] = 0;
  res.residual_norm = r.norm();
  res.load_norm = f.norm();
  if (!u.allFinite() || (res.load_norm > 0 && res.residual_norm > 1e-6 * res.load_norm))
    throw SingularSystem("singular or ill-conditioned system: relative residual " +
                         std::to_string(res.load_norm > 0 ? res.residual_norm / res.load_norm
                                                          : res.residual_norm));
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) ns.u[static_cast<std::size_t>(d)][i] = u[D * static_cast<Eigen::Index>(i) + d];
  ns.sync_all_current();
  return res;
}

}  // namespace periadapt
