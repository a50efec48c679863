#pragma once
// Bonds as bytes, for the messages of a run split over ranks (issue 19): a bond goes with
// a particle that moves to another rank's brick, and every rank's bonds are gathered
// where the run is made whole. A bond carries what its step reads and keeps (its ends'
// ids, kind, rest length, section, sequence and loads); its scratch fields start at 0.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/bond_store.hpp"

namespace regodem {

/// The bytes one bond adds to a message.
std::size_t bytes_per_bond();

/// Appends to `bytes` the count of the bonds at `indices` of `bonds`, then each of them.
void pack_bonds(const BondStore& bonds, std::span<const std::uint32_t> indices, std::vector<std::byte>& bytes);

/// Appends to `bonds` the bonds of one message pack_bonds wrote at the start of `bytes`
/// (their local indices unknown until BondStore::refresh_indices); returns the bytes it
/// took. Throws SimulationError when the bytes end early.
std::size_t unpack_bonds(std::span<const std::byte> bytes, BondStore& bonds);

}  // namespace regodem
