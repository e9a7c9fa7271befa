// Plasticity of a warped-stiffness body, after OpenTissue's model (Müller and Gross 2004): each
// element keeps a plastic strain eps_p in its rotated (rest) frame. The elastic strain is the
// corotated total strain minus eps_p; where its norm exceeds `yield`, eps_p creeps towards it at
// rate `creep`, and its norm is capped at `max_strain`. The body then relaxes towards the
// plastically deformed shape through the plastic forces f_i = R V (lambda tr(eps_p) I +
// 2 mu eps_p) grad N_i, which the step adds to its loads (explicitly, once per step).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/elements/corotational_elasticity.h"
#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

struct PlasticitySettings {
  double yield = 0.01;      ///< elastic strain norm (Frobenius) above which the element flows, -
  double creep = 10.0;      ///< rate at which plastic strain absorbs the excess, 1/s
  double max_strain = 0.2;  ///< cap on the plastic strain norm, -
};

/// Throws std::invalid_argument naming the setting that is out of range (yield >= 0, creep >= 0,
/// max_strain > 0, all finite).
void validate(const PlasticitySettings& settings);

class Plasticity {
 public:
  Plasticity(const Mesh& mesh, const PlasticitySettings& settings);

  /// Advances the plastic strains by dt from positions x and the element rotations of the last
  /// elasticity update, and writes the plastic forces (3n, N) into `forces`. Allocates nothing.
  void step(const Mesh& mesh, const CorotationalElasticity& elasticity, const Eigen::VectorXd& x,
            double dt, Eigen::VectorXd& forces);

  /// Per element (tetrahedra first, then cells), symmetric, in the element's rotated frame.
  const std::vector<Eigen::Matrix3d>& plasticStrains() const { return plastic_strains_; }
  /// Elements that flowed in the last step.
  int flowingElements() const { return flowing_; }

 private:
  /// Updates element e's plastic strain from its deformation gradient; returns the plastic
  /// stress (Pa) whose forces the step adds.
  Eigen::Matrix3d flow(int e, const Eigen::Matrix3d& f, const Eigen::Matrix3d& r, double lambda,
                       double mu, double dt);

  PlasticitySettings settings_;
  std::vector<Eigen::Matrix3d> plastic_strains_;
  int flowing_ = 0;
};

}  // namespace deformable_sim::core
