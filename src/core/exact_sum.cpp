#include "core/exact_sum.hpp"

#include <bit>
#include <cmath>

namespace periadapt {

namespace {
constexpr std::int64_t kDigit = std::int64_t{1} << 32;
// A limb absorbs terms of less than 2^32 each: normalizing every 2^30 terms keeps it far from
// 2^63.
constexpr std::uint32_t kNormalizeEvery = 1u << 30;
}  // namespace

void ExactSum::add(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0x7ff) {
    special_ += x;
    return;
  }
  std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  // x = mantissa x 2^(position - 1074): subnormals at position 0, normals above.
  int position = 0;
  if (biased > 0) {
    mantissa |= std::uint64_t{1} << 52;
    position = biased - 1;
  }
  if (mantissa == 0) return;
  const unsigned __int128 shifted = static_cast<unsigned __int128>(mantissa) << (position & 31);
  const int k = position >> 5;
  const auto d0 = static_cast<std::int64_t>(shifted & 0xffffffffu);
  const auto d1 = static_cast<std::int64_t>((shifted >> 32) & 0xffffffffu);
  const auto d2 = static_cast<std::int64_t>(shifted >> 64);
  if (bits >> 63) {
    limb_[k] -= d0;
    limb_[k + 1] -= d1;
    limb_[k + 2] -= d2;
  } else {
    limb_[k] += d0;
    limb_[k + 1] += d1;
    limb_[k + 2] += d2;
  }
  if (++pending_ == kNormalizeEvery) normalize();
}

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
