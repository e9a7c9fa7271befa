#include "deformable_sim/core/outputs/drawn_surfaces.h"

#include "deformable_sim/core/outputs/strain.h"

namespace deformable_sim::core {

DrawnSurfaces::DrawnSurfaces(const Simulation& simulation) {
  for (size_t b = 0; b < simulation.bodies().size(); ++b) {
    const EmbeddedSurface* embedded = simulation.embeddedSurface(static_cast<int>(b));
    embedded_.push_back(embedded ? std::optional<EmbeddedSurface>(*embedded) : std::nullopt);
    boundaries_.push_back(embedded ? std::vector<Triangle>{}
                                   : extractSurface(simulation.bodies()[b].mesh()));
  }
}

void DrawnSurfaces::update(const Body& body, int index) {
  const bool strain = body.settings().effects.stress_colouring;
  if (strain) nodalStrain(body, nodal_strain_);
  if (embedded_[index]) {
    updateEmbedded(*embedded_[index], body, strain);
    return;
  }
  const std::vector<Triangle>& boundary = boundaries_[index];
  corners_.resize(3 * boundary.size());
  strains_.resize(strain ? 3 * boundary.size() : 0);
  const Eigen::VectorXd& x = body.positions();
  for (size_t t = 0; t < boundary.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int node = boundary[t][k];
      corners_[3 * t + k] = x.segment<3>(3 * node);
      if (strain) strains_[3 * t + k] = nodal_strain_[node];
    }
  }
}

void DrawnSurfaces::updateEmbedded(EmbeddedSurface& surface, const Body& body, bool strain) {
  surface.update(body.positions());
  const std::vector<Eigen::Vector3i>& triangles = surface.triangles();
  corners_.resize(3 * triangles.size());
  strains_.resize(strain ? 3 * triangles.size() : 0);
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[t][k];
      corners_[3 * t + k] = surface.positions()[v];
      if (!strain) continue;
      const std::array<int, 8>& nodes = surface.nodes(v);
      double weighted = 0.0;
      for (int n = 0; n < 8; ++n) weighted += surface.weights(v)[n] * nodal_strain_[nodes[n]];
      strains_[3 * t + k] = weighted;
    }
  }
}

}  // namespace deformable_sim::core
