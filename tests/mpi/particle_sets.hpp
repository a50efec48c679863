#pragma once
// The particles the MPI tests share: every rank draws the same set from one seed, so each
// can check what it holds against the whole.
#include "core/particle_store.hpp"
#include "core/rng.hpp"
#include "parallel/mpi/communicator.hpp"
#include "parallel/recursive_bisection.hpp"

namespace regodem {

const Brick kDomain{{-0.05, -0.05, 0.0}, {0.05, 0.05, 0.2}};
constexpr std::size_t kParticles = 4000;

// The whole set, ids 0 .. kParticles - 1.
inline ParticleStore whole_set() {
  Rng rng(31);
  ParticleStore all;
  for (std::size_t k = 0; k < kParticles; ++k) {
    NewParticle p;
    p.position_m = {rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(0.0, 0.2)};
    p.velocity_m_per_s = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    p.angular_velocity_rad_per_s = {rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50)};
    p.radius_m = rng.uniform(3e-4, 1.2e-3);
    p.density_kg_per_m3 = 3100.0;
    p.material = static_cast<MaterialIndex>(k % 2);
    p.region = static_cast<RegionTag>(k % 4);
    p.temperature_K = rng.uniform(80, 250);
    all.add(p);
  }
  return all;
}

// Rank r starts with the particles k with k % ranks == r: nowhere near its brick.
inline ParticleStore dealt(ParticleStore& all, const Communicator& comm) {
  std::vector<char> other(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) other[k] = static_cast<int>(k % comm.size()) != comm.rank();
  ParticleStore mine = all;
  mine.remove_if(other);
  return mine;
}

}  // namespace regodem
