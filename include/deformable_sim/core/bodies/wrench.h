// Spreading a wrench (a force and a torque about a point) over a group of nodes so that the group's
// net force and net torque equal it exactly.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace deformable_sim::core {

/// Nodal forces f_i on the nodes at `positions` with weights w_i > 0 (e.g. lumped masses) whose
/// sum is `force` and whose moment about `point` is `torque`:
///   c = Σ w_i r_i / Σ w_i,  τ' = τ + (p − c) × F,  J = Σ w_i (|r_i − c|² I − (r_i − c)(r_i − c)ᵀ),
///   f_i = w_i F / Σ w + w_i (J⁺ τ') × (r_i − c).
/// J is singular for one node or nodes on a line: a torque component they cannot carry (about the
/// line) throws std::invalid_argument rather than being dropped. `forces` is resized to match.
void distributeWrench(const std::vector<Eigen::Vector3d>& positions,
                      const std::vector<double>& weights, const Eigen::Vector3d& force,
                      const Eigen::Vector3d& torque, const Eigen::Vector3d& point,
                      std::vector<Eigen::Vector3d>& forces);

}  // namespace deformable_sim::core
