#include "deformable_sim/identify/observed_series.h"

#include <algorithm>
#include <cmath>

namespace deformable_sim::identify {

Eigen::VectorXd SimulatedSeries::at(double time) const {
  const long last = static_cast<long>(steps.size()) - 1;
  const double k = std::clamp(time / dt, 0.0, static_cast<double>(last));
  const long before = std::min(static_cast<long>(std::floor(k)), std::max(last - 1, 0L));
  if (last <= 0) return steps.front();
  const double fraction = k - static_cast<double>(before);
  return (1.0 - fraction) * steps[before] + fraction * steps[before + 1];
}

}  // namespace deformable_sim::identify
