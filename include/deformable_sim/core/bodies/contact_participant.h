// A body as contact between bodies sees it: where a point of its surface is, how fast it moves,
// and how it answers an impulse there within its last step. One implementation per kind of body
// — finite elements (core/bodies/elastic_participant.h) and whole-body models
// (core/bodies/whole_body_participant.h) — made by Body::contactParticipant().
#pragma once

#include <Eigen/Core>
#include <limits>

#include "deformable_sim/core/geometry/surface_point.h"

namespace deformable_sim::core {

class ContactParticipant {
 public:
  virtual ~ContactParticipant() = default;

  /// Takes the body's state after its step of `dt`; a rigid or pseudo-rigid body starts with no
  /// change. `new_step`: false for a later round of the same step, whose answers are still good.
  virtual void begin(double dt, bool new_step = true) = 0;
  /// Gives the body what the contact changed, and the constraint forces its impulses asked of its
  /// held nodes.
  virtual void end() = 0;
  /// After end(): the most any node moved in the round (the whole-body answers, and the local
  /// pushes and nudges), m, an upper bound; infinity where not known.
  virtual double largestMove() const { return std::numeric_limits<double>::infinity(); }

  virtual Eigen::Vector3d position(const SurfacePoint& point) const = 0;
  virtual Eigen::Vector3d velocity(const SurfacePoint& point) const = 0;
  /// n^T W n: how fast the point moves along the unit normal n per unit impulse along it (a
  /// quadratic form in n, whatever its length).
  virtual double inverseMass(const SurfacePoint& point, const Eigen::Vector3d& normal) const = 0;
  /// W itself: the point's velocity change per unit impulse there; `local`: a finite-element
  /// body's nodes answering alone, by their lumped masses; `kept`: keep()'s number for the point
  /// (then W comes from what it summed).
  virtual Eigen::Matrix3d compliance(const SurfacePoint& point, bool local = false,
                                     int kept = -1) const;
  /// The velocity change of point `at` per unit impulse at point `from`, both of this body (W_ij
  /// of the contacts there; compliance() when they are one); `from_kept`: keep()'s number for
  /// `from`, or -1.
  virtual Eigen::Matrix3d coupling(const SurfacePoint& at, const SurfacePoint& from,
                                   int from_kept = -1) const = 0;
  /// Linear solves a finite-element body took in this step to answer impulses.
  virtual int solves() const { return 0; }
  /// The point's body takes `impulse` (N s) there within the step: its velocities change by
  /// W impulse and, the step being x = x0 + dt v, its positions by dt W impulse (`local`: see
  /// compliance()).
  virtual void push(const SurfacePoint& point, const Eigen::Vector3d& impulse, bool local = false,
                    int kept = -1) = 0;
  /// Readies the point for many push()es within the round (a finite-element body sums its
  /// nodes' answers once, not at every push) and returns the `kept` to pass them and
  /// compliance(); -1: nothing to ready. A point kept before another point's nodes first touched
  /// is answered as if not kept. Allocates only while a body meets more points than ever before.
  virtual int keep(const SurfacePoint&) { return -1; }
  /// keep() for a point that is the same from step to step (a corner of the body's surface,
  /// numbered `id`): what was readied may be kept from one step to the next.
  virtual int keepCorner(int, const SurfacePoint& point) { return keep(point); }
  /// A point that is the sum of kept points with `weights` (a triangle's of its corners'),
  /// kept as keep() would; -1 when not kept.
  virtual int keepSum(const int*, const double*, int) { return -1; }
  /// A small correction of positions only (what is left inside after the impulses), momentum
  /// untouched: a finite-element body's nodes move by their lumped inverse masses alone, so that
  /// the correction stays where it is needed; other bodies with their whole motion.
  virtual void nudge(const SurfacePoint& point, const Eigen::Vector3d& shift) = 0;
  virtual double nudgeCompliance(const SurfacePoint& point,
                                 const Eigen::Vector3d& normal) const = 0;
  /// The part of the point's weight on nodes free to move: 1 for a rigid or pseudo-rigid body,
  /// 0 where a finite-element body is held all over.
  virtual double movable(const SurfacePoint& point) const = 0;

 protected:
  /// W from the quadratic form n^T W n on the axes and their sums (W is symmetric).
  Eigen::Matrix3d complianceFromInverseMass(const SurfacePoint& point) const;
};

}  // namespace deformable_sim::core
