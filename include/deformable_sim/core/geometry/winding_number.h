// The generalized winding number of a triangle surface (Jacobson, Kavan and Sorkine-Hornung 2013,
// "Robust inside-outside segmentation using generalized winding numbers"): the signed solid angle
// the triangles subtend at a point, over 4 pi. 1 inside a closed, outward-facing surface, 0
// outside, and a smooth value in between across holes, so a threshold of 1/2 decides inside for
// the imperfect (open, self-intersecting) meshes of real parts. Far triangles are summed by
// groups as dipoles (Barill et al. 2018, "Fast winding numbers for soups and clouds", first
// order), near ones exactly.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "deformable_sim/core/geometry/triangle_mesh.h"

namespace deformable_sim::core {

/// The signed solid angle of triangle (a, b, c) seen from q, sr: positive when q sees it
/// counter-clockwise (behind an outward-facing triangle). Van Oosterom and Strackee 1983.
double solidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& q);

/// Every triangle's solid angle summed over 4 pi: the exact winding number, O(triangles).
double exactWindingNumber(const TriangleMesh& surface, const Eigen::Vector3d& q);

class WindingNumber {
 public:
  /// Builds the tree over `surface` (which must outlive this object). Allocates.
  explicit WindingNumber(const TriangleMesh& surface);

  /// The winding number at q: groups of triangles farther than kFarRatio times their radius by
  /// their dipole, the rest exactly. Allocates nothing.
  double at(const Eigen::Vector3d& q) const;

  /// At this distance over a group's radius the dipole's relative error (of the order of the
  /// ratio's inverse for a curved group, its square for a flat one) stays within the margin of a
  /// threshold at 1/2.
  static constexpr double kFarRatio = 3.0;

 private:
  struct Node {
    Eigen::Vector3d centre;       ///< area-weighted centroid of its triangles, m
    Eigen::Vector3d area_normal;  ///< sum of area x outward unit normal, m^2
    double radius = 0.0;          ///< of the ball about centre holding its triangles, m
    int first = 0, count = 0;     ///< leaf: order_[first, first + count)
    int left = -1, right = -1;    ///< inner: its children; leaf: -1
  };
  void build(int begin, int end);
  void summarize(Node& node, int begin, int end) const;

  const TriangleMesh& surface_;
  std::vector<Node> nodes_;
  std::vector<int> order_;                  ///< triangle indices, each leaf's a contiguous range
  std::vector<Eigen::Vector3d> centroids_;  ///< only while building
};

}  // namespace deformable_sim::core
