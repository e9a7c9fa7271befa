// The error of a scene spec that cannot be built: a selection that selects no node, a load with
// nothing to act on, a bad material. It keeps the key of the offending entry as a scene file
// spells it, so that whoever read the file can add where the entry stands there.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace deformable_sim::core {

class SpecError : public std::invalid_argument {
 public:
  /// what() is "key: message".
  SpecError(std::string key, const std::string& message)
      : std::invalid_argument(key + ": " + message), key_(std::move(key)) {}

  /// "bodies[0].groups.tip", "bodies[0].loads[1]", "dt".
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

}  // namespace deformable_sim::core
