#include "deformable_sim/core/driver/refusal_log.h"

namespace deformable_sim::core {

std::string RefusalLog::refuse(const std::string& topic, const std::string& reason, double now) {
  ++count_;
  last_ = topic + ": " + reason;
  TopicLog& log = topics_[topic];
  if (log.warned && now - log.last_warning < period_s_) {
    ++log.silenced;
    return "";
  }
  std::string warning = last_ + " (message dropped";
  if (log.silenced > 0) {
    warning += "; " + std::to_string(log.silenced) + " more dropped on " + topic +
               " since the last warning";
  }
  warning += ")";
  log.last_warning = now;
  log.warned = true;
  log.silenced = 0;
  return warning;
}

}  // namespace deformable_sim::core
