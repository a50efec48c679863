#include "geometry/mesh_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace regodem {
namespace {

std::array<std::uint32_t, 2> feature_vertices(const TriangleMesh& mesh, std::uint32_t t, const TriangleClosestPoint& q) {
  const auto& tri = mesh.triangles[t];
  const auto k = static_cast<std::size_t>(q.local);
  switch (q.feature) {
    case MeshFeature::edge: {
      const std::uint32_t u = tri[k];
      const std::uint32_t v = tri[(k + 1) % 3];
      return {std::min(u, v), std::max(u, v)};
    }
    case MeshFeature::vertex:
      return {tri[k], tri[k]};
    case MeshFeature::face:
      break;
  }
  return {tri[0], tri[1]};
}

bool has_vertex(const std::array<std::uint32_t, 3>& tri, std::uint32_t v) {
  return tri[0] == v || tri[1] == v || tri[2] == v;
}

/// Whether triangle `tri` contains the edge or vertex of contact c.
bool contains_feature(const std::array<std::uint32_t, 3>& tri, const MeshContact& c) {
  return has_vertex(tri, c.vertices[0]) && has_vertex(tri, c.vertices[1]);
}

bool same_feature(const MeshContact& a, const MeshContact& b) {
  return a.feature == b.feature && a.feature != MeshFeature::face && a.vertices == b.vertices;
}

}  // namespace

// ---------------------------------------------------------------------------------
TriangleClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Region by region, as in Ericson 5.1.5: the three vertex regions, the three edge
  // regions, then the face. d1..d6 are projections on the edges ab and ac of the
  // vectors from each corner to p; va, vb, vc are the barycentric numerators.
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = dot(ab, ap);
  const double d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, MeshFeature::vertex, 0};

  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp);
  const double d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, MeshFeature::vertex, 1};

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, MeshFeature::edge, 0};
  }

  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp);
  const double d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, MeshFeature::vertex, 2};

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, MeshFeature::edge, 2};
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), MeshFeature::edge, 1};
  }

  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom;
  const double w = vc * denom;
  return {a + v * ab + w * ac, MeshFeature::face, 0};
}

// ---------------------------------------------------------------------------------
void mesh_contacts_among(const TriangleMesh& mesh, const std::vector<std::uint32_t>& candidates,
                         const Vec3& centre_m, double radius_m, std::vector<MeshContact>& out,
                         std::vector<MeshContact>& collected) {
  out.clear();
  collected.clear();
  if (!(radius_m > 0.0)) return;

  // 1. The closest point of each candidate triangle, if inside the sphere.
  for (const std::uint32_t t : candidates) {
    const TriangleClosestPoint q =
        closest_point_on_triangle(centre_m, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
    const Vec3 offset = q.point_m - centre_m;
    const double d = norm(offset);
    if (!(d < radius_m)) continue;
    MeshContact c;
    c.distance_m = d;
    c.normal = d > 0.0 ? offset / d : -mesh.normal(t);
    c.contact_point_m = q.point_m;
    c.triangle = t;
    c.feature = q.feature;
    c.vertices = feature_vertices(mesh, t, q);
    collected.push_back(c);
  }
  if (collected.empty()) return;

  const double scale = std::max({std::abs(centre_m.x), std::abs(centre_m.y), std::abs(centre_m.z)}) + radius_m;
  const double tol = 1e-9 * radius_m + 64.0 * std::numeric_limits<double>::epsilon() * scale;

  // 2. Drop an edge or vertex contact when a triangle that contains the feature has its
  //    closest point elsewhere (more than tol from this one). That triangle contains
  //    this contact point, so its own closest point, being different, is strictly
  //    closer: this one is no local minimum of the distance to the surface. Comparing
  //    points rather than distances matters: a centre a small offset delta off a shared
  //    edge changes the distances only by about delta^2 / d, the points by delta.
  const auto apart = [tol](const MeshContact& a, const MeshContact& b) {
    return norm(a.contact_point_m - b.contact_point_m) > tol;
  };
  for (const MeshContact& c : collected) {
    const bool dominated =
        c.feature != MeshFeature::face &&
        std::any_of(collected.begin(), collected.end(), [&](const MeshContact& other) {
          return other.triangle != c.triangle && contains_feature(mesh.triangles[other.triangle], c) &&
                 apart(other, c);
        });
    if (!dominated) out.push_back(c);
  }

  // 3. Merge contacts at the same point, or on the same edge or vertex. The one kept
  //    from each group is the best placed: a face before an edge before a vertex (a
  //    face's point within tol of an edge point is the exact foot of the normal, so its
  //    normal is the plane's), then the shorter distance, then the lower triangle.
  const auto rank = [](const MeshContact& c) { return static_cast<int>(c.feature); };
  std::sort(out.begin(), out.end(), [&](const MeshContact& a, const MeshContact& b) {
    return std::tuple(rank(a), a.distance_m, a.triangle) < std::tuple(rank(b), b.distance_m, b.triangle);
  });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const bool duplicate = std::any_of(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(kept),
                                       [&](const MeshContact& k) { return same_feature(k, out[i]) || !apart(k, out[i]); });
    if (!duplicate) out[kept++] = out[i];
  }
  out.resize(kept);

  // 4. Output order: by triangle (one contact per triangle at most).
  std::sort(out.begin(), out.end(), [](const MeshContact& a, const MeshContact& b) { return a.triangle < b.triangle; });
}

// ---------------------------------------------------------------------------------
void mesh_contacts(const TriangleMesh& mesh, const MeshGrid& grid, const Vec3& centre_m, double radius_m,
                   std::vector<MeshContact>& out, MeshContactScratch& scratch) {
  grid.candidates(centre_m, radius_m, scratch.candidates);
  mesh_contacts_among(mesh, scratch.candidates, centre_m, radius_m, out, scratch.collected);
}

void mesh_contacts(const TriangleMesh& mesh, const MeshGrid& grid, const Vec3& centre_m, double radius_m,
                   std::vector<MeshContact>& out) {
  MeshContactScratch scratch;
  mesh_contacts(mesh, grid, centre_m, radius_m, out, scratch);
}

}  // namespace regodem
