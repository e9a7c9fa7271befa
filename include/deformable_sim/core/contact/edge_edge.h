// The narrow phase for edges of two surfaces that cross: two bars laid across each other, a
// cube's edge pressed across another's, meet where neither has a node, so nodes against
// triangles (core/contact/node_triangle.h) never see them. Two edges meet when the points of their
// lines nearest to each other lie inside both edges, closer than a skin or past each other, along
// the common normal of the two edges turned out of the second edge's body.
#pragma once

#include <Eigen/Core>

namespace deformable_sim::core {

/// Where an edge's two ends move within a step: start and end positions.
struct SweptEdge {
  Eigen::Vector3d start[2], end[2];
};

struct EdgeEdgeHit {
  /// How far the first edge's point is behind the second's along `normal` at the end, m
  /// (negative: still in front, within the skin).
  double depth = 0.0;
  /// Unit, perpendicular to both edges, out of the second edge's body.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double s = 0.0, t = 0.0;  ///< where the nearest points are: end[0] + s (end[1] - end[0])
};

/// A hit when edges `a` and `b` end the step nearer than `skin` (m) or past each other, their
/// nearest points inside both (the ends are nodes: nodes against triangles take those), and
/// either `a` was in front of `b` at the start (it came through) or is behind it by at most
/// `shallow` (m) now. `outward_a`, `outward_b`: directions out of each edge's body at the end
/// (the sum of its two triangles' unit normals); the common normal must point out of b and into
/// a, near both. Nearly parallel edges, and edges whose common normal points out of neither body
/// (side by side in one plane), are never hit: their nodes and faces touch first.
bool edgesMeet(const SweptEdge& a, const SweptEdge& b, const Eigen::Vector3d& outward_a,
               const Eigen::Vector3d& outward_b, double skin, double shallow, EdgeEdgeHit* hit);

}  // namespace deformable_sim::core
