// ExactSum (core/exact_sum.hpp): the exact sum of doubles, whatever their order.
// Expected values are exact sums worked by hand; the order test compares bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/exact_sum.hpp"

namespace regodem {
namespace {

double exact_sum_of(const std::vector<double>& terms) {
  ExactSum sum;
  for (const double t : terms) sum.add(t);
  return sum.value();
}

TEST(ExactSum, KeepsWhatPlainAdditionLoses) {
  // 1e16 + 1 rounds back to 1e16 in doubles: the plain sum of these is 0.
  EXPECT_EQ(exact_sum_of({1e16, 1.0, -1e16}), 1.0);
  EXPECT_EQ(exact_sum_of({1.0, 1e100, 1.0, -1e100}), 2.0);
  // Ten times the double nearest 0.1 is 1 + 5.55e-17 exactly; the nearest double is 1.
  // Plain addition gives 0.9999999999999999.
  EXPECT_EQ(exact_sum_of(std::vector<double>(10, 0.1)), 1.0);
}

TEST(ExactSum, SignsZerosAndTheEdgesOfTheRange) {
  EXPECT_EQ(ExactSum{}.value(), 0.0);
  EXPECT_EQ(exact_sum_of({-2.5, 0.5}), -2.0);
  EXPECT_EQ(exact_sum_of({-1.0, 1.0}), 0.0);
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(exact_sum_of({tiny, tiny, tiny}), 3.0 * tiny);
  EXPECT_EQ(exact_sum_of({-tiny, 0.5, -0.5}), -tiny);
  const double huge = std::numeric_limits<double>::max();
  // Past the largest double and back: exact in the accumulator, infinite in doubles.
  EXPECT_EQ(exact_sum_of({huge, huge, -huge}), huge);
  EXPECT_EQ(exact_sum_of({huge, huge}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact_sum_of({-huge, -huge}), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact_sum_of({1.0, std::numeric_limits<double>::infinity()}), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(exact_sum_of({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

TEST(ExactSum, ManyTermsCarryWithoutLoss) {
  // Past the carry interval (2^28 terms) would take seconds; 2^22 terms of 2^40 + 1
  // each fill the words' carries well beyond one digit.
  ExactSum sum;
  const double term = std::ldexp(1.0, 40) + 1.0;
  const std::uint64_t n = std::uint64_t{1} << 22;
  for (std::uint64_t k = 0; k < n; ++k) sum.add(term);
  EXPECT_EQ(sum.value(), std::ldexp(1.0, 62) + std::ldexp(1.0, 22));
}

TEST(ExactSum, TheSameBitsInAnyOrderAndAnyGrouping) {
  // Terms over thirty orders of magnitude, of both signs: the plain sum depends on the
  // order, the exact one must not.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-50, 50);
  std::vector<double> terms(5000);
  for (double& t : terms) t = std::ldexp(mantissa(rng), exponent(rng));
  const double reference = exact_sum_of(terms);
  bool plain_sums_differed = false;
  double first_plain = 0.0;
  for (const double t : terms) first_plain += t;
  for (int shuffle = 0; shuffle < 10; ++shuffle) {
    std::shuffle(terms.begin(), terms.end(), rng);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(exact_sum_of(terms)), std::bit_cast<std::uint64_t>(reference));
    double plain = 0.0;
    for (const double t : terms) plain += t;
    plain_sums_differed = plain_sums_differed || plain != first_plain;
    // Split in three, as over three ranks, merged in any order.
    ExactSum a, b, c;
    for (std::size_t k = 0; k < terms.size(); ++k) (k % 3 == 0 ? a : k % 3 == 1 ? b : c).add(terms[k]);
    ExactSum merged = c;
    merged.merge(a);
    merged.merge(b);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(merged.value()), std::bit_cast<std::uint64_t>(reference));
  }
  EXPECT_TRUE(plain_sums_differed) << "the terms do not test the order (every plain sum agreed)";
}

TEST(ExactSum, TravelsAsDoublesBetweenRanks) {
  ExactSum a, b;
  for (const double t : {1e16, 1.0, -3e-300, 7.25}) a.add(t);
  b.add(-std::numeric_limits<double>::infinity());
  std::vector<double> message{42.0};  // something before, as in a packed message
  a.append_to(message);
  b.append_to(message);
  ExactSum{}.append_to(message);
  std::size_t at = 1;
  const ExactSum a_read = ExactSum::read_from(message, at);
  const ExactSum b_read = ExactSum::read_from(message, at);
  const ExactSum empty = ExactSum::read_from(message, at);
  EXPECT_EQ(at, message.size());
  EXPECT_EQ(a_read.value(), a.value());
  EXPECT_EQ(b_read.value(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(empty.value(), 0.0);
  // A negative sum travels as its magnitude's few digits, not a two's complement.
  ExactSum negative;
  negative.add(-1.0);
  negative.add(-0.5);
  std::vector<double> small;
  negative.append_to(small);
  EXPECT_LE(small.size(), 5u + 4u) << "a negative sum sent in " << small.size() << " doubles";
  std::size_t from_small = 0;
  EXPECT_EQ(ExactSum::read_from(small, from_small).value(), negative.value());
  EXPECT_EQ(negative.value(), -1.5);
  ExactSum with_more = a_read;
  with_more.add(-1e16);
  EXPECT_EQ(with_more.value(), 8.25);  // -3e-300 is far below the last place of 8.25
  std::vector<double> cut(message.begin(), message.begin() + 3);
  std::size_t from = 1;
  EXPECT_THROW(ExactSum::read_from(cut, from), std::invalid_argument);
}

}  // namespace
}  // namespace regodem
