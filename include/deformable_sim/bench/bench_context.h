// What every case of one bench run shares: the reference folder, its results table, and each
// mesh read once.
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "deformable_sim/bench/reference_beam.h"
#include "deformable_sim/bench/reference_results.h"

namespace deformable_sim::bench {

class BenchContext {
 public:
  /// Reads `reference_dir`/results.csv. Throws std::runtime_error when it cannot.
  explicit BenchContext(const std::string& reference_dir);

  const std::string& referenceDir() const { return reference_dir_; }
  const ReferenceResults& results() const { return results_; }

  /// The beam on that mesh, read (or made from its surface: ReferenceBeam::fromSurface) on first
  /// use.
  const ReferenceBeam& beam(const std::string& mesh);

  /// Results of expensive reference runs of our own (converged trajectories), computed once per
  /// key by whoever needs them.
  std::map<std::string, std::vector<Eigen::Vector3d>>& ownReferences() { return own_references_; }

 private:
  std::string reference_dir_;
  ReferenceResults results_;
  std::map<std::string, std::unique_ptr<ReferenceBeam>> beams_;
  std::map<std::string, std::vector<Eigen::Vector3d>> own_references_;
};

}  // namespace deformable_sim::bench
