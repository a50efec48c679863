#include "parallel/bond_transfer.hpp"

#include <fmt/format.h>

#include <cstring>

#include "core/error.hpp"

namespace regodem {
namespace {

// One bond's bytes: the fields that travel one after another (BondStore::for_each_field),
// the state rows last.
template <typename Store, typename F>  // Store: BondStore or const BondStore
void for_each_bond_value(Store& bonds, std::size_t b, F&& f) {
  BondStore::for_each_field([&](auto member, auto role) {
    if constexpr (role == BondStore::FieldRole::travels) {
      auto& value = (bonds.*member)[b];
      f(&value, sizeof value);
    }
  });
  for (auto& row : bonds.state) f(&row[b], sizeof(double));
}

/// A store of one bond, every field in place: what a bond is read into, or measured by.
BondStore one_bond() {
  BondStore one;
  BondStore::for_each_field([&](auto member, auto) { (one.*member).resize(1); });
  one.resize_state(1);
  return one;
}

}  // namespace

std::size_t bytes_per_bond() {
  BondStore one = one_bond();
  std::size_t bytes = 0;
  for_each_bond_value(one, 0, [&](const void*, std::size_t size) { bytes += size; });
  return bytes;
}

void pack_bonds(const BondStore& bonds, std::span<const std::uint32_t> indices, std::vector<std::byte>& bytes) {
  const auto append = [&](const void* data, std::size_t size) {
    const std::size_t at = bytes.size();
    bytes.resize(at + size);
    std::memcpy(bytes.data() + at, data, size);
  };
  const std::uint64_t count = indices.size();
  append(&count, sizeof count);
  for (const std::uint32_t b : indices) for_each_bond_value(bonds, b, append);
}

std::size_t unpack_bonds(std::span<const std::byte> bytes, BondStore& bonds) {
  std::size_t at = 0;
  const auto take = [&](void* data, std::size_t size) {
    if (at + size > bytes.size())
      throw SimulationError(fmt::format("a bond message ends early: {} bytes, {} needed", bytes.size(), at + size));
    std::memcpy(data, bytes.data() + at, size);
    at += size;
  };
  std::uint64_t count = 0;
  take(&count, sizeof count);
  BondStore one = one_bond();
  for (std::uint64_t k = 0; k < count; ++k) {
    for_each_bond_value(one, 0, take);
    bonds.append_from(one, 0);
  }
  return at;
}

}  // namespace regodem
