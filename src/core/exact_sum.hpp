#pragma once
// A sum of doubles kept exact until it is read, so that it does not depend on the order
// of its terms: a sum over particles (energies, mean temperatures, a region's statistics)
// comes out the same bits whatever order the particles are in, on any thread or MPI rank
// count (issue 19: ranks reduce their partial sums instead of gathering the particles).
//
// Kulisch's long accumulator: every finite double is an integer times 2^-1074, so the
// sum is held as a fixed-point integer over the whole double range, in 32-bit digits kept
// in signed 64-bit words. A term adds its 53-bit significand to at most three digits,
// less than 2^33 to each: a word could take 2^30 terms before overflowing, and is
// carried every 2^28.
// Reading turns the exact sum into a double by one fixed rule (its digits added from the
// most significant: within one unit in the last place, not always the nearest double),
// a function of the exact value alone.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace regodem {

class ExactSum {
 public:
  void add(double term);
  ExactSum& operator+=(double term) {
    add(term);
    return *this;
  }
  /// Adds another sum's terms (exactly).
  void merge(const ExactSum& other);
  /// The sum rounded to a double: the same for the same terms in any order. An infinite
  /// or NaN term makes it what adding the non-finite terms as doubles gives.
  double value() const;

  /// For a message between ranks: appends a few doubles (each exact: the sign, then the
  /// magnitude's nonzero 32-bit digits) that read_from() turns back into this sum.
  void append_to(std::vector<double>& out) const;
  /// Reads one sum written by append_to() at `at` and moves `at` past it. Throws
  /// std::invalid_argument on a malformed record.
  static ExactSum read_from(std::span<const double> in, std::size_t& at);

 private:
  static constexpr int kDigitBits = 32;
  static constexpr int kLowestExponent = -1074;  // of the least subnormal
  // Bits 0 .. 2098 hold any double's significand; the rest is room for the carries of
  // 2^31 terms and a sign.
  static constexpr std::size_t kWords = 68;
  static constexpr std::uint32_t kCarryEvery = 1u << 28;

  void carry();  // every word but the last into [0, 2^32); the last holds the sign

  std::array<std::int64_t, kWords> words_{};
  std::uint32_t terms_since_carry_ = 0;
  double non_finite_ = 0.0;  // the infinite and NaN terms, added as doubles
  bool has_non_finite_ = false;
};

}  // namespace regodem
