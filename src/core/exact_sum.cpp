#include "core/exact_sum.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace regodem {
namespace {

constexpr std::int64_t kDigitMask = 0xffffffff;

/// Every word but the last into [0, 2^32), the rest carried up (an arithmetic shift
/// floors, so negative words borrow); the value is unchanged and its digits unique.
template <std::size_t N>
void carry_words(std::array<std::int64_t, N>& words) {
  for (std::size_t i = 0; i + 1 < N; ++i) {
    const std::int64_t up = words[i] >> 32;
    words[i] &= kDigitMask;
    words[i + 1] += up;
  }
}

}  // namespace

void ExactSum::add(double term) {
  if (term == 0.0) return;
  if (!std::isfinite(term)) {
    non_finite_ += term;
    has_non_finite_ = true;
    return;
  }
  int exponent = 0;
  const double fraction = std::frexp(std::abs(term), &exponent);  // in [0.5, 1)
  auto significand = static_cast<std::uint64_t>(std::ldexp(fraction, 53));  // exact, < 2^53
  int position = exponent - 53 - kLowestExponent;  // of the significand's lowest bit
  if (position < 0) {  // a subnormal: the bits shifted out are zeros
    significand >>= -position;
    position = 0;
  }
  const auto word = static_cast<std::size_t>(position / kDigitBits);
  const int shift = position % kDigitBits;
  // The significand in two halves, each shifted into place: < 2^63 and < 2^53.
  const std::uint64_t low = (significand & kDigitMask) << shift;
  const std::uint64_t high = (significand >> 32) << shift;
  const std::int64_t sign = term < 0.0 ? -1 : 1;
  words_[word] += sign * static_cast<std::int64_t>(low & kDigitMask);
  words_[word + 1] += sign * static_cast<std::int64_t>((low >> 32) + (high & kDigitMask));
  words_[word + 2] += sign * static_cast<std::int64_t>(high >> 32);
  // Each word took less than 2^33: carried long before it could overflow.
  if (++terms_since_carry_ >= kCarryEvery) carry();
}

void ExactSum::carry() {
  carry_words(words_);
  terms_since_carry_ = 0;
}

void ExactSum::merge(const ExactSum& other) {
  ExactSum theirs = other;
  theirs.carry();
  carry();
  for (std::size_t i = 0; i < kWords; ++i) words_[i] += theirs.words_[i];
  carry();
  if (other.has_non_finite_) {
    non_finite_ += other.non_finite_;
    has_non_finite_ = true;
  }
}

double ExactSum::value() const {
  if (has_non_finite_) return non_finite_;
  std::array<std::int64_t, kWords> digits = words_;
  carry_words(digits);
  // Sign and magnitude, then the digits added from the most significant: the rounding
  // depends on the digits alone, which the value fixes.
  const bool negative = digits[kWords - 1] < 0;
  if (negative) {
    for (std::int64_t& d : digits) d = -d;
    carry_words(digits);
  }
  double sum = 0.0;
  for (std::size_t i = kWords; i-- > 0;)
    if (digits[i] != 0)
      sum += std::ldexp(static_cast<double>(digits[i]), static_cast<int>(i) * kDigitBits + kLowestExponent);
  return negative ? -sum : sum;
}

void ExactSum::append_to(std::vector<double>& out) const {
  // Sign and magnitude: a negative sum's two's-complement digits would run to the top word.
  std::array<std::int64_t, kWords> digits = words_;
  carry_words(digits);
  const bool negative = digits[kWords - 1] < 0;
  if (negative) {
    for (std::int64_t& d : digits) d = -d;
    carry_words(digits);
  }
  std::size_t lowest = 0, end = 0;  // the words that are not zero: [lowest, end)
  for (std::size_t i = 0; i < kWords; ++i)
    if (digits[i] != 0) {
      if (end == 0) lowest = i;
      end = i + 1;
    }
  out.insert(out.end(), {has_non_finite_ ? 1.0 : 0.0, non_finite_, negative ? -1.0 : 1.0, static_cast<double>(lowest),
                         static_cast<double>(end - lowest)});
  // Digits below 2^32, and a last word far smaller than 2^53: exact as doubles.
  for (std::size_t i = lowest; i < end; ++i) out.push_back(static_cast<double>(digits[i]));
}

ExactSum ExactSum::read_from(std::span<const double> in, std::size_t& at) {
  const auto malformed = [&](const char* why) {
    return std::invalid_argument("an exact sum's record at " + std::to_string(at) + " is malformed: " + why);
  };
  if (at + 5 > in.size()) throw malformed("it is cut short");
  ExactSum sum;
  sum.has_non_finite_ = in[at] != 0.0;
  sum.non_finite_ = in[at + 1];
  const double sign = in[at + 2], lowest = in[at + 3], count = in[at + 4];
  if (sign != 1.0 && sign != -1.0) throw malformed("its sign is neither +1 nor -1");
  if (!(lowest >= 0.0 && count >= 0.0 && lowest + count <= static_cast<double>(kWords)))
    throw malformed("its digits lie outside the accumulator");
  const auto first = static_cast<std::size_t>(lowest), n = static_cast<std::size_t>(count);
  if (at + 5 + n > in.size()) throw malformed("its digits are cut short");
  for (std::size_t k = 0; k < n; ++k)
    sum.words_[first + k] = static_cast<std::int64_t>(sign) * static_cast<std::int64_t>(in[at + 5 + k]);
  at += 5 + n;
  return sum;
}

}  // namespace regodem
