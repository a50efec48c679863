#pragma once
// A parametric auger (a drill with helical flutes) as a triangle mesh, in its own
// frame: axis +z, tip down with its apex at z = 0, the top at z = length, centred on
// the z axis. Place it in a scene with a MeshTransform.
//
// Construction: a union of closed, outward-wound shells that overlap, not one
// boolean-merged surface (docs/auger.md):
//  * the core: a regular N-gon prism of the core diameter (N = segments_per_turn,
//    vertices on the circle, the first at angle 0), flat on top, and at the bottom flat
//    or a cone (the N-gon pyramid) of the given apex angle, height r_core / tan(angle/2);
//  * one blade per flute: the helical sweep of the rectangle [r_root, r_outer] x
//    [0, flute_thickness] (radius x axial) from the top of the tip, where the core
//    reaches full radius, until the blade's top face reaches z = length. It ends in two
//    flat radial faces. r_root = kBladeRootFraction x r_core, inside the core (inside
//    the N-gon's inscribed circle, as N >= 16), so blade and core overlap with no gap.
//    Flute k starts at angle 2 pi k / flutes.
// Every shell is watertight (each edge in exactly two of its triangles, once each
// way); the shells share no vertex, so they are the mesh's connected components. The
// union's inside is winding_number >= 1/2 (geometry/mesh_inside.hpp).
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace regodem {

enum class AugerTip { flat, cone };
/// right: the flutes climb counterclockwise seen from above (+z), like a right-hand
/// screw thread; left: the mirror image.
enum class FluteHand { right, left };

/// The blade's inner radius as a fraction of the core radius (see above).
inline constexpr double kBladeRootFraction = 0.95;

struct AugerSpec {
  double outer_diameter_m = 0.0;    // over the flutes
  double core_diameter_m = 0.0;     // the shaft the flutes wind around
  double pitch_m = 0.0;             // axial advance of one flute per turn
  int flutes = 1;                   // number of helical blades, evenly spaced in angle
  double flute_thickness_m = 0.0;   // axial thickness of each blade
  double length_m = 0.0;            // tip apex to top
  AugerTip tip = AugerTip::flat;
  double tip_angle_rad = 2.0594885173533086;  // cone apex angle (full), 118 degrees; cone only
  int segments_per_turn = 64;       // facets around the core and per blade turn
  FluteHand hand = FluteHand::right;

  /// Throws InputError with a message naming the parameter when a length is not
  /// finite and positive, the core is not thinner than the outer diameter, the blades
  /// would touch (flute_thickness >= pitch / flutes), the tip angle is outside (0, 180)
  /// degrees, the tip and one blade thickness do not fit in the length, flutes < 1,
  /// segments_per_turn outside [16, 4096], or the mesh would exceed 2e7 triangles.
  void validate() const;
  /// Height of the conical tip (0 for a flat one), where the core reaches full radius.
  double tip_height_m() const;
};

/// The shells separately: the core, then one blade per flute (flute k at index k).
struct AugerShells {
  TriangleMesh core;
  std::vector<TriangleMesh> blades;
};

/// Validates the spec, then builds the shells (source "auger core", "auger flute k").
AugerShells make_auger_shells(const AugerSpec& spec);
/// All shells in one mesh (core first, then the flutes in order; source "auger").
TriangleMesh make_auger(const AugerSpec& spec);

}  // namespace regodem
