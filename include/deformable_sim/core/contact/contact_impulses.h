// A step's contact with obstacles as one problem (core/contact/contact_problem.h), in the order a
// reader follows it: every body first takes its step free of contact; detection then finds the
// points of its collision surface that may meet an obstacle in the step (obstacle_touches.h); the
// problem gathers them all, each with its free relative velocity, the least normal velocity that
// leaves it outside at the step's end, and the Delassus blocks of every pair of contacts on one
// body from the body's own step (core/bodies/contact_participant.h: a finite-element body answers
// an impulse through the matrix of its implicit step, so the blocks are those of the constrained
// step itself); one solve gives impulses that only push (λn >= 0) and friction within Coulomb's
// disc (|λt| <= μ λn); the bodies then take them, velocities and end positions alike. Sticking,
// sliding and letting go all come out of that solve: a point whose obstacle moves away is simply
// not pushed, and one held by friction moves with its obstacle.
//
// The least normal velocity: a point that was outside at the step's start may close its gap
// within the step, and no more; one found inside at the start (bodies placed into an obstacle, or
// the solve's tolerance) is pushed out at no more than kPushOutSpeed, so that a deep overlap costs
// steps, not energy.
//
// With contact between bodies (core/contact/body_contact.h) in the same problem: its detection
// finds the pairs of points, each a contact whose two sides are points of bodies (one body twice
// for a body touching itself), and whose Delassus blocks are the sums of both sides' answers,
// signed by the side; the bodies push through the same participants. A point that lies mostly on
// held nodes (BodyContact::kMovable), with an obstacle or another body, neither takes impulses nor
// feels the others' in the problem: its free nodes alone would take 1 / weight^2 the impulse, and
// be flung (a block held by grasp attachments had a node thrown 30 cm by a finger's edge).
//
// Each contact starts the solve from its impulse of the last step when the same point touched
// the same obstacle then. Storage is sized once per body and grows only while more points touch
// than ever before.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/bodies/contact_participant.h"
#include "deformable_sim/core/contact/body_contact.h"
#include "deformable_sim/core/contact/body_surface.h"
#include "deformable_sim/core/contact/contact.h"
#include "deformable_sim/core/contact/contact_problem.h"
#include "deformable_sim/core/contact/obstacle_touches.h"

namespace deformable_sim::core {

class ContactImpulses {
 public:
  /// Obstacle contact for the bodies b with `takes_part[b]`, with friction μ from `settings`, and
  /// the contacts `between` bodies finds, if given (it must outlive this). Builds the collision
  /// surfaces; allocates.
  ContactImpulses(BodyList& bodies, const ContactSettings& settings,
                  const std::vector<bool>& takes_part, BodyContact* between = nullptr);

  /// Body b touches with `surface`, the one it was made from. Allocates.
  void embed(int b, const EmbeddedSurface& surface, const Body& body);

  /// After every body's free step of dt: finds the contacts, solves them as one problem and gives
  /// the bodies their impulses. `start_poses[k]`: obstacle k's pose at the step's start. Adds each
  /// body's touching points to reports[b].contacts. Contact between bodies is found on `threads`.
  void resolve(BodyList& bodies, const std::vector<PlacedShape>& obstacles,
               const std::vector<Eigen::Isometry3d>& start_poses, double dt, int threads,
               std::vector<StepReport>& reports);
  /// Body b went back to where it started the step, or the obstacles are others: its last
  /// impulses are no start for the next solve.
  void forget(int b);
  void forgetAll();

  /// Whether obstacle contact acts on body b.
  bool takesPart(int b) const { return surfaces_[b].has_value(); }
  /// Per obstacle, what body b felt from it in the last step.
  const std::vector<ContactLoad>& loads(int b) const { return loads_[b]; }
  /// The solve of the last step.
  const ContactSolveReport& lastSolve() const { return last_solve_; }
  /// Wall time of the last resolve() spent finding and recording contact between bodies, s.
  double timeBetweenBodies() const { return time_between_; }
  const ContactProblem& problem() const { return problem_; }
  /// Contact i's relative velocity (its frame, m/s) from the bodies' velocities now: after the
  /// step, what the last solve's problem().velocity(i) said it would be.
  Eigen::Vector3d velocityNow(int i, const BodyList& bodies) const;

  /// The widest a body's point may stand off an obstacle and still take part in its problem: this
  /// fraction of the body's size (the diagonal of its rest bounding box).
  static constexpr double kMarginOfSize = 0.01;
  /// m/s: the fastest a point found inside an obstacle at the step's start is pushed out.
  static constexpr double kPushOutSpeed = 0.1;
  /// The solve's sweeps at most and its tolerance, m/s: 0.01 µm/s leaves a point 0.1 nm off
  /// where it should be after a step of 10 ms (Newton gets there where the sweeps crawl).
  static constexpr int kMaxSweeps = 200;
  static constexpr double kTolerance = 1e-8;
  /// Coupling blocks reserved per contact that can be.
  static constexpr int kCouplingsPerContact = 32;

 private:
  /// One side of a contact: a point of a body, or of an obstacle (body -1) whose motion is given.
  struct Side {
    int body = -1;
    SurfacePoint point;
    SurfaceCorners corners;  ///< the point on the body's surface corners
    double sign = 1.0;       ///< +1: the side the normal points into; -1: the other
    bool moves = true;       ///< takes impulses
    int kept = -1;           ///< its ContactParticipant::keep()
  };

  /// Finds the contacts with obstacles (touches_, body_start_) and between bodies, and their sides.
  int findContacts(BodyList& bodies, const std::vector<PlacedShape>& obstacles,
                   const std::vector<Eigen::Isometry3d>& start_poses, double dt, int threads,
                   std::vector<StepReport>& reports);
  /// Where body b's surface corners were at the step's start, and their velocities now (after its
  /// free step), into starts_[b] and velocities_[b].
  void placeCorners(int b, const FiniteElementBody& body);
  /// The point of body b a touch is at (a corner, or a point of a triangle), and on its corners.
  SurfacePoint pointOf(const ObstacleTouch& touch) const;
  SurfaceCorners cornersOf(const ObstacleTouch& touch) const;
  /// Body b's collision surface: its own, or the one contact between bodies made.
  const BodySurface& surfaceOf(int b) const {
    return surfaces_[b] ? *surfaces_[b] : between_->surface(b);
  }
  /// Readies a side's point for the solve's pushes (ContactParticipant::keep): a corner, or in
  /// `with_sums` passes a point between corners as the sum of its corners'.
  int keepSide(const Side& side, bool with_sums);
  /// How far the point's free step moved it: dt times its velocity now.
  static Eigen::Vector3d freeStep(const SurfacePoint& point, const FiniteElementBody& body,
                                  double dt);
  /// Where a touch's point is at the body's positions now.
  Eigen::Vector3d pointNow(const ObstacleTouch& touch, const Body& body) const;
  /// Sets contact i of the problem: its frame, friction, free relative velocity, least normal
  /// velocity, Delassus diagonal and warm start.
  void setContact(int i, double dt);
  /// The Delassus blocks of every pair of contacts that share a body.
  void addCouplings();
  /// Gives each body its contacts' impulses, and records the loads and warm starts.
  void apply(BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt,
             std::vector<StepReport>& reports);
  /// Body b's loads from the contacts that pushed, at its points where they ended the step, and
  /// their impulses kept for the next step's start.
  void addLoads(int b, const Body& body, const std::vector<PlacedShape>& obstacles, double dt);
  /// Room in the problem for every point that can touch at once.
  void reserveProblem();

  ContactSettings settings_;
  ContactSolveSettings solve_settings_{kMaxSweeps, kTolerance};
  std::vector<std::optional<BodySurface>> surfaces_;
  BodyContact* between_ = nullptr;
  /// Per body, what it answers through: between_'s participant, or its own (owned_).
  std::vector<ContactParticipant*> participants_;
  std::vector<std::unique_ptr<ContactParticipant>> owned_;
  std::vector<char> begun_;  ///< per body: its own participant began this step
  /// Per body, per corner: where it was at the step's start, and its free velocity.
  std::vector<std::vector<Eigen::Vector3d>> starts_, velocities_;
  std::vector<double> margins_;             ///< per body, m
  std::vector<ObstacleTouch> touches_;      ///< the step's contacts, body by body
  std::vector<int> near_triangles_;         ///< room for a mesh obstacle's triangles near a face
  std::vector<std::array<Side, 2>> sides_;  ///< per contact: the obstacles', then between_'s
  /// Per body, the (contact, side) pairs on it that take impulses, in contact order.
  std::vector<std::vector<std::pair<int, int>>> on_body_;
  std::vector<int> body_start_;  ///< per body, its first contact (and one past the last)
  ContactProblem problem_;
  ContactSolveReport last_solve_;
  double time_between_ = 0.0;
  std::vector<std::vector<ContactLoad>> loads_;  ///< per body, per obstacle
  /// Per body, per corner and then per triangle: the obstacle it pushed on in the last step (-1:
  /// none) and the impulse (world, N s). addLoads() writes it as it goes, and so also tells
  /// which points one obstacle name has already counted in this step.
  struct Warm {
    int obstacle = -1;
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  };
  std::vector<std::vector<Warm>> warm_;
  /// The slot of a touch's warm start in warm_[touch.body].
  int warmSlot(const ObstacleTouch& touch) const;
};

}  // namespace deformable_sim::core
