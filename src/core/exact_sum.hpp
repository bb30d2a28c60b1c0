#pragma once
// The exact sum of doubles in a fixed-point accumulator wide enough for every finite double
// (2^-1074 ... 2^1024, with room for 2^30 carries), so that the result is the same bits whatever
// the order of the terms: threads and ranks may each add their own nodes and then add their
// accumulators (mpi::sum_exact), and a distributed run's history sums equal the serial run's.
// Each term costs a few integer additions. value() rounds the exact sum to a double
// deterministically (within one unit in the last place); infinities and NaN propagate.
#include <array>
#include <cstdint>

namespace periadapt {

class ExactSum {
 public:
  // 32-bit digits in 64-bit limbs: 64 limbs span the doubles' 2,098 bit positions with a mantissa
  // crossing three of them; the limbs above take the carries and the sign.
  static constexpr int kLimbs = 68;

  void add(double x);
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
