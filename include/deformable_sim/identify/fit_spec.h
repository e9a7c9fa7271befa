// What a material fit asks for (deformable_sim_identify's YAML): the recorded bag, the scene to
// start from, the parameters to identify within bounds, what was measured and where to write the
// fitted scene. Paths are resolved against the fit file's directory.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace deformable_sim::identify {

/// A fit file that cannot be used; what() is "FILE: KEY: problem" (or "FILE:LINE: KEY: problem").
class FitSpecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One parameter to identify: a live-tuning name (youngs_modulus, poisson_ratio, density,
/// damping_mass, damping_stiffness) or friction, within [min, max].
struct FitParameter {
  std::string body;
  std::string parameter;
  double min = 0.0;
  double max = 0.0;
  std::string key;  ///< "fit[1]", for messages
  /// A time offset's observation (parameter "time_offset", no body); -1: a scene parameter.
  int observation = -1;
};

/// What was measured: a tracked frame on a material point, or a force/torque sensor.
struct ObservationSpec {
  enum class Kind { kFrame, kWrench };
  enum class Source { kReactions, kGrasp, kLink };  ///< what a wrench is compared with
  Kind kind = Kind::kFrame;
  std::string topic;  ///< tf: the child frame; wrench: the WrenchStamped topic
  std::string body;   ///< tf: the body the point is on; wrench: reactions' body
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  ///< m, rest position (tf)
  Source source = Source::kReactions;
  std::string name;           ///< grasp or link name
  double sigma = 0.0;         ///< m (tf) or N (wrench)
  double torque_sigma = 0.0;  ///< N m (wrench)
  std::string key;            ///< "observations[0]", for messages
  /// s: the sensor's clock minus the node's (a sample stamped t was taken at t - offset); fixed,
  /// or the first guess of one fitted within [offset_min, offset_max].
  double time_offset = 0.0;
  bool fit_time_offset = false;
  double offset_min = 0.0, offset_max = 0.0;
  /// Huber's loss from this many sigmas on (a sample's weighted residual beyond it counts
  /// linearly: outliers pull less); 0: plain least squares.
  double huber = 0.0;
};

struct FitSpec {
  std::string bag;    ///< resolved path
  std::string scene;  ///< resolved path, or empty: the bag's ~scene
  std::vector<FitParameter> fit;
  std::vector<ObservationSpec> observations;
  std::string out;  ///< resolved path
};

/// The parameter names a fit accepts.
const std::vector<std::string>& fitParameterNames();

/// Parses fit YAML text; `source` names it in messages, relative paths are resolved against
/// `base_directory`. Throws FitSpecError naming the key: missing or unknown keys, wrong types,
/// min >= max, an unknown parameter, sigma <= 0.
FitSpec parseFitSpec(const std::string& yaml_text, const std::string& source,
                     const std::string& base_directory);
/// Reads and parses a fit file.
FitSpec readFitSpec(const std::string& path);

}  // namespace deformable_sim::identify
