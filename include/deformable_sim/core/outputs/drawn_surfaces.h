// The bodies' surfaces as a viewer draws them: three corners per triangle, where the body is now,
// each with the strain it is coloured by. The node's ~mesh and the replay's output bag draw them.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/session/simulation.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"

namespace deformable_sim::core {

/// A body made from a surface is drawn with that surface, carried by its grid
/// (Simulation::embeddedSurface); any other with its mesh's boundary (extractSurface).
class DrawnSurfaces {
 public:
  explicit DrawnSurfaces(const Simulation& simulation);

  /// Places the corners of `body`, the `index`th of the bodies, where it is now, and their
  /// strains (nodalStrain, weighted as the corner's position is) when the body has
  /// stress_colouring. What corners() and strains() give until the next call.
  void update(const Body& body, int index);
  /// m, three per triangle, counter-clockwise seen from outside.
  const std::vector<Eigen::Vector3d>& corners() const { return corners_; }
  /// One per corner; empty for a body without stress_colouring.
  const std::vector<double>& strains() const { return strains_; }

 private:
  void updateEmbedded(EmbeddedSurface& surface, const Body& body, bool strain);

  std::vector<std::vector<Triangle>> boundaries_;         ///< per body, empty if embedded
  std::vector<std::optional<EmbeddedSurface>> embedded_;  ///< per body
  std::vector<double> nodal_strain_;
  std::vector<Eigen::Vector3d> corners_;
  std::vector<double> strains_;
};

}  // namespace deformable_sim::core
