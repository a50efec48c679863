#include "sim/insertion.hpp"

#include <algorithm>
#include <cmath>

#include "sim/simulation.hpp"

namespace regodem {
namespace {

constexpr int kAttemptsPerParticle = 300;

/// A uniform hash-free grid over the insertion region's neighbourhood holding the
/// particles a new sphere could overlap.
class OverlapGrid {
 public:
  OverlapGrid(const Vec3& lo, const Vec3& hi, double cell) : lo_(lo), cell_(cell) {
    const Vec3 e = hi - lo;
    nx_ = std::max(1, static_cast<int>(std::ceil(e.x / cell)));
    ny_ = std::max(1, static_cast<int>(std::ceil(e.y / cell)));
    nz_ = std::max(1, static_cast<int>(std::ceil(e.z / cell)));
    cells_.resize(static_cast<std::size_t>(nx_) * ny_ * nz_);
  }
  void add(const Vec3& x, double r) {
    const std::size_t k = centres_.size();
    centres_.push_back(x);
    radii_.push_back(r);
    cells_[cell_index(x)].push_back(static_cast<std::uint32_t>(k));
  }
  bool overlaps(const Vec3& x, double r, double max_other_r) const {
    const int reach = static_cast<int>(std::ceil((r + max_other_r) / cell_));
    int cx, cy, cz;
    coordinates(x, cx, cy, cz);
    for (int iz = std::max(0, cz - reach); iz <= std::min(nz_ - 1, cz + reach); ++iz)
      for (int iy = std::max(0, cy - reach); iy <= std::min(ny_ - 1, cy + reach); ++iy)
        for (int ix = std::max(0, cx - reach); ix <= std::min(nx_ - 1, cx + reach); ++ix)
          for (std::uint32_t k : cells_[(static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix]) {
            const double sum = r + radii_[k];
            if (norm2(centres_[k] - x) < sum * sum) return true;
          }
    return false;
  }

 private:
  void coordinates(const Vec3& x, int& ix, int& iy, int& iz) const {
    auto clamp = [this](double c, double o, int n) {
      const int i = static_cast<int>(std::floor((c - o) / cell_));
      return std::clamp(i, 0, n - 1);
    };
    ix = clamp(x.x, lo_.x, nx_);
    iy = clamp(x.y, lo_.y, ny_);
    iz = clamp(x.z, lo_.z, nz_);
  }
  std::size_t cell_index(const Vec3& x) const {
    int ix, iy, iz;
    coordinates(x, ix, iy, iz);
    return (static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix;
  }
  Vec3 lo_;
  double cell_;
  int nx_ = 1, ny_ = 1, nz_ = 1;
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<Vec3> centres_;
  std::vector<double> radii_;
};

bool touches_a_wall(const Simulation& sim, const Vec3& x, double r) {
  for (const WallPrimitive& w : sim.walls.primitives) {
    const WallProximity p = closest_wall_point(w, x);
    if (p.candidate && p.distance_m < r) return true;
  }
  return false;
}

/// The size class furthest behind its share: stratified, so the counts follow the
/// fractions exactly rather than on average.
std::size_t next_size_class(const Insertion& ins) {
  std::size_t best = 0;
  double best_deficit = -1e300;
  const double next_total = static_cast<double>(ins.inserted + 1);
  for (std::size_t c = 0; c < ins.sizes.size(); ++c) {
    const double deficit = ins.sizes[c].number_fraction * next_total - static_cast<double>(ins.inserted_per_class[c]);
    if (deficit > best_deficit) best_deficit = deficit, best = c;
  }
  return best;
}

}  // namespace

void Insertion::start(double time_s) {
  inserted = 0;
  inserted_per_class.assign(sizes.size(), 0);
  start_time_s = time_s;
  attempts = 0;
  fruitless_attempts = 0;
  finished = false;
}

InsertionReport insert_due_particles(Simulation& sim, Insertion& ins, Rng& rng) {
  InsertionReport report;
  if (ins.finished) return report;
  ++ins.attempts;
  if (!ins.from_file.empty()) {
    for (const NewParticle& p : ins.from_file) sim.add_particle(p);
    report.requested = report.placed = ins.from_file.size();
    ins.inserted = ins.from_file.size();
    ins.finished = true;
    return report;
  }
  std::size_t due = ins.target_count;
  if (ins.rate_per_s > 0.0) {
    const double elapsed = static_cast<double>(ins.attempts) * ins.interval_s;
    due = std::min(ins.target_count, static_cast<std::size_t>(std::llround(ins.rate_per_s * elapsed)));
  }
  report.requested = due > ins.inserted ? due - ins.inserted : 0;
  if (report.requested == 0) {
    ins.finished = ins.inserted >= ins.target_count;
    return report;
  }

  double max_new_radius = 0.0;
  for (const SizeClass& c : ins.sizes) max_new_radius = std::max(max_new_radius, c.radius_m);
  double max_radius = max_new_radius;
  for (double r : sim.particles.radius_m) max_radius = std::max(max_radius, r);
  Vec3 lo, hi;
  ins.region.bounds(lo, hi);
  const Vec3 margin{max_radius + max_new_radius, max_radius + max_new_radius, max_radius + max_new_radius};
  lo -= margin;
  hi += margin;
  OverlapGrid grid(lo, hi, 2.0 * max_radius);
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    const Vec3& x = sim.particles.position_m[i];
    if (x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= hi.x && x.y <= hi.y && x.z <= hi.z)
      grid.add(x, sim.particles.radius_m[i]);
  }

  while (report.placed < report.requested) {
    const std::size_t size_class = next_size_class(ins);
    const double r = ins.sizes[size_class].radius_m;
    bool placed = false;
    for (int attempt = 0; attempt < kAttemptsPerParticle && !placed; ++attempt) {
      Vec3 x;
      if (!ins.region.sample_centre(rng, r, x)) break;
      if (grid.overlaps(x, r, max_radius) || touches_a_wall(sim, x, r)) continue;
      NewParticle p;
      p.position_m = x;
      p.velocity_m_per_s = ins.velocity_m_per_s;
      p.radius_m = r;
      p.density_kg_per_m3 = ins.density_kg_per_m3;
      p.material = ins.material;
      p.region = ins.tag;
      p.temperature_K = ins.temperature.at(x);
      sim.add_particle(p);
      grid.add(x, r);
      placed = true;
    }
    if (!placed) break;  // no room left this attempt
    ++report.placed;
    ++ins.inserted;
    ++ins.inserted_per_class[size_class];
  }
  // All-at-once insertion ends after its one attempt, full region or not; a dynamic
  // one when it has placed everything, or after several attempts in a row found no
  // room (the particles below are not making way).
  constexpr int kMaxFruitlessAttempts = 5;
  ins.fruitless_attempts = report.placed == 0 ? ins.fruitless_attempts + 1 : 0;
  if (ins.inserted >= ins.target_count || ins.rate_per_s <= 0.0 || ins.fruitless_attempts >= kMaxFruitlessAttempts)
    ins.finished = true;
  return report;
}

}  // namespace regodem
