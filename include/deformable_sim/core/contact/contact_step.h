// The order of a step's contact, written once for whatever steps bodies (Simulation, the
// benchmarks run through it): before the bodies step, each holds the points it has on the
// obstacles; after, the bodies meet one another (detection, response with friction, separation)
// while those points are still held, so that what presses on a body goes through it to the
// obstacles under it; then each body lets go of what would pull, and the obstacles have the last
// say: what is inside them is put back out (projection). With `one_problem`
// (core/contact/contact_impulses.h) there are no holds: after the bodies' free steps, every
// contact, with obstacles and between bodies, is found and solved as one problem, and the bodies
// take its impulses.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/contact/body_contact.h"
#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/contact/contact_impulses.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"

namespace deformable_sim::core {

class ContactStep {
 public:
  /// For `bodies` as built: obstacle contact for each finite-element body (rigid and pseudo-rigid
  /// ones pass through obstacles), contact between bodies and of a body with itself where the
  /// settings and the bodies' own effects ask for it. Allocates here, in embed(), and in begin()
  /// when the number of obstacles changes.
  ContactStep(BodyList& bodies, const ContactSettings& settings);

  /// Body b touches with `surface`, the one it was made from, not its grid's boundary.
  void embed(int b, const EmbeddedSurface& surface, const Body& body);

  /// Before the bodies step, with the obstacles where they will be at its end: when they are
  /// others than in the last step (a scene's first step, a robot's links appearing in tf), they
  /// start where they are and no point touches them yet.
  void begin(const std::vector<PlacedShape>& obstacles);
  /// Body b about to step by dt: holds its points on the obstacles at
  /// their place on them. Returns the wall time it took, s. Bodies may be held side by side.
  double hold(int b, Body& body, const std::vector<PlacedShape>& obstacles, double dt);
  /// After every body's step: between bodies, then the obstacles; reports[b] gains its contact
  /// counts and times, each pair its depth left at the end. Bodies are put back on `threads`
  /// threads.
  void finish(BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt, int threads,
              std::vector<StepReport>& reports);
  /// Whether contact acts on body b at all.
  bool actsOn(int b) const {
    return states_[b].has_value() || body_contact_ || (impulses_ && impulses_->takesPart(b));
  }
  /// Body b went back to where it started the step: what it touched is forgotten.
  void forget(int b);

  /// What body b felt from each obstacle in the last step (empty for a body it does not act on).
  const std::vector<ContactLoad>& obstacleContacts(int b) const;
  long obstacleSteps() const { return obstacle_steps_; }  ///< body steps with obstacle contact
  long bodySteps() const { return body_steps_; }          ///< steps with contact between bodies
  const ContactImpulses* obstacleImpulses() const { return impulses_ ? &*impulses_ : nullptr; }
  const BodyContact* bodyContact() const { return body_contact_.get(); }

 private:
  /// Contact between bodies and with themselves, if the settings and some body ask for it.
  void addBodyContact(BodyList& bodies);
  /// Contact between bodies after their steps; its time shared among those taking part.
  void resolveBetweenBodies(BodyList& bodies, double dt, int threads,
                            std::vector<StepReport>& reports);

  /// `seconds` shared equally among the bodies b that `takes_part(b)`, added to their times'
  /// `part`.
  template <typename TakesPart>
  static void shareTime(double seconds, const TakesPart& takes_part, double StepTimes::*part,
                        std::vector<StepReport>& reports) {
    const int n = static_cast<int>(reports.size());
    int taking_part = 0;
    for (int b = 0; b < n; ++b) taking_part += takes_part(b);
    for (int b = 0; b < n; ++b) {
      if (takes_part(b)) reports[b].times.*part += seconds / taking_part;
    }
  }

  ContactSettings settings_;
  std::vector<std::optional<ContactState>> states_;  ///< per body: its obstacle contact
  /// Only when some body touches others; on the heap, where impulses_ finds it.
  std::unique_ptr<BodyContact> body_contact_;
  /// Obstacle contact as one problem (ContactSettings::one_problem), in place of states_.
  std::optional<ContactImpulses> impulses_;
  std::vector<Eigen::Isometry3d> starts_;  ///< the obstacles' poses at the step's start
  long obstacle_steps_ = 0;
  long body_steps_ = 0;
};

}  // namespace deformable_sim::core
