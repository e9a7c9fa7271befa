// Contact between bodies and of a body with itself (the `bodies` and `self` keys of the contact
// effect), for every pair of models. After every body has taken its step, each surface node that
// ended the step behind a surface triangle of another body (or of its own body, away from its own
// elements) is found through the triangles' bounding-volume trees (core/body_surface.h) and the
// swept test of core/node_triangle.h. It is then put back by equal and opposite position shifts
// of the node and of the triangle's point (split by their inverse masses, barycentric among the
// corners), so momentum is kept; friction undoes the pair's tangential slip within Coulomb's cone
// of that push; and their velocities lose the approach along the normal and, within the cone of
// the impulses, the slip. A velocity-level projection, after the implicit step: unlike the
// obstacles' hold, nothing keeps a touching pair apart within the next solve, so a body resting
// on a soft body is pushed back each step rather than carried (see doc/physics.md).
#pragma once

#include <optional>
#include <vector>

#include "deformable_sim/core/body.h"
#include "deformable_sim/core/body_surface.h"
#include "deformable_sim/core/contact.h"
#include "deformable_sim/core/contact_participant.h"

namespace deformable_sim::core {

class BodyContact {
 public:
  /// `with_bodies[b]`: body b touches the other bodies that do; `with_self[b]`: it touches
  /// itself. Builds the surfaces of those bodies; allocates only here.
  BodyContact(const std::vector<Body>& bodies, const ContactSettings& settings,
              const std::vector<bool>& with_bodies, const std::vector<bool>& with_self);

  /// After every body's step of length dt: finds and resolves the contacts, and adds to
  /// reports[b] the counts and the depth left. Allocates nothing.
  void resolve(std::vector<Body>& bodies, double dt, std::vector<StepReport>& reports);

  /// The depth a node may be left inside the other body after a step: 1 % of the smaller body's
  /// size (the diagonal of its rest bounding box), m.
  double tolerance(int a, int b) const;
  /// Whether body b takes part (its surface is built).
  bool takesPart(int b) const { return surfaces_[b].has_value(); }
  const BodySurface& surface(int b) const { return *surfaces_[b]; }

  /// Fraction of a pair's tolerance to which the position passes bring every contact.
  static constexpr double kTarget = 0.01;
  /// Passes over the contacts to separate them (Gauss-Seidel) and to settle their velocities.
  static constexpr int kPositionPasses = 64;
  static constexpr int kVelocityPasses = 8;

 private:
  struct Contact {
    int node_body = 0, triangle_body = 0;
    SurfacePoint node, triangle;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< out of the triangle's body
    double pushed = 0.0;   ///< kg m: the normal shift of the position passes
    double impulse = 0.0;  ///< N s: the normal impulse of the velocity passes
  };

  bool touches(int a, int b) const;
  /// The contact of surface node i of body a, if it ended the step behind some triangle.
  void findContact(int a, int i);
  /// Position passes until every contact is within kTarget of its tolerance; returns the
  /// largest depth left, per body into `left`.
  void separate(std::vector<StepReport>& reports);
  /// Undoes each pair's tangential slip within the step, within μ times the normal shift.
  void holdBySlip();
  void settleVelocities(double dt);
  /// The slip of the contact's two points within the step (positions now minus at the start).
  Eigen::Vector3d slip(const Contact& c) const;
  double gap(const Contact& c) const;
  void shift(Contact& c, const Eigen::Vector3d& amount);

  ContactSettings settings_;
  std::vector<bool> with_bodies_, with_self_;
  std::vector<std::optional<BodySurface>> surfaces_;
  std::vector<std::optional<ContactParticipant>> participants_;
  std::vector<Contact> contacts_;  ///< at most one per surface node: reserved once
};

}  // namespace deformable_sim::core
