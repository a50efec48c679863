#include "parallel/particle_transfer.hpp"

#include <fmt/format.h>

#include <cstring>

#include "core/error.hpp"

namespace regodem {
namespace {

bool carried(const ParticleField& field, ParticleTransfer kind) {
  switch (kind) {
    case ParticleTransfer::migration: return field.migrates;
    case ParticleTransfer::ghost: return field.ghosts_need;
    case ParticleTransfer::ghost_refresh: return field.ghosts_refresh;
    case ParticleTransfer::whole: return true;
  }
  return false;
}

// Reads from the front of a message, checking its end.
struct MessageReader {
  std::span<const std::byte> bytes;
  std::size_t at = 0;
  void take(void* data, std::size_t size) {
    if (at + size > bytes.size())
      throw SimulationError(fmt::format("a particle message ends early: {} bytes, {} needed", bytes.size(), at + size));
    std::memcpy(data, bytes.data() + at, size);
    at += size;
  }
};

}  // namespace

std::size_t bytes_per_particle(ParticleTransfer kind) {
  ParticleStore none;
  std::size_t bytes = 0;
  none.for_each_described_field([&](const ParticleField& field, auto& values) {
    if (carried(field, kind)) bytes += sizeof(typename std::remove_reference_t<decltype(values)>::value_type);
  });
  return bytes;
}

void pack_particles(ParticleStore& store, std::span<const std::uint32_t> indices, ParticleTransfer kind,
                    std::vector<std::byte>& bytes) {
  const std::uint64_t count = indices.size();
  const auto append = [&](const void* data, std::size_t size) {
    const std::size_t at = bytes.size();
    bytes.resize(at + size);
    std::memcpy(bytes.data() + at, data, size);
  };
  append(&count, sizeof count);
  store.for_each_described_field([&](const ParticleField& field, auto& values) {
    if (!carried(field, kind)) return;
    using T = typename std::remove_reference_t<decltype(values)>::value_type;
    const std::size_t at = bytes.size();
    bytes.resize(at + indices.size() * sizeof(T));
    for (std::size_t k = 0; k < indices.size(); ++k)
      std::memcpy(bytes.data() + at + k * sizeof(T), &values[indices[k]], sizeof(T));
  });
}

std::size_t unpack_particles(std::span<const std::byte> bytes, ParticleTransfer kind, ParticleStore& store) {
  MessageReader message{bytes};
  std::uint64_t count = 0;
  message.take(&count, sizeof count);
  const std::size_t first = store.size();
  store.for_each_described_field([&](const ParticleField& field, auto& values) {
    using T = typename std::remove_reference_t<decltype(values)>::value_type;
    values.resize(first + count, T{});
    if (carried(field, kind)) message.take(values.data() + first, count * sizeof(T));
  });
  return message.at;
}

std::size_t unpack_particles_at(std::span<const std::byte> bytes, ParticleTransfer kind, ParticleStore& store,
                                std::span<const std::uint32_t> indices) {
  MessageReader message{bytes};
  std::uint64_t count = 0;
  message.take(&count, sizeof count);
  if (count != indices.size())
    throw SimulationError(fmt::format("a particle message holds {} particles for {} places", count, indices.size()));
  store.for_each_described_field([&](const ParticleField& field, auto& values) {
    if (!carried(field, kind)) return;
    for (const std::uint32_t i : indices) message.take(&values[i], sizeof values[i]);
  });
  return message.at;
}

}  // namespace regodem
