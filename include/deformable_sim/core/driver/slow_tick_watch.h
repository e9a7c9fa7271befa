// Notices a driver that stays slower than real time: a node warns when its real-time factor has
// stayed under kSlowFactor for kPatience s of wall time, not at one slow tick.
#pragma once

namespace deformable_sim::core {

class SlowTickWatch {
 public:
  static constexpr double kSlowFactor = 0.9;
  static constexpr double kPatience = 5.0;  ///< s of wall time

  /// A tick at wall time `wall_s` with the real-time factor measured then; a paused tick (or one
  /// that did not step) starts the count again.
  void sample(double wall_s, double real_time_factor, bool stepping);
  /// Slower than kSlowFactor for at least kPatience s in a row.
  bool slow() const { return slow_; }
  /// Wall seconds it has been slow for (0 when it is not).
  double slowFor(double wall_s) const { return since_ < 0.0 ? 0.0 : wall_s - since_; }
  void clear();

 private:
  double since_ = -1.0;  ///< wall time the factor went under, -1: it is not under
  bool slow_ = false;
};

}  // namespace deformable_sim::core
