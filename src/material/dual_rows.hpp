#pragma once
// A distributed pass of a dual-horizon kernel (solver/internal_forces.cpp): a node's force
// gathers the memberships that point at it from their owners' rows, so a rank evaluates the
// memberships of `first` (its rows and the rows with a membership pointing at one of them) and
// gathers the forces of `rows` (its own). A membership breaks in its owner's rank only (`own`,
// per node); the caller shares the breaks. Null: every row, the serial pass.
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace periadapt {

using BrokenMemberships = std::vector<std::pair<std::uint64_t, std::uint32_t>>;  // (bond, owner)
// A gathered break in a row this rank does not hold (held bond rows): counted, not applied.
inline constexpr std::uint64_t kBondNotHeld = ~std::uint64_t{0};

struct DualRows {
  const std::vector<std::uint32_t>* first = nullptr;
  const std::vector<std::uint32_t>* rows = nullptr;
  const char* own = nullptr;
  // LPS, whose dilatations read every bond's state: turns this rank's breaks, found before the
  // dilatation pass, into every rank's, sorted (collective); those in rows this rank does not
  // hold come back as kBondNotHeld.
  std::function<void(BrokenMemberships&)> gather_breaks;

  std::size_t count(std::size_t n, bool gathered) const {
    const auto* r = gathered ? rows : first;
    return r ? r->size() : n;
  }
  std::size_t at(std::size_t k, bool gathered) const {
    const auto* r = gathered ? rows : first;
    return r ? (*r)[k] : k;
  }
  bool breaks_here(std::size_t i) const { return !own || own[i]; }
};

}  // namespace periadapt
