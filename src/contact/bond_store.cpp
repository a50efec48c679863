#include "contact/bond_store.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace regodem {
namespace {
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
}

void BondStore::add(const ParticleStore& particles, std::uint32_t a, std::uint32_t b, std::uint16_t bond_kind,
                    const BondSection& bond_section) {
  id_i.push_back(particles.id[a]);
  id_j.push_back(particles.id[b]);
  local_i.push_back(a);
  local_j.push_back(b);
  kind.push_back(bond_kind);
  const Vec3 d = particles.position_m[b] - particles.position_m[a];
  rest_length_m.push_back(norm(d));
  section.push_back(bond_section);
  sequence.push_back(static_cast<std::uint32_t>(size() - 1));
  for_each_field([&](auto member, auto role) {
    if constexpr (role == FieldRole::pass_result) (this->*member).emplace_back();
  });
  resize_state(size());
  set_state(size() - 1, normalized(d), {});
  broken.push_back(0);
}

void BondStore::set_state(std::size_t b, const Vec3& normal, const BondLoads& loads) {
  state[normal_x][b] = normal.x;
  state[normal_y][b] = normal.y;
  state[normal_z][b] = normal.z;
  state[normal_force][b] = loads.normal_force_N;
  state[twist_moment][b] = loads.twist_moment_N_m;
  state[shear_x][b] = loads.shear_force_N.x;
  state[shear_y][b] = loads.shear_force_N.y;
  state[shear_z][b] = loads.shear_force_N.z;
  state[bend_x][b] = loads.bend_moment_N_m.x;
  state[bend_y][b] = loads.bend_moment_N_m.y;
  state[bend_z][b] = loads.bend_moment_N_m.z;
}

void BondStore::resize_state(std::size_t bonds) {
  for (std::vector<double>& row : state) row.resize(bonds + kStatePadding, 0.0);
}

std::size_t BondStore::refresh_indices(const ParticleStore& particles) {
  const std::size_t n = particles.size();
  // (id, index) sorted by id: a look-up that grows with the particles, not the ids.
  std::vector<std::pair<ParticleId, std::uint32_t>> by_id(n);
  for (std::size_t p = 0; p < n; ++p) by_id[p] = {particles.id[p], static_cast<std::uint32_t>(p)};
  std::sort(by_id.begin(), by_id.end());
  const auto index_of = [&](ParticleId id) {
    const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair<ParticleId, std::uint32_t>{id, 0});
    return it != by_id.end() && it->first == id ? it->second : kNone;
  };
  for (std::size_t b = 0; b < size(); ++b) {
    local_i[b] = index_of(id_i[b]);
    local_j[b] = index_of(id_j[b]);
  }
  for (std::size_t b = 0; b < size(); ++b)
    if (local_i[b] == kNone || local_j[b] == kNone) return b;
  rebuild_per_particle(n);
  return size();
}

void BondStore::renumber(const std::vector<std::uint32_t>& new_index_of_old, std::size_t particle_count, int threads) {
  const std::size_t nb = size();
#pragma omp parallel for schedule(static) num_threads(threads) if (nb > 4096)
  for (std::size_t b = 0; b < nb; ++b) {
    local_i[b] = new_index_of_old[local_i[b]];
    local_j[b] = new_index_of_old[local_j[b]];
  }
  rebuild_per_particle(particle_count);
}

void BondStore::remove_broken(const ParticleStore& particles, int threads) {
  // The bonds before the first broken one stay where they are; each field is moved up
  // on its own, the fields shared out over the threads.
  std::size_t first = 0;
  while (first < size() && !broken[first]) ++first;
  std::size_t kept = first;
  for (std::size_t b = first; b < size(); ++b) kept += broken[b] == 0;
  const auto compact = [&](auto& field) {
    std::size_t to = first;
    for (std::size_t b = first; b < size(); ++b)
      if (!broken[b]) field[to++] = field[b];
  };
  const int jobs = kFields + static_cast<int>(state.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (size() > 4096)
  for (int job = 0; job < jobs; ++job) {
    if (job >= kFields) {
      compact(state[static_cast<std::size_t>(job - kFields)]);
      continue;
    }
    int field = 0;
    for_each_field([&](auto member, auto) {
      if (field++ == job) compact(this->*member);
    });
  }
  for_each_field([&](auto member, auto) { (this->*member).resize(kept); });
  resize_state(kept);
  broken.assign(kept, 0);
  rebuild_per_particle(particles.size());
}

void BondStore::remove_with_particles(const ParticleStore& particles, const std::vector<char>& removed) {
  for (std::size_t b = 0; b < size(); ++b)
    if (removed[local_i[b]] || removed[local_j[b]]) broken[b] = 1;
  remove_broken(particles);
}

void BondStore::number_in_order() {
  sequence.resize(size());
  for (std::size_t b = 0; b < size(); ++b) sequence[b] = static_cast<std::uint32_t>(b);
}

void BondStore::append_from(const BondStore& from, std::size_t b) {
  for_each_field([&](auto member, auto role) {
    auto& field = this->*member;
    if constexpr (role == FieldRole::travels)
      field.push_back((from.*member)[b]);
    else if constexpr (role == FieldRole::local_index)
      field.push_back(kNone);  // found again by refresh_indices
    else
      field.emplace_back();
  });
  resize_state(size());
  for (int row = 0; row < state_rows; ++row) state[row][size() - 1] = from.state[row][b];
  broken.push_back(0);
}

void BondStore::keep_in_sequence_order(const std::vector<char>& keep) {
  std::vector<std::uint32_t> order;
  for (std::size_t b = 0; b < size(); ++b)
    if (keep[b]) order.push_back(static_cast<std::uint32_t>(b));
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t c) { return sequence[a] < sequence[c]; });
  order.erase(std::unique(order.begin(), order.end(),
                          [&](std::uint32_t a, std::uint32_t c) { return sequence[a] == sequence[c]; }),
              order.end());
  BondStore kept;
  for (const std::uint32_t b : order) kept.append_from(*this, b);
  *this = std::move(kept);
}

void BondStore::rebuild_per_particle(std::size_t particle_count) {
  // Counting sort by particle; within a particle the entries follow bond order, so
  // the gather sums in an order fixed by the bond list alone.
  bond_offset.assign(particle_count + 1, 0);
  for (std::size_t b = 0; b < size(); ++b) {
    ++bond_offset[local_i[b] + 1];
    ++bond_offset[local_j[b] + 1];
  }
  for (std::size_t p = 0; p < particle_count; ++p) bond_offset[p + 1] += bond_offset[p];
  bond_entry.assign(2 * size() + kEntryPadding, 0);
  std::vector<std::uint32_t> fill(bond_offset.begin(), bond_offset.end() - 1);
  for (std::size_t b = 0; b < size(); ++b) {
    bond_entry[fill[local_i[b]]++] = static_cast<std::uint32_t>(2 * b);
    bond_entry[fill[local_j[b]]++] = static_cast<std::uint32_t>(2 * b + 1);
  }
}

}  // namespace regodem
