// The narrow phase of contact between bodies: does a node end a step behind a surface triangle of
// another body (or of its own), so that it must be put back? Tested with the positions at the
// step's start and end, so that a node that passed through a thin part within the step is found
// by the side it came from.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// Where a node and a triangle move within a step: start and end positions.
struct SweptNode {
  Eigen::Vector3d start, end;
};
struct SweptTriangle {
  Eigen::Vector3d start[3], end[3];  ///< corners counter-clockwise seen from outside
};

struct NodeTriangleHit {
  /// How far the node is behind the triangle's plane at the end, m (negative: in front of it).
  double depth = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   ///< the triangle's outward unit normal
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  ///< barycentric, of the node's foot point
  /// It was in front of the plane at the start: it came through this triangle. Such a hit tells
  /// the way back better than any triangle the node merely ended near.
  bool crossed = false;
};

/// A hit when the node ends behind the triangle's plane, or in front of it by less than `skin`
/// (m: about to touch), with its foot point on the triangle, and either was in front of the plane
/// (within `skin`) at the start of the step (it crossed it) or is behind it by at most `shallow`
/// (m: it was touching and sank in a little). A triangle of no area is never hit.
bool nodeHitsTriangle(const SweptNode& node, const SweptTriangle& triangle, double skin,
                      double shallow, NodeTriangleHit* hit);

}  // namespace deformable_sim::core
