#include "parallel/ghost_layer.hpp"

#include <bit>

#include "parallel/mpi_env.hpp"

namespace periadapt {

void refresh_ghost_layer(RowPartition& p, const BondFamilies& bf,
                         const std::vector<std::uint32_t>& around) {
  if (p.region_generation == p.generation) return;
  const std::size_t n = p.mine.size();
  std::vector<char> in(p.mine.begin(), p.mine.end());
  for (std::uint32_t i : around) {
    in[i] = 1;
    for (std::uint64_t k = bf.begin(i); k < bf.end(i); ++k) in[bf.neighbor[k]] = 1;
  }
  p.region.clear();
  std::vector<std::uint32_t> ghosts;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in[i]) continue;
    p.region.push_back(static_cast<std::uint32_t>(i));
    if (!p.mine[i]) ghosts.push_back(static_cast<std::uint32_t>(i));
  }
  // Every rank's ghosts: what this rank sends each peer is its own nodes among that peer's
  // ghosts; what it receives, its ghosts grouped by owner.
  std::vector<int> counts;
  const std::vector<std::uint32_t> all_ghosts = mpi::all_gather(ghosts, &counts);
  const int P = mpi::size(), me = mpi::rank();
  std::vector<std::vector<std::uint32_t>> send(static_cast<std::size_t>(P)), recv(static_cast<std::size_t>(P));
  std::size_t at = 0;
  for (int r = 0; r < P; ++r) {
    const std::size_t end = at + static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]);
    if (r != me)
      for (std::size_t q = at; q < end; ++q)
        if (p.mine[all_ghosts[q]]) send[static_cast<std::size_t>(r)].push_back(all_ghosts[q]);
    at = end;
  }
  for (std::uint32_t g : ghosts) recv[static_cast<std::size_t>(p.owner[g])].push_back(g);
  p.peers.clear();
  p.send_ids.clear();
  p.recv_ids.clear();
  for (int r = 0; r < P; ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (send[k].empty() && recv[k].empty()) continue;
    p.peers.push_back(r);
    p.send_ids.push_back(std::move(send[k]));
    p.recv_ids.push_back(std::move(recv[k]));
  }
  p.ghosts = ghosts.size();
  p.in_region = std::move(in);
  p.region_generation = p.generation;
}

void share_ghost_forces(const RowPartition& p, NodeSet& ns) {
  const int D = ns.dim;
  double* f[3] = {ns.f[0].data(), ns.f[1].data(), ns.f[2].data()};
  // Reused from step to step: the exchange neither allocates nor clears them.
  static std::vector<std::vector<double>> send, recv;
  send.resize(p.peers.size());
  recv.resize(p.peers.size());
  for (std::size_t k = 0; k < p.peers.size(); ++k) {
    send[k].resize(p.send_ids[k].size() * static_cast<std::size_t>(D));
    recv[k].resize(p.recv_ids[k].size() * static_cast<std::size_t>(D));
    for (std::size_t q = 0; q < p.send_ids[k].size(); ++q)
      for (int d = 0; d < D; ++d) send[k][q * D + d] = f[d][p.send_ids[k][q]];
  }
  mpi::exchange_with(p.peers, send, recv);
  for (std::size_t k = 0; k < p.peers.size(); ++k)
    for (std::size_t q = 0; q < p.recv_ids[k].size(); ++q)
      for (int d = 0; d < D; ++d) f[d][p.recv_ids[k][q]] = recv[k][q * D + d];
}

void gather_owned_state(const RowPartition& p, NodeSet& ns,
                        const std::vector<std::vector<double>*>& per_row) {
  const int D = ns.dim;
  const std::size_t width = 4 * static_cast<std::size_t>(D) + per_row.size();
  std::vector<double> values(p.owned.size() * width), all_values;
  for (std::size_t k = 0; k < p.owned.size(); ++k) {
    const std::uint32_t i = p.owned[k];
    double* v = &values[k * width];
    for (int d = 0; d < D; ++d) {
      v[d] = ns.u[d][i];
      v[D + d] = ns.v[d][i];
      v[2 * D + d] = ns.a[d][i];
      v[3 * D + d] = ns.f[d][i];
    }
    for (std::size_t q = 0; q < per_row.size(); ++q) v[4 * D + q] = (*per_row[q])[i];
  }
  std::vector<int> counts;
  mpi::all_gather_into(values, all_values, &counts);
  const std::size_t own_begin = mpi::own_offset(counts) / width, own_end = own_begin + p.owned.size();
  for (std::size_t k = 0; k < p.all_owned.size(); ++k) {
    if (k == own_begin) k = own_end;
    if (k >= p.all_owned.size()) break;
    const std::uint32_t i = p.all_owned[k];
    const double* v = &all_values[k * width];
    for (int d = 0; d < D; ++d) {
      ns.u[d][i] = v[d];
      ns.v[d][i] = v[D + d];
      ns.a[d][i] = v[2 * D + d];
      ns.f[d][i] = v[3 * D + d];
    }
    for (std::size_t q = 0; q < per_row.size(); ++q) (*per_row[q])[i] = v[4 * D + q];
    ns.sync_current(i);
  }
}

long stale_region_nodes(const RowPartition& p, const NodeSet& ns) {
  const int D = ns.dim;
  const std::size_t width = 2 * static_cast<std::size_t>(D);
  std::vector<double> values(p.owned.size() * width);
  for (std::size_t k = 0; k < p.owned.size(); ++k)
    for (int d = 0; d < D; ++d) {
      values[k * width + d] = ns.u[d][p.owned[k]];
      values[k * width + D + d] = ns.v[d][p.owned[k]];
    }
  const std::vector<double> all = mpi::all_gather(values);
  long stale = 0;
  for (std::size_t k = 0; k < p.all_owned.size(); ++k) {
    const std::uint32_t i = p.all_owned[k];
    if (i >= p.in_region.size() || !p.in_region[i]) continue;
    for (int d = 0; d < D; ++d)
      if (std::bit_cast<std::uint64_t>(ns.u[d][i]) != std::bit_cast<std::uint64_t>(all[k * width + d]) ||
          std::bit_cast<std::uint64_t>(ns.v[d][i]) != std::bit_cast<std::uint64_t>(all[k * width + D + d])) {
        ++stale;
        break;
      }
  }
  // A count is exact in a double.
  return static_cast<long>(mpi::sum_real(static_cast<double>(stale)));
}

}  // namespace periadapt
