// FNV-1a: tiny, dependency-free and stable across platforms; this is an identity for
// reports, not a security measure.
#include "scenario/content_hash.hpp"

#include <cstdint>

#include <fmt/format.h>

namespace regodem {
namespace {

constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ULL;
constexpr std::uint64_t kFnvPrime = 1099511628211ULL;

void fnv1a(std::uint64_t& hash, std::string_view bytes) {
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= kFnvPrime;
  }
}

}  // namespace

std::string scenario_content_hash(std::string_view file_bytes,
                                  const std::vector<std::string>& overrides) {
  std::uint64_t hash = kFnvOffsetBasis;
  fnv1a(hash, file_bytes);
  for (const std::string& text : overrides) {
    fnv1a(hash, std::string_view("\0", 1));
    fnv1a(hash, text);
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace regodem
