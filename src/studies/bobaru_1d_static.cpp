#include "studies/bobaru_1d_static.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "model/model.hpp"
#include "solver/linear_static.hpp"
#include "studies/convergence_rate.hpp"
#include "studies/study_csv.hpp"

namespace periadapt {

namespace {

bool in_zone(const BarSpec& s, double x, double tol) {
  for (const BarZone& z : s.zones)
    if (x >= z.lo - tol && x <= z.hi + tol) return true;
  return false;
}

Model bar_model(const BarSpec& s, std::vector<double>& xs, std::vector<double>& cells) {
  const double tol = 1e-9 * s.dx;
  const double half = 0.5 * s.length;
  const double fine = s.dx / s.factor;
  // Coarse nodes on multiples of dx outside the zones, fine nodes on multiples of dx/factor
  // inside them (zone ends are snapped to the coarse lattice).
  xs.clear();
  const long nc = std::lround(half / s.dx);
  for (long k = -nc; k <= nc; ++k) {
    const double x = k * s.dx;
    if (!in_zone(s, x, tol)) xs.push_back(x);
  }
  for (const BarZone& z : s.zones) {
    const long lo = std::lround(z.lo / fine), hi = std::lround(z.hi / fine);
    for (long k = lo; k <= hi; ++k) xs.push_back(k * fine);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [&](double p, double q) { return q - p < tol; }),
           xs.end());
  const std::size_t n = xs.size();
  cells.assign(n, 0.0);
  std::vector<double> cl(n), cr(n);
  for (std::size_t i = 0; i < n; ++i) {
    cl[i] = i == 0 ? xs[0] : 0.5 * (xs[i - 1] + xs[i]);
    cr[i] = i + 1 == n ? xs[n - 1] : 0.5 * (xs[i] + xs[i + 1]);
    cells[i] = cr[i] - cl[i];
  }
  Model m;
  NodeSet& ns = m.nodes;
  ns.dim = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const bool f = in_zone(s, xs[i], tol);
    const std::size_t id = ns.append({xs[i], 0, 0}, cells[i], f ? fine : s.dx);
    ns.horizon[id] = s.m * ns.spacing[id];
    ns.micromodulus[id] = micromodulus_c0(1, PlaneCondition::None, s.shape, 1.0, ns.horizon[id], 1.0);
    ns.density[id] = 1.0;
  }
  // Families: nodes within the source horizon, weighted by the part of their cell inside it.
  BondFamilies& bf = m.bonds;
  bf.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = ns.horizon[i], lo = xs[i] - d, hi = xs[i] + d;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || std::abs(xs[j] - xs[i]) > d * (1 + 1e-12)) continue;
      const double overlap = std::min(cr[j], hi) - std::max(cl[j], lo);
      if (overlap <= 0) continue;
      bf.neighbor.push_back(static_cast<std::uint32_t>(j));
      bf.inv_length.push_back(1.0 / std::abs(xs[j] - xs[i]));
      bf.beta.push_back(static_cast<float>(overlap / cells[j]));
    }
    bf.offsets[i + 1] = bf.neighbor.size();
  }
  bf.close_contiguous();
  m.material.shape = s.shape;
  m.material.E = 1.0;
  m.damage_enabled = false;
  auto node_at = [&](double x) -> std::uint32_t {
    auto it = std::min_element(xs.begin(), xs.end(),
                               [&](double p, double q) { return std::abs(p - x) < std::abs(q - x); });
    if (std::abs(*it - x) > tol)
      throw std::invalid_argument(fmt::format("bar grid has no node at x = {}", x));
    return static_cast<std::uint32_t>(it - xs.begin());
  };
  for (int sign : {+1, -1}) {
    BodyLoad l;
    l.name.append(sign > 0 ? "+a" : "-a");  // (append: GCC 12 warns falsely on assignment)
    const std::uint32_t i = node_at(sign * s.a);
    l.nodes = {i};
    l.density = {sign / cells[i], 0, 0};  // unit point load over the node's length (A = 1)
    m.loads.push_back(l);
  }
  return m;
}

}  // namespace

BarSolution solve_bobaru_bar(const BarSpec& s) {
  std::vector<double> xs, cells;
  Model m = bar_model(s, xs, cells);
  // Antisymmetric loads: u(0) = 0 removes the rigid translation without changing the solution.
  std::uint32_t mid = 0;
  for (std::size_t i = 0; i < xs.size(); ++i)
    if (std::abs(xs[i]) < std::abs(xs[mid])) mid = static_cast<std::uint32_t>(i);
  StaticOptions opt;
  opt.pairing = s.pairing;
  solve_linear_static(m, {{mid, 0, 0.0}}, opt);
  BarSolution out;
  out.x = xs;
  out.cell = cells;
  out.horizon = m.nodes.horizon;
  out.u = m.nodes.u[0];
  auto it = std::lower_bound(xs.begin(), xs.end(), s.probe - 1e-12);
  const std::size_t k = static_cast<std::size_t>(it - xs.begin());
  if (std::abs(xs[k] - s.probe) < 1e-9 * s.dx) {
    out.u_probe = out.u[k];
  } else {
    const double w = (s.probe - xs[k - 1]) / (xs[k] - xs[k - 1]);
    out.u_probe = (1 - w) * out.u[k - 1] + w * out.u[k];
  }
  out.relative_error = std::abs(out.u_probe - s.probe) / std::abs(s.probe);
  double fc = 0, nf = 0, cc = 0, nc = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    const double cnt = static_cast<double>(m.bonds.end(i) - m.bonds.begin(i) + 1);
    if (m.nodes.spacing[i] < s.dx * (1 - 1e-9)) fc += cnt, ++nf;
    else cc += cnt, ++nc;
  }
  out.nodes_in_horizon_coarse = nc > 0 ? cc / nc : 0;
  out.nodes_in_horizon_fine = nf > 0 ? fc / nf : 0;
  return out;
}

void bobaru_seven_node_system(std::vector<double>& A, std::vector<double>& rhs) {
  BarSpec s;
  s.length = 6.0;
  s.dx = 1.0;
  s.m = 2.0;
  s.pairing = BondPairing::SourceHorizon;  // the printed system: V_ip of the source's horizon
  std::vector<double> xs, cells;
  // Shift so that nodes sit at 0..6 with loads on nodes 3 and 5 (x = 2 and x = 4): same bar
  // centred, loads at +-1 around the middle node.
  s.a = 1.0;
  Model m = bar_model(s, xs, cells);
  const auto K = assemble_bond_stiffness(m.nodes, m.bonds, s.shape, s.pairing);
  const int n = static_cast<int>(xs.size());
  A.assign(static_cast<std::size_t>(n * n), 0.0);
  rhs.assign(static_cast<std::size_t>(n), 0.0);
  for (int r = 0; r < n; ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(K, r); it; ++it)
      A[static_cast<std::size_t>(r * n + it.col())] = -2.0 * it.value();
  for (const BodyLoad& l : m.loads)
    for (std::uint32_t i : l.nodes) rhs[i] = -2.0 * l.density[0] * cells[i];
}

int run_bobaru_1d_study(const std::string& out_dir) {
  std::ofstream csv = open_study_csv(out_dir, "bobaru_1d_static.csv",
                                     "table,case,shape,nodes,coarse_horizon,fine_horizon,relative_error_pct,published_pct");
  const InfluenceShape shapes[2] = {InfluenceShape::Constant, InfluenceShape::Triangular};
  const char* shape_name[2] = {"constant", "triangular"};

  // Table II, uniform refinement: bar length 20, 201..801 nodes, 21..51 nodes in the horizon,
  // i.e. m = 10..25 and delta = 1, 0.75, 2/3, 0.625. Beside each error: the same horizon with 8x
  // the nodes (m-convergence, the continuum peridynamic value; scripts/bobaru_bar_fourier.py
  // computes it independently by Fourier transform) and the published value. Errors are signed
  // here (the paper prints magnitudes).
  fmt::print("Bobaru et al. 2009, Table II (uniform grids, bar length 20, relative error of u at "
             "x = 0.5, %, signed)\n");
  fmt::print("{:>6} {:>4} {:>7} | {:>8} {:>8} {:>6} | {:>8} {:>8} {:>6}\n", "nodes", "m", "delta",
             "const", "8m", "pub.", "tri", "8m", "pub.");
  const int nodes2[4] = {201, 401, 601, 801};
  const double m2[4] = {10, 15, 20, 25};
  const double pub2[2][4] = {{3.375, 1.025, 0.516, 0.259}, {3.745, 1.259, 0.562, 0.288}};
  std::vector<double> nn, e2[2];
  int within = 0;
  for (int r = 0; r < 4; ++r) {
    double err[2], conv[2];
    BarSpec s;
    s.length = 20.0;
    s.dx = 20.0 / (nodes2[r] - 1);
    s.m = m2[r];
    for (int k = 0; k < 2; ++k) {
      s.shape = shapes[k];
      const BarSolution sol = solve_bobaru_bar(s);
      err[k] = 100 * (sol.u_probe - s.probe) / s.probe;
      BarSpec fine = s;
      fine.dx = s.dx / 8;
      fine.m = 8 * s.m;
      const BarSolution cs = solve_bobaru_bar(fine);
      conv[k] = 100 * (cs.u_probe - s.probe) / s.probe;
      e2[k].push_back(std::abs(err[k]));
      const double ratio = std::abs(err[k]) / pub2[k][r];
      within += ratio <= 1.5 && ratio >= 1 / 1.5;
      if (csv) csv << fmt::format("II,uniform,{},{},{},{},{:.6g},{}\n", shape_name[k], nodes2[r],
                                  s.m * s.dx, s.m * s.dx, err[k], pub2[k][r]);
    }
    nn.push_back(nodes2[r]);
    fmt::print("{:>6} {:>4.0f} {:>7.4f} | {:>+8.3f} {:>+8.3f} {:>6.3f} | {:>+8.3f} {:>+8.3f} {:>6.3f}\n",
               nodes2[r], s.m, s.m * s.dx, err[0], conv[0], pub2[0][r], err[1], conv[1],
               pub2[1][r]);
  }
  fmt::print("rates of |error|: constant {:.3f} (published 1.822), triangular {:.3f} (published "
             "1.834); {} of 8 errors within a factor 1.5 of the published ones\n",
             fitted_rate(nn, e2[0]), fitted_rate(nn, e2[1]), within);
  fmt::print("The continuum peridynamic error at x = 0.5 changes sign near delta = 0.725 (constant) "
             "and 0.80 (triangular): no discretization converging to it can decrease monotonically "
             "over delta = 1 ... 0.625 as the published column does.\n\n");

  // Table II, non-uniform columns: the same coarse grids with a zone refined 2x or 4x (horizon /2,
  // /4, m kept) around the loads, placed as case (b) below: [-(a + 3 delta_c/2), a + 3 delta_c/2],
  // so that only refined nodes see the loads (the paper gives no bounds, only "< 15% of the
  // length", which no zone that hides the loads from the coarse horizons of 1 ... 0.625 meets:
  // ours spans 25-19%). Signed errors at x = 0.5, as above; rates against our total nodes.
  fmt::print("Bobaru et al. 2009, Table II (non-uniform: zone x2 / x4 around the loads, case (b) "
             "placement; relative error of u at x = 0.5, %, signed)\n");
  fmt::print("{:>6} | {:>6} {:>8} {:>6} {:>8} {:>6} | {:>6} {:>8} {:>6} {:>8} {:>6}\n", "coarse",
             "nodes", "2x const", "pub.", "2x tri", "pub.", "nodes", "4x const", "pub.", "4x tri",
             "pub.");
  const double pub_nu[2][2][4] = {{{1.172, 0.625, 0.454, 0.314}, {1.047, 0.331, 0.170, 0.109}},
                                  {{0.627, 0.285, 0.200, 0.139}, {0.562, 0.178, 0.101, 0.055}}};
  std::vector<double> nu_nodes[2], nu_err[2][2];
  for (int r = 0; r < 4; ++r) {
    std::string line;
    for (int f = 0; f < 2; ++f) {
      BarSpec s;
      s.length = 20.0;
      s.dx = 20.0 / (nodes2[r] - 1);
      s.m = m2[r];
      s.factor = f == 0 ? 2 : 4;
      const double dc = s.m * s.dx, reach = std::round((s.a + 1.5 * dc) / s.dx) * s.dx;
      s.zones = {{-reach, reach}};
      std::size_t total = 0;
      line += " |";
      for (int k = 0; k < 2; ++k) {
        s.shape = shapes[k];
        const BarSolution sol = solve_bobaru_bar(s);
        total = sol.x.size();
        const double err = 100 * (sol.u_probe - s.probe) / s.probe;
        nu_err[f][k].push_back(std::max(std::abs(err), 1e-12));
        if (k == 0) line += fmt::format(" {:>6}", total);
        line += fmt::format(" {:>+8.3f} {:>6.3f}", err, pub_nu[f][k][r]);
        if (csv) csv << fmt::format("II,{}x,{},{},{},{},{:.6g},{}\n", s.factor, shape_name[k], total,
                                    dc, dc / s.factor, err, pub_nu[f][k][r]);
      }
      nu_nodes[f].push_back(static_cast<double>(total));
    }
    fmt::print("{:>6}{}\n", nodes2[r], line);
  }
  fmt::print("rates of |error|: 2x constant {:.3f} (published 0.9296), triangular {:.3f} (1.643); "
             "4x constant {:.3f} (1.0722), triangular {:.3f} (1.642)\n",
             fitted_rate(nu_nodes[0], nu_err[0][0]), fitted_rate(nu_nodes[0], nu_err[0][1]),
             fitted_rate(nu_nodes[1], nu_err[1][0]), fitted_rate(nu_nodes[1], nu_err[1][1]));
  // Closed form: at integer m the triangular kernel's midpoint sum of g(xi) xi over exact cells
  // is (m^2 - 1)/(6 m^2) delta^2 instead of delta^2/6, a modulus E (1 - 1/m^2).
  fmt::print("Triangular: the zone's quadrature stiffness defect 1/m^2 = {:.3f}, {:.3f}, {:.3f}, "
             "{:.3f} % gives u = x/(E(1 - 1/m^2)) between the loads; constant: exact for the "
             "linear field once the fine horizon no longer reaches from a load to the probe.\n\n",
             100 / (m2[0] * m2[0]), 100 / (m2[1] * m2[1]), 100 / (m2[2] * m2[2]), 100 / (m2[3] * m2[3]));

  // Table I: placement of a refined zone (density x2, horizon / 2) on a bar of length 4, with the
  // published horizon sequence: fine delta 0.2, 0.15, 0.133, 0.125 (= 0.2 (q + 1) / 2q) and
  // m = 5 (q + 1) = 10 ... 25 on both sides (the paper's coarse horizons are 2.2x, ours 2x).
  // The seeds do not give the zone bounds; ours, in coarse horizons delta_c:
  //  (a) [-(a + delta_c/2), a + delta_c/2]: contains the loads, coarse nodes still see them;
  //  (b) [-(a + 3 delta_c/2), a + 3 delta_c/2]: loads seen by refined nodes only;
  //  (c) [-(a - delta_c), a - delta_c]: strictly inside the loads;
  //  (d) [+-a - 3 delta_c/2, +-a + 3 delta_c/2]: around each load (error at x = 0.7).
  fmt::print("Bobaru et al. 2009, Table I (refined zone x2 on a bar of length 4; rates of the "
             "error of u at x = 0.5, case d at 0.7)\n");
  fmt::print("{:>4} {:>11} | {:>30} | {:>8} {:>10}\n", "case", "shape", "errors % (fine delta 0.2 .. 0.125)",
             "rate", "published");
  const double pub_rate[4][2] = {{1.175, 1.800}, {1.179, 2.040}, {1.165, 1.745}, {1.355, 1.860}};
  const char* cases = "abcd";
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 2; ++k) {
      std::vector<double> tot, err;
      std::string line;
      for (int q = 1; q <= 4; ++q) {
        BarSpec s;
        s.length = 4.0;
        s.m = 5.0 * (q + 1);
        s.dx = 2.0 * (0.2 * (q + 1) / (2.0 * q)) / s.m;  // coarse spacing: twice the fine one
        s.factor = 2;
        s.shape = shapes[k];
        const double dc = s.m * s.dx, a = s.a;
        switch (c) {
          case 0: s.zones = {{-(a + 0.5 * dc), a + 0.5 * dc}}; break;
          case 1: s.zones = {{-(a + 1.5 * dc), a + 1.5 * dc}}; break;
          case 2: s.zones = {{-(a - dc), a - dc}}; break;
          default:
            s.zones = {{-a - 1.5 * dc, -a + 1.5 * dc}, {a - 1.5 * dc, a + 1.5 * dc}};
            s.probe = 0.7;
        }
        for (BarZone& z : s.zones) {  // snap to the coarse lattice
          z.lo = std::round(z.lo / s.dx) * s.dx;
          z.hi = std::round(z.hi / s.dx) * s.dx;
        }
        const BarSolution sol = solve_bobaru_bar(s);
        tot.push_back(static_cast<double>(sol.x.size()));
        err.push_back(100 * sol.relative_error);
        line += fmt::format("{:7.3f}", err.back());
        if (csv) csv << fmt::format("I,{},{},{},{},{},{:.6g},\n", cases[c], shape_name[k],
                                    sol.x.size(), dc, dc / 2, err.back());
      }
      // A rate needs errors above round-off: with exact midpoint overlaps a constant
      // micromodulus reproduces the linear field between the loads exactly in several cases.
      const bool resolved = *std::min_element(err.begin(), err.end()) > 1e-6;
      fmt::print("({}) {:>11} | {:>30} | {:>8} {:>10.3f}\n", cases[c], shape_name[k], line,
                 resolved ? fmt::format("{:.3f}", fitted_rate(tot, err)) : std::string("exact"),
                 pub_rate[c][k]);
    }
  return 0;
}

}  // namespace periadapt
