#pragma once
// Particles as bytes, for the messages of a run split over ranks (issue 19): what a
// particle that moves to another rank's brick takes with it (the fields the field table
// marks `migrates`), or what a ghost image of it needs (`ghosts_need`). The field table
// (ParticleStore::for_each_described_field) decides, so a field added there travels
// without a change here.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/particle_store.hpp"

namespace regodem {

/// What a message carries: a migrating particle (fields marked `migrates`), a new ghost
/// (`ghosts_need`), a ghost's update between builds (`ghosts_refresh`), or every field (a
/// run gathered on every rank between steps, its forces kept for the next step).
enum class ParticleTransfer { migration, ghost, ghost_refresh, whole };

/// The bytes one particle adds to a message of this kind (the fields it carries).
std::size_t bytes_per_particle(ParticleTransfer kind);

/// Appends to `bytes` the particles at `indices` of `store`: their count, then each
/// field that `kind` carries, in the table's order, all the particles' values together.
void pack_particles(ParticleStore& store, std::span<const std::uint32_t> indices, ParticleTransfer kind,
                    std::vector<std::byte>& bytes);

/// Appends to `store` the particles of one message pack_particles wrote at the start of
/// `bytes` (the fields it does not carry start at 0); returns the bytes it took. Throws
/// SimulationError when the bytes end early.
std::size_t unpack_particles(std::span<const std::byte> bytes, ParticleTransfer kind, ParticleStore& store);

/// Writes the particles of one message over those at `indices` of `store` (one index per
/// particle of the message), only the fields `kind` carries; returns the bytes it took.
/// Throws SimulationError when the bytes end early or hold another count.
std::size_t unpack_particles_at(std::span<const std::byte> bytes, ParticleTransfer kind, ParticleStore& store,
                                std::span<const std::uint32_t> indices);

}  // namespace regodem
