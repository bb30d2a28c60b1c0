#pragma once
// The exact sum of doubles in a fixed-point accumulator wide enough for every finite double
// (2^-1074 ... 2^1024, with room for 2^30 carries), so that the result is the same bits whatever
// the order of the terms: threads and ranks may each add their own nodes and then add their
// accumulators (mpi::sum_exact), and a distributed run's history sums equal the serial run's.
// Each term costs a few integer additions. value() rounds the exact sum to a double
// deterministically (within one unit in the last place); infinities and NaN propagate.
#include <array>
#include <bit>
#include <cstdint>

namespace periadapt {

class ExactSum {
 public:
  // 32-bit digits in 64-bit limbs: 64 limbs span the doubles' 2,098 bit positions with a mantissa
  // crossing three of them; the limbs above take the carries and the sign.
  static constexpr int kLimbs = 68;
  // A limb absorbs terms of less than 2^32 each: normalizing every 2^30 terms keeps it far from
  // 2^63.
  static constexpr std::uint32_t kNormalizeEvery = 1u << 30;

  // Inline: the history adds one term per node.
  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const auto biased = static_cast<int>((bits >> 52) & 0x7ff);
    if (biased == 0x7ff) [[unlikely]] {
      special_ += x;
      return;
    }
    // x = mantissa x 2^(position - 1074): subnormals at position 0, normals above.
    const std::uint64_t normal = biased > 0;
    const std::uint64_t mantissa = (bits & ((std::uint64_t{1} << 52) - 1)) | (normal << 52);
    const int position = biased - static_cast<int>(normal);
    const unsigned __int128 shifted = static_cast<unsigned __int128>(mantissa) << (position & 31);
    const std::int64_t sign = 1 - 2 * static_cast<std::int64_t>(bits >> 63);
    std::int64_t* l = &limb_[static_cast<std::size_t>(position >> 5)];
    l[0] += sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted) & 0xffffffffu);
    l[1] += sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> 32) & 0xffffffffu);
    l[2] += sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> 64));
    if (++pending_ == kNormalizeEvery) [[unlikely]] normalize();
  }
  void add(const ExactSum& other);
  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  double value() const;

  // The limbs with every digit in [0, 2^32) below the top one (which carries the sign), and the
  // non-finite part: what the ranks add (mpi::sum_exact). Adding P normalized accumulators limb by
  // limb stays exact below 2^31 ranks; normalize() after.
  void normalize();
  std::array<std::int64_t, kLimbs>& limbs() { return limb_; }
  double& special() { return special_; }

 private:
  std::array<std::int64_t, kLimbs> limb_{};
  double special_ = 0;         // the sum of the infinite and NaN terms
  std::uint32_t pending_ = 0;  // terms added since the last normalize()
};

}  // namespace periadapt
