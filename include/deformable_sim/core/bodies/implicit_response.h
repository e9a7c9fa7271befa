// How a finite-element body answers impulses at its nodes within its last step: the columns of
// A^-1, with A = (1 + h a) M + (h b + h^2) K' the matrix of the step's last solve, for the nodes
// that contact touches, each solved when first asked for. With them contact between bodies is
// resolved with the step's own operator: an impulse on a node moves the whole body as the
// implicit step would have. A node's lumped mass alone misses the dt^2 K that ties it to its
// neighbours, a hundred times its mass for a soft cube at 0.01 s, and a correction made with it
// compresses the layer of elements it touches instead of carrying the body.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/bodies/finite_element_body.h"

namespace deformable_sim::core {

class ImplicitResponse {
 public:
  explicit ImplicitResponse(int num_nodes) : slot_of_(num_nodes, -1) {}

  /// A new step of `body`: forgets the columns of the last one (keeps their storage).
  void begin(FiniteElementBody& body);
  /// The velocity change of node j per unit impulse at node i (zero where either is held).
  Eigen::Matrix3d block(int j, int i);
  /// dv += the body's answer to `impulse` at node i: A^-1 e_i impulse.
  void add(int i, const Eigen::Vector3d& impulse, Eigen::VectorXd& dv);
  /// Linear solves taken since begin(): three for each node asked about.
  int solves() const { return solves_; }

 private:
  /// The first of node i's three columns, solved on first use (an empty one: a held node).
  int slot(int i);

  FiniteElementBody* body_ = nullptr;
  std::vector<int> slot_of_;              ///< per node, its slot; -1: not solved in this step
  std::vector<int> used_;                 ///< nodes with a slot in this step
  std::vector<Eigen::VectorXd> columns_;  ///< three per slot; grows, never shrinks
  Eigen::VectorXd unit_;
  int slots_ = 0, solves_ = 0;
};

}  // namespace deformable_sim::core
