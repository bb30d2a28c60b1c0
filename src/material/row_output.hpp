#pragma once
// A force pass's per-row output over `rows` (every row when null), e.g. the stretch trigger's
// measure: the rows the pass skips keep their values, new nodes start at `none`, and listed rows
// that are inactive (parents an event switched off; the kernels skip them) hold `none`.
#include <cstdint>
#include <vector>

#include "core/node_set.hpp"

namespace periadapt {

inline double* prepare_row_output(std::vector<double>* out, const NodeSet& ns,
                                  const std::vector<std::uint32_t>* rows, double none) {
  if (!out) return nullptr;
  out->resize(ns.size(), none);
  const std::size_t n = rows ? rows->size() : ns.size();
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = rows ? (*rows)[r] : r;
    if (!(ns.flags[i] & kActive)) (*out)[i] = none;
  }
  return out->data();
}

}  // namespace periadapt
