// How a finite-element body answers impulses at its nodes within its last step: the columns of
// A^-1, with A = (1 + h a) M + (h b + h^2) K' the matrix of the step's last solve, for the nodes
// that contact touches, each solved when first asked for. With them contact between bodies is
// resolved with the step's own operator: an impulse on a node moves the whole body as the
// implicit step would have. A node's lumped mass alone misses the dt^2 K that ties it to its
// neighbours, a hundred times its mass for a soft cube at 0.01 s, and a correction made with it
// compresses the layer of elements it touches instead of carrying the body.
//
// The columns are kept from step to step while the matrix they came from still stands for the
// body's: the same nodes held (in place and on planes), the same material and step length, and
// its elements turned on average by less than kStaleTurn since. A body resting in a pile then
// solves nothing at all after its first step in contact: only nodes that start touching cost
// their three solves. Kept columns answer as the body did a few steps ago, to within the turn;
// an answer of any A^-1 whose K' has the rigid translations in its null space keeps momentum
// exactly (1^T M A^-1 = 1^T / (1 + h a)), so contact keeps it too.
//
// Impulses are gathered node by node (addImpulse) while their velocity changes are kept only
// where contact looks, at the nodes with columns, through the columns' rows there (a dense block
// over those nodes, a third of a soft block's nodes for a block in a row of them): an impulse
// costs that block's width, not the body's. The whole body's change is made once, at the end.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/bodies/finite_element_body.h"

namespace deformable_sim::core {

class ImplicitResponse {
 public:
  explicit ImplicitResponse(const FiniteElementBody& body);

  /// A new step of `body`: keeps the columns of earlier steps if they still answer for its
  /// matrix (see above), else forgets them (keeping their storage).
  void begin(FiniteElementBody& body);
  /// The velocity change of node j per unit impulse at node i (zero where either is held).
  Eigen::Matrix3d block(int j, int i);
  /// Starts gathering impulses: none so far.
  void clearImpulses();
  /// Node i takes `impulse` (N s) within the step.
  void addImpulse(int i, const Eigen::Vector3d& impulse);
  /// The velocity change of node j from the impulses so far.
  Eigen::Vector3d velocityChange(int j) const;
  /// Sums the dense block's columns of a point on `count` nodes with `weights` once, for many
  /// addPointImpulse()s; returns its number. Forgotten by clearImpulses().
  int keepPoint(const int* nodes, const double* weights, int count);
  /// keepPoint() for a point that is the same from step to step (a surface's corner, numbered
  /// `id` >= 0 by the caller): its sum is kept while the columns are and no node starts touching,
  /// not only for the round.
  int keepCorner(int id, const int* nodes, const double* weights, int count);
  /// A point kept as the sum of kept points with `weights` (-1 if one went stale: a node started
  /// touching since).
  int keepSum(const int* points, const double* weights, int count);
  /// addImpulse(nodes[k], weights[k] impulse) for every k at the cost of one, through the sum
  /// kept (point = keepPoint()'s number for the same nodes and weights).
  void addPointImpulse(int point, const int* nodes, const double* weights, int count,
                       const Eigen::Vector3d& impulse);
  /// w = the point's velocity change per unit impulse there, from its kept sum: its rows at
  /// the point's nodes, weighed. False (w untouched) when a node started touching since.
  bool keptCompliance(int point, const int* nodes, const double* weights, int count,
                      Eigen::Matrix3d& w) const;
  /// dv = the velocity change of every node from the impulses so far, sum_i A^-1 e_i f_i.
  void velocityChanges(Eigen::VectorXd& dv) const;
  /// Linear solves taken since begin(): three for each node asked about for the first time
  /// since the columns were last forgotten.
  int solves() const { return solves_; }
  /// Nodes whose columns are kept.
  int kept() const { return slots_; }

  /// The root mean square of the elements' turns (rad) past which kept columns are solved again.
  static constexpr double kStaleTurn = 0.05;

 private:
  /// The first of node i's three columns, solved on first use (an empty one: a held node).
  int slot(int i);
  /// Room for one more kept point, covering the slots there are now; its number.
  int newPoint();
  /// Columns 3 point .. 3 point + 2 of `into` = the point's weighed sum of its nodes' columns of
  /// near_ (every node with a slot).
  void sumColumns(Eigen::MatrixXd& into, int point, const int* nodes, const double* weights,
                  int count) const;
  /// Whether the kept columns still answer for the body's matrix now.
  bool stillAnswers(const FiniteElementBody& body) const;
  /// What the columns about to be solved depend on: holds, version, rotations.
  void remember(const FiniteElementBody& body);
  void forget();
  /// Room in the dense block for `slots` nodes (grows it, keeping what it holds).
  void makeRoom(int slots);

  FiniteElementBody* body_ = nullptr;
  std::vector<int> slot_of_;              ///< per node, its slot; -1: no kept column
  std::vector<int> used_;                 ///< nodes with a slot
  std::vector<Eigen::VectorXd> columns_;  ///< three per slot; grows, never shrinks
  Eigen::VectorXd unit_;
  int slots_ = 0, solves_ = 0;
  /// The columns' rows at the nodes with slots: 3x3 block (t, s) is the velocity change of
  /// slot t's node per unit impulse at slot s's. Room for capacity_ slots.
  Eigen::MatrixXd near_;
  int capacity_ = 0;
  /// Per kept point, its three summed columns of near_ and how many slots they cover.
  Eigen::MatrixXd points_;
  std::vector<int> point_slots_;
  int kept_points_ = 0;
  /// The same for kept corners, numbered from kCornerHandle; and each corner's place by its id.
  static constexpr int kCornerHandle = 1 << 24;
  Eigen::MatrixXd corner_sums_;
  std::vector<int> corner_slots_, corner_of_id_, corner_ids_;
  int corners_kept_ = 0;
  /// A kept point's or corner's summed columns, over the slots there are now.
  auto pointBlock(int handle) const {
    return handle >= kCornerHandle
               ? corner_sums_.block(0, 3 * (handle - kCornerHandle), 3 * slots_, 3)
               : points_.block(0, 3 * handle, 3 * slots_, 3);
  }
  int pointSlots(int handle) const {
    return handle >= kCornerHandle ? corner_slots_[handle - kCornerHandle] : point_slots_[handle];
  }
  Eigen::VectorXd impulses_;      ///< per slot, the impulse gathered (3 each)
  Eigen::VectorXd near_changes_;  ///< per slot, its node's velocity change (3 each)
  bool has_impulses_ = false;
  // What the kept columns were solved for.
  bool remembered_ = false;
  std::vector<char> held_;              ///< per node, held in place
  std::vector<PlaneHold> planes_;       ///< room for every node, reserved once
  std::vector<Eigen::Matrix3d> turns_;  ///< per element, its rotation
  int matrix_version_ = -1;
};

}  // namespace deformable_sim::core
