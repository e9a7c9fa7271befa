// What a simulation predicts for one observation at the current step: a tracked material point's
// position (3 values, m, world) or a sensor's wrench (6: force N then torque N m, in the
// sensor's frame about its origin).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "deformable_sim/core/outputs/contact_pairs.h"
#include "deformable_sim/core/session/session.h"
#include "deformable_sim/identify/fit_spec.h"
#include "deformable_sim/identify/material_point.h"

namespace deformable_sim::identify {

class ObservationModel {
 public:
  /// `sensor_frame`: the wrench's frame in the world (identity for the world frame). Throws
  /// FitSpecError naming the key: an unknown body, `at` outside the body.
  ObservationModel(const ObservationSpec& spec, const core::Simulation& simulation,
                   const Eigen::Isometry3d& sensor_frame = Eigen::Isometry3d::Identity());

  int size() const { return spec_.kind == ObservationSpec::Kind::kFrame ? 3 : 6; }
  const ObservationSpec& spec() const { return spec_; }
  /// The value now. A grasp not (yet) in effect reads zero.
  Eigen::VectorXd predict(const core::Session& session);

 private:
  core::Wrench wrench(const core::Session& session);

  ObservationSpec spec_;
  int body_ = -1;
  MaterialPoint point_;
  Eigen::Isometry3d sensor_frame_;
  std::vector<core::ContactPair> pairs_;  ///< reused between steps (link wrenches)
};

}  // namespace deformable_sim::identify
