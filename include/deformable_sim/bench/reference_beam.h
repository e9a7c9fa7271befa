// The cantilever of ../shared/reference (its README, section 1) on one of the shipped meshes:
// x in [0, 1] m, a 0.1 m square section, E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3, clamped on the
// face x = 0 (fix_nodes.txt), loaded on the face x = 1 by the consistent nodal shares of a uniform
// traction (tip_load_unit.csv), measured by the area-weighted mean displacement of that face.
// Or the same beam given as a surface, its body the grid of cubes it encloses
// (core/surface_bodies/voxelization.h): clamped at the grid's nodes on x = 0, loaded and measured
// equally at its nodes on x = 1.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::bench {

/// The reference material: E = 1e6 Pa, nu = 0.3, rho = 1000 kg/m^3.
core::LinearElasticMaterial referenceMaterial();

/// Bending stiffness E I of the section, N m^2 (I = b h^3 / 12 = 8.3333e-6 m^4).
double referenceBendingStiffness();

/// Tip load P = alpha E I / L^2 of the large-deflection case at load level alpha, N.
double largeDeflectionLoad(double alpha);

class ReferenceBeam {
 public:
  /// Reads meshes/<mesh_id>/<mesh_id>.msh, fix_nodes.txt and tip_load_unit.csv under
  /// `reference_dir`. Throws std::runtime_error naming the file that is missing or wrong.
  ReferenceBeam(const std::string& reference_dir, const std::string& mesh_id);

  /// The beam's surface turned `turn_degrees` about its long axis, voxelized with `cells` cells
  /// along it; its id is "surface<turn_degrees>_c<cells>" ("surface30_c24").
  static ReferenceBeam fromSurface(double turn_degrees, int cells);
  /// The (turn, cells) of a surface beam's id, or false for a shipped mesh's id.
  static bool parseSurfaceId(const std::string& id, double* turn_degrees, int* cells);

  const std::string& id() const { return id_; }
  const core::Mesh& mesh() const { return mesh_; }

  /// A body on this mesh with the reference material, its clamp fixed.
  core::FiniteElementBody makeBeamBody(const core::BodyEffects& effects,
                                       const core::SolverSettings& solver) const;

  /// Sets the body's external forces to a total tip load of `load_n` newtons in -z, spread over
  /// the tip nodes by the reference's consistent shares (nodal force = -P weight).
  void applyTipLoad(core::Body& body, double load_n) const;

  /// Area-weighted mean displacement of the tip face (the reference's tip_*_mean_area), m.
  Eigen::Vector3d tipDisplacement(const core::Body& body) const;

 private:
  ReferenceBeam() = default;

  std::string id_;
  core::Mesh mesh_;
  std::vector<int> clamp_;  ///< node indices of the face x = 0
  std::vector<int> tip_;    ///< node indices of the face x = L
  std::vector<double> tip_weights_;
};

}  // namespace deformable_sim::bench
