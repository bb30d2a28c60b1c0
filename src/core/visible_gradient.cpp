#include "core/visible_gradient.hpp"

#include <algorithm>
#include <cmath>

namespace periadapt {

void fit_gradient(const NodeSet& ns, const BondFamilies& bf, std::uint32_t p,
                  const std::array<std::vector<double>, 3>& F, double G[3][3], const float* beta) {
  if (!beta) beta = bf.beta.data();
  const int D = ns.dim;
  double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, R[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (std::uint64_t k = bf.begin(p); k < bf.end(p); ++k) {
    if (!BondFamilies::intact(beta[k])) continue;
    const std::uint32_t j = bf.neighbor[k];
    if (!(ns.flags[j] & kActive)) continue;
    double dx[3];
    for (int e = 0; e < D; ++e) dx[e] = ns.x[e][j] - ns.x[e][p];
    for (int a = 0; a < D; ++a) {
      for (int b = 0; b < D; ++b) M[a][b] += dx[a] * dx[b];
      for (int c = 0; c < D; ++c) R[c][a] += dx[a] * (F[c][j] - F[c][p]);
    }
  }
  for (int a = 0; a < 3; ++a) G[a][0] = G[a][1] = G[a][2] = 0;
  // Invert the D x D moment matrix (Cramer); degenerate -> no gradient (parent value only).
  double inv[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  double scale = 0;
  for (int a = 0; a < D; ++a) scale = std::max(scale, M[a][a]);
  if (!(scale > 0)) return;
  if (D == 1) {
    inv[0][0] = 1.0 / M[0][0];
  } else if (D == 2) {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    if (std::abs(det) < 1e-10 * scale * scale) return;
    inv[0][0] = M[1][1] / det, inv[1][1] = M[0][0] / det;
    inv[0][1] = -M[0][1] / det, inv[1][0] = -M[1][0] / det;
  } else {
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    if (std::abs(det) < 1e-10 * scale * scale * scale) return;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int a1 = (b + 1) % 3, a2 = (b + 2) % 3, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
        inv[a][b] = (M[a1][b1] * M[a2][b2] - M[a1][b2] * M[a2][b1]) / det;
      }
  }
  for (int c = 0; c < D; ++c)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) G[c][a] += R[c][b] * inv[b][a];
}

}  // namespace periadapt
