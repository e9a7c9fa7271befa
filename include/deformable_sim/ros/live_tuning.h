// Live tuning through dynamic_reconfigure: material, damping, solver limits and the rate change
// between steps. Impossible values are refused (a warning, the parameter keeps its value), never
// clamped to something the user did not ask for.
#pragma once

#include <dynamic_reconfigure/server.h>

#include <functional>
#include <memory>
#include <string>

#include "deformable_sim/SimConfig.h"
#include "deformable_sim/core/session/live_settings.h"

namespace deformable_sim::ros_layer {

class LiveTuning {
 public:
  /// Applies a command as the node records it; throws core::CommandError when refused.
  using Apply = std::function<int(const core::SessionCommand&)>;
  using Refuse = std::function<void(const std::string& reason)>;

  /// Starts from the scene's values (of its first body) at `rate` Hz; `on_rate` hears of a new
  /// rate once it is in effect.
  LiveTuning(const ros::NodeHandle& private_node, const core::Session& session, double rate,
             int substeps, Apply apply, Refuse refuse, std::function<void(double)> on_rate);

  /// After a reset to the scene's values: applies again what had been tuned.
  void reapply();

 private:
  void onReconfigure(SimConfig& config);

  const core::Session& session_;
  int substeps_;
  Apply apply_;
  Refuse refuse_;
  std::function<void(double)> on_rate_;
  core::LiveSettings applied_;  ///< what is in effect
  core::LiveSettings scene_;    ///< the scene's own values
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<SimConfig>> server_;
};

}  // namespace deformable_sim::ros_layer
