#include "core/exact_sum.hpp"

#include <cmath>

namespace periadapt {

namespace {
constexpr std::int64_t kDigit = std::int64_t{1} << 32;
}  // namespace

void ExactSum::add(const ExactSum& other) {
  ExactSum o = other;
  o.normalize();
  normalize();
  for (int k = 0; k < kLimbs; ++k) limb_[k] += o.limb_[k];
  special_ += o.special_;
  normalize();
}

void ExactSum::normalize() {
  for (int k = 0; k + 1 < kLimbs; ++k) {
    // Floor division by 2^32 (an arithmetic shift), so that the digit left is in [0, 2^32).
    const std::int64_t carry = limb_[k] >> 32;
    limb_[k] -= carry * kDigit;
    limb_[k + 1] += carry;
  }
  pending_ = 0;
}

double ExactSum::value() const {
  if (special_ != 0 || std::isnan(special_)) return special_;
  ExactSum t = *this;
  t.normalize();
  const bool negative = t.limb_[kLimbs - 1] < 0;
  if (negative) {
    for (std::int64_t& l : t.limb_) l = -l;
    t.normalize();
  }
  int top = kLimbs - 1;
  while (top >= 0 && t.limb_[top] == 0) --top;
  if (top < 0) return 0.0;
  // The three highest digits carry 64 bits or more beyond the leading one; the digits below
  // weigh less than 2^-64 of the sum. Added from the lowest, they round within one ulp, the
  // same way every time.
  double r = 0;
  for (int k = top >= 2 ? top - 2 : 0; k <= top; ++k)
    r += std::ldexp(static_cast<double>(t.limb_[k]), 32 * k - 1074);
  return negative ? -r : r;
}

}  // namespace periadapt
