// Wrenches that lapse: a source's wrench is removed when its sender has been silent for longer
// than a timeout (a crashed teleoperation client must not push forever).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace deformable_sim::core {

class WrenchTimeouts {
 public:
  /// `timeout` s; 0: wrenches never lapse.
  explicit WrenchTimeouts(double timeout = 0.0) : timeout_(timeout) {}

  /// The source sent a wrench at `now` (s); a zero wrench (`clears`) forgets the source.
  void heard(const std::string& source, double now, bool clears) {
    if (clears) {
      heard_.erase(source);
    } else {
      heard_[source] = now;
    }
  }
  /// The sources silent for longer than the timeout at `now`; they are forgotten.
  std::vector<std::string> expire(double now) {
    std::vector<std::string> expired;
    if (timeout_ <= 0.0) return expired;
    for (auto it = heard_.begin(); it != heard_.end();) {
      if (now - it->second > timeout_) {
        expired.push_back(it->first);
        it = heard_.erase(it);
      } else {
        ++it;
      }
    }
    return expired;
  }
  void clear() { heard_.clear(); }

 private:
  double timeout_;
  std::map<std::string, double> heard_;  ///< source -> when last heard, s
};

}  // namespace deformable_sim::core
