// The exact accumulator behind the history's sums (core/exact_sum.hpp): order-free to the bit,
// exact where a plain sum cancels, within one ulp of a quad-precision reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/exact_sum.hpp"

using periadapt::ExactSum;

namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

double exact_sum(const std::vector<double>& v) {
  ExactSum s;
  for (double x : v) s.add(x);
  return s.value();
}

// Terms of mixed sign over 2^-40 ... 2^40: their quad-precision sum (113-bit mantissa) is exact
// (80 bits of range, 53 of mantissa, a few of carries).
std::vector<double> mixed_terms(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> exp(-40, 40);
  std::vector<double> v(n);
  for (double& x : v) x = std::ldexp(mant(rng), exp(rng));
  return v;
}

}  // namespace

TEST(ExactSum, TheSumDoesNotDependOnTheOrderOrOnHowPartialSumsAreCombined) {
  std::vector<double> v = mixed_terms(20000, 7);
  const double reference = exact_sum(v);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(v.begin(), v.end(), rng);
    EXPECT_EQ(bits(exact_sum(v)), bits(reference));
    // Split into uneven chunks (threads, ranks), each summed alone, then combined backwards.
    std::vector<ExactSum> parts(1 + static_cast<std::size_t>(trial) * 3);
    for (std::size_t i = 0; i < v.size(); ++i) parts[(i * i + 3 * i) % parts.size()].add(v[i]);
    ExactSum total;
    for (auto it = parts.rbegin(); it != parts.rend(); ++it) total.add(*it);
    EXPECT_EQ(bits(total.value()), bits(reference));
  }
}

TEST(ExactSum, IsWithinOneUlpOfAQuadPrecisionReference) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const std::vector<double> v = mixed_terms(5000, seed);
    __float128 q = 0;
    for (double x : v) q += x;
    const auto ref = static_cast<double>(q);
    const double got = exact_sum(v);
    EXPECT_LE(std::abs(got - ref), std::abs(std::nextafter(ref, 2 * ref) - ref)) << seed;
  }
}

TEST(ExactSum, CancellationsThatAPlainSumLosesComeOutExact) {
  EXPECT_EQ(exact_sum({1e16, 1.0, -1e16}), 1.0);  // the plain sum gives 0
  const double big = std::numeric_limits<double>::max();
  // The plain sum overflows to infinity on the way.
  EXPECT_EQ(exact_sum({big, big, 0.5, -big, -big}), 0.5);
  // The smallest subnormal survives beside 1.
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact_sum({1.0, tiny, -1.0, tiny}), 2 * tiny);
  EXPECT_EQ(exact_sum({0.1, 0.2, -0.1, -0.2}), 0.0);
  EXPECT_EQ(exact_sum({-3.5, 1.25}), -2.25);
  EXPECT_EQ(exact_sum({}), 0.0);
  // A million terms at the top of the range carry into the limbs above it without loss.
  ExactSum s;
  for (int k = 0; k < 1000000; ++k) s.add(std::ldexp(1.0, 1020));
  for (int k = 0; k < 1000000; ++k) s.add(-std::ldexp(1.0, 1020));
  s.add(3.0);
  EXPECT_EQ(s.value(), 3.0);
}

TEST(ExactSum, InfinitiesAndNaNPropagate) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(exact_sum({1.0, inf, 2.0}), inf);
  EXPECT_EQ(exact_sum({-inf, 1.0}), -inf);
  EXPECT_TRUE(std::isnan(exact_sum({inf, -inf})));
  EXPECT_TRUE(std::isnan(exact_sum({1.0, std::numeric_limits<double>::quiet_NaN()})));
  // A finite sum beyond the largest double is infinite.
  const double big = std::numeric_limits<double>::max();
  EXPECT_EQ(exact_sum({big, big}), inf);
}
