#pragma once
// The one walk over a particle's listed contacts (issue 18, "one contact pass"): its
// particle pairs, its analytic walls and its mesh touches, each handed with its geometry
// to what the caller does with it. The force pass, the static bed's frozen network, the
// snapshots' contact counts and the largest overlap all walk the lists through it, so "in
// contact" means one thing everywhere: two spheres overlap, or a wall point is nearer than
// the radius (a mesh's touches counted once per face, edge or vertex, MeshTouchFinder).
#include <cstdint>
#include <vector>

#include "contact/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "geometry/mesh_contact.hpp"
#include "geometry/wall_set.hpp"

namespace regodem {

/// One particle–wall contact, analytic or mesh.
struct WallTouch {
  double distance_m = 0.0;  // from the sphere's centre to the contact point (< radius)
  Vec3 normal;              // unit, from the centre towards the wall
  Vec3 contact_point_m;
  MaterialIndex material = 0;
  std::uint32_t body = 0;
  std::uint32_t segment = 0;  // the body's thermal segment at the point (0 for an analytic wall)
  bool on_mesh = false;       // entry indexes the list's mesh entries, else its analytic wall entries
  std::uint32_t entry = 0;    // the list entry, whose tangential spring the contact carries
};

/// Either side of the walk may ignore what it is told.
struct IgnoreContact {
  template <class... Args>
  void operator()(Args&&...) const {}
};

class ContactWalk {
 public:
  /// Views of the lists and positions as they are: the walk holds no copies.
  ContactWalk(const ParticleStore& particles, const NeighborList& lists, const WallSet& walls)
      : x_(particles.position_m.data()),
        radius_(particles.radius_m.data()),
        offset_(lists.offset.data()),
        partner_(lists.partner.data()),
        lists_(lists),
        walls_(walls) {}

  /// The owners the lists were built for (particles appended since are in none yet).
  std::size_t owners() const { return lists_.offset.empty() ? 0 : lists_.offset.size() - 1; }

  /// One listed pair of particle i at entry k: the spheres are in contact unless apart().
  struct ListedPair {
    std::uint32_t j;
    Vec3 d_m;  // x_j - x_i
    double distance2_m2;
    double radius_j_m;
    double radius_sum_m;
    // Written as a test for "apart" so that a NaN distance (a blow-up) counts as a contact,
    // whose force then carries the NaN to the blow-up check.
    bool apart() const { return distance2_m2 >= radius_sum_m * radius_sum_m; }
  };
  std::uint32_t pairs_begin(std::uint32_t i) const { return offset_[i]; }
  std::uint32_t pairs_end(std::uint32_t i) const { return offset_[i + 1]; }
  [[gnu::always_inline]] ListedPair listed_pair(const Vec3& xi, double ri, std::uint32_t k) const {
    ListedPair p;
    p.j = partner_[k];
    p.d_m = x_[p.j] - xi;
    p.radius_j_m = radius_[p.j];
    p.radius_sum_m = ri + p.radius_j_m;
    p.distance2_m2 = norm2(p.d_m);
    return p;
  }

  /// Particle i's listed pairs in contact: touch(entry, pair). The force pass runs the
  /// same loop itself over listed_pair (a loop of its own keeps its sums in registers).
  template <class Touch>
  [[gnu::always_inline]] void pairs(std::uint32_t i, Touch&& touch) const {
    const Vec3 xi = x_[i];
    const double ri = radius_[i];
    for (std::uint32_t k = pairs_begin(i), end = pairs_end(i); k < end; ++k) {
      const ListedPair p = listed_pair(xi, ri, k);
      if (!p.apart()) touch(k, p);
    }
  }

  /// Particle i's wall contacts: touch(WallTouch) for each, the analytic walls first, then
  /// each mesh in list order. apart(entry, wall, proximity) for an analytic wall entry not
  /// touching; mesh_run(mesh, first_entry, count, touches) once per mesh before its touches
  /// (the force pass carries its springs there).
  template <class Touch, class Apart = IgnoreContact, class MeshRun = IgnoreContact>
  [[gnu::always_inline]] void walls(std::uint32_t i, MeshTouchFinder& finder, std::vector<MeshTouch>& touches,
                                    Touch&& touch, Apart&& apart = {}, MeshRun&& mesh_run = {}) const {
    const Vec3 xi = x_[i];
    const double ri = radius_[i];
    const std::uint32_t* __restrict wall_primitive = lists_.wall_primitive.data();
    const WallPrimitive* __restrict primitives = walls_.primitives.data();
    const std::uint32_t end = lists_.wall_offset[i + 1];
    for (std::uint32_t k = lists_.wall_offset[i]; k < end; ++k) {
      const WallPrimitive& wall = primitives[wall_primitive[k]];
      const WallProximity prox = closest_wall_point(wall, xi);
      if (!prox.candidate || prox.distance_m >= ri) {
        apart(k, wall, prox);
        continue;
      }
      touch(WallTouch{prox.distance_m, prox.normal, prox.contact_point_m, wall.material, wall.body, 0u, false, k});
    }
    // Most particles touch no mesh: the test saves the call (1 % of the force pass in a profile).
    if (lists_.mesh_offset[i] == lists_.mesh_offset[i + 1]) return;
    for_each_mesh_run(lists_, i, [&](std::uint32_t wall_index, std::uint32_t g, std::uint32_t g_end) {
      const MeshWall& mesh = walls_.meshes[wall_index];
      finder.find(mesh, walls_.bodies[mesh.body].pose, lists_.mesh_triangle.data() + g, g_end - g, xi, ri, touches);
      mesh_run(mesh, g, g_end - g, touches);
      const std::uint16_t* segment = mesh.triangle_segment.empty() ? nullptr : mesh.triangle_segment.data();
      for (const MeshTouch& t : touches) {
        const std::uint32_t entry = g + t.entry;
        touch(WallTouch{t.distance_m, t.normal, t.contact_point_m, mesh.material, mesh.body,
                        segment ? segment[lists_.mesh_triangle[entry]] : 0u, true, entry});
      }
    });
  }

 private:
  const Vec3* __restrict x_;
  const double* __restrict radius_;
  const std::uint32_t* __restrict offset_;
  const std::uint32_t* __restrict partner_;
  const NeighborList& lists_;
  const WallSet& walls_;
};

}  // namespace regodem
