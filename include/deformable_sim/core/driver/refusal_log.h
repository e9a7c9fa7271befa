// Refused commands: every one is counted and the last reason kept; warnings are throttled per
// topic (at most one a second each) and say how many were refused since the previous warning.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace deformable_sim::core {

class RefusalLog {
 public:
  explicit RefusalLog(double period_s = 1.0) : period_s_(period_s) {}

  /// Records a refusal on `topic` at `now` (s, a wall clock); returns the warning to print now,
  /// or "" while throttled.
  std::string refuse(const std::string& topic, const std::string& reason, double now);

  std::uint64_t count() const { return count_; }
  const std::string& last() const { return last_; }

 private:
  struct TopicLog {
    double last_warning = 0.0;  ///< s
    bool warned = false;
    int silenced = 0;
  };
  double period_s_;
  std::uint64_t count_ = 0;
  std::string last_;
  std::map<std::string, TopicLog> topics_;
};

}  // namespace deformable_sim::core
