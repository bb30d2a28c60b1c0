#include "material/impactor.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/node_set.hpp"

namespace periadapt {

namespace {

struct Touch {
  double depth = 0;  // p > 0: in contact
  Vec3 normal{0, 0, 0};
};

// Signed distance from the impactor's surface (negative inside) and the outward normal there.
Touch touch(const Impactor& im, const Vec3& y, double reach) {
  const Vec3 r = sub(y, im.center);
  Touch t;
  if (im.shape == Impactor::Shape::Sphere) {
    const double d = norm(r);
    if (!(d > 0)) return t;
    t.depth = reach - (d - im.radius);
    t.normal = scale(r, 1.0 / d);
    return t;
  }
  const double a = dot(r, im.axis);
  const Vec3 radial = sub(r, scale(im.axis, a));
  const double rho = norm(radial);
  const Vec3 er = rho > 0 ? scale(radial, 1.0 / rho) : Vec3{0, 0, 0};
  const Vec3 ea = scale(im.axis, a >= 0 ? 1.0 : -1.0);
  const double dr = rho - im.radius, da = std::abs(a) - im.half_length;
  if (dr <= 0 && da <= 0) {
    // Inside: out through the nearer face.
    t.depth = reach - std::max(dr, da);
    t.normal = dr > da ? er : ea;
    if (dr > da && !(rho > 0)) t.normal = ea;
    return t;
  }
  const double pr = std::max(dr, 0.0), pa = std::max(da, 0.0);
  const double d = std::hypot(pr, pa);
  t.depth = reach - d;
  t.normal = scale(add(scale(er, pr), scale(ea, pa)), 1.0 / d);
  return t;
}

double node_stiffness(const Impactor& im, const NodeSet& ns, std::size_t i) {
  return im.stiffness_factor * ns.micromodulus[i] / ns.horizon[i] * ns.volume[i] * ns.volume[i];
}

Vec3 current(const NodeSet& ns, std::size_t i) {
  return {ns.cur[4 * i], ns.dim > 1 ? ns.cur[4 * i + 1] : 0.0, ns.dim > 2 ? ns.cur[4 * i + 2] : 0.0};
}

}  // namespace

void add_impactor_forces(std::vector<Impactor>& impactors, NodeSet& ns,
                         const std::vector<std::uint32_t>* rows, std::vector<double>* W) {
  const std::size_t n = ns.size();
  std::vector<char> in_rows;
  if (rows) {
    in_rows.assign(n, 0);
    for (std::uint32_t i : *rows) in_rows[i] = 1;
  }
  // Fixed blocks of nodes, summed in block order: the impactor's force has one order of
  // summation whatever the thread count.
  constexpr std::size_t kBlock = 4096;
  const std::size_t nb = (n + kBlock - 1) / kBlock;
  std::vector<std::array<double, 4>> part(nb);
  for (Impactor& im : impactors) {
#pragma omp parallel for schedule(static)
    for (std::size_t b = 0; b < nb; ++b) {
      std::array<double, 4> s{0, 0, 0, 0};  // force on the impactor, contact energy
      for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
        if (!(ns.flags[i] & kActive)) continue;
        const Touch t = touch(im, current(ns, i), 0.5 * ns.spacing[i]);
        if (!(t.depth > 0)) continue;
        const double k = node_stiffness(im, ns, i);
        const Vec3 F = scale(t.normal, k * t.depth);
        for (int d = 0; d < 3; ++d) s[d] -= F[d];
        s[3] += 0.5 * k * t.depth * t.depth;
        if (rows && !in_rows[i]) continue;
        for (int d = 0; d < ns.dim; ++d) ns.f[d][i] += F[d] / ns.volume[i];
        if (W) (*W)[i] += 0.5 * k * t.depth * t.depth / ns.volume[i];
      }
      part[b] = s;
    }
    std::array<double, 4> total{0, 0, 0, 0};
    for (const auto& s : part)
      for (int d = 0; d < 4; ++d) total[d] += s[d];
    im.force = {total[0], total[1], total[2]};
    im.contact_energy = total[3];
  }
}

void add_impactor_energy(const std::vector<Impactor>& impactors, const NodeSet& ns,
                         std::vector<double>& W) {
  for (const Impactor& im : impactors)
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (!(ns.flags[i] & kActive)) continue;
      const Touch t = touch(im, current(ns, i), 0.5 * ns.spacing[i]);
      if (t.depth > 0) W[i] += 0.5 * node_stiffness(im, ns, i) * t.depth * t.depth / ns.volume[i];
    }
}

double impactor_stiffness_bound(const std::vector<Impactor>& impactors, const NodeSet& ns,
                                std::size_t i) {
  double k = 0;
  for (const Impactor& im : impactors)
    k = std::max(k, im.stiffness_factor * ns.micromodulus[i] / ns.horizon[i] * ns.volume[i]);
  return k;
}

}  // namespace periadapt
