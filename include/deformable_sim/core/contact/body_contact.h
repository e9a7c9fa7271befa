// Contact between bodies and of a body with itself (the `bodies` and `self` keys of the contact
// effect), for every pair of models. After every body has taken its step (its nodes on obstacles
// still held), each surface node that ended the step behind a surface triangle of another body
// (or of its own body, away from its own elements), or in front of it by less than the
// tolerance, is found through the triangles' bounding-volume trees (core/body_surface.h) and the
// swept test of core/node_triangle.h; so is each surface edge that ended the step across an edge
// of another body (or of its own, away from it), or nearer than the tolerance
// (core/edge_edge.h): edges meet where neither surface has a node. Equal and opposite impulses on
// the node and the triangle's point (barycentric among its corners), in Gauss-Seidel passes that
// start from the impulses the same node had last step and stop once they change nothing by more
// than kVelocityTolerance, then let each pair approach no faster than closes the gap it had at the
// step's start, and friction stop its slip within Coulomb's cone; each impulse moves the end
// positions with the velocities (x = x0 + dt v). A finite-element body answers an impulse as its
// implicit step would have, through its own matrix (core/bodies/implicit_response.h), so a body
// resting on a soft body is carried, and what presses on a body goes through it to what holds
// it. Against a surface held all over the free side answers node by node. A last round finds the
// contacts again and puts back, node by node, what the impulses pressed in elsewhere. Momentum is
// kept (doc/physics.md). A body made from a surface takes part with that surface (embed()): its
// points are on its cells' nodes. Each body finds its contacts and takes its answers on the
// solver's threads: the same bits on any count.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "deformable_sim/core/bodies/body_list.h"
#include "deformable_sim/core/bodies/contact_participant.h"
#include "deformable_sim/core/contact/body_surface.h"
#include "deformable_sim/core/contact/contact.h"

namespace deformable_sim::core {

class BodyContact {
 public:
  /// `with_bodies[b]`: body b touches the other bodies that do; `with_self[b]`: it touches
  /// itself. Builds the surfaces of those bodies; allocates only here.
  BodyContact(BodyList& bodies, const ContactSettings& settings,
              const std::vector<bool>& with_bodies, const std::vector<bool>& with_self);

  /// Body b was made from `surface`: it touches with that surface, not its grid's boundary, which
  /// stands up to a cell outside it. Allocates.
  void embed(int b, const EmbeddedSurface& surface, const Body& body);

  /// After every body's step of length dt: finds and resolves the contacts, and adds to
  /// reports[b] the counts and the depth left. Finds them and gives each body its answers on
  /// `threads` threads, a body to a thread (the same bits on any count). Allocates nothing.
  void resolve(BodyList& bodies, double dt, int threads, std::vector<StepReport>& reports);
  /// At the step's very end (after the obstacles' correction too): each pair's depth, how far
  /// its last contacts are left inside, from the bodies' positions. Allocates nothing.
  void measureDepths(const BodyList& bodies);

  /// The depth a node may be left inside the other body after a step: 1 % of the smaller body's
  /// size (the diagonal of its rest bounding box), m.
  double tolerance(int a, int b) const;
  /// Whether body b takes part (its surface is built).
  bool takesPart(int b) const { return surfaces_[b].has_value(); }

  /// How far one body starts inside another: a corner of body `inside` behind the closed surface
  /// of body `of` by `depth` m (the deepest such; inside -1 when none is).
  struct Overlap {
    int inside = -1, of = -1;
    double depth = 0.0;
  };
  /// The deepest overlap of two bodies that touch each other, where they are now. A body whose
  /// surface is open, or not a valid closed mesh, is not looked into. Allocates.
  Overlap deepestOverlap() const;
  /// The deepest two bodies may start inside each other, as a fraction of the pair's tolerance.
  /// Deeper, detection is not to be trusted with the way out: two tubes placed 9 mm into each
  /// other (walls 5 mm thick) have their surfaces in each other's bores, and the position passes
  /// fed each other up to 1e130 J in 200 steps; 2 mm apart they came out clean in a step.
  static constexpr double kStartingOverlap = 1.0;
  /// What body a felt from body b in the last step (a == b: from itself, which nets to zero
  /// force): the contact impulses over dt, the torque about the world origin, the points found
  /// touching and the deepest of them inside before being put back. Zero when they did not touch.
  const ContactLoad& load(int a, int b) const { return loads_[a * surfaces_.size() + b]; }
  const BodySurface& surface(int b) const { return *surfaces_[b]; }

  /// Fraction of a pair's tolerance to which the position passes bring every contact.
  static constexpr double kTarget = 0.01;
  /// Passes over the contacts to separate them (Gauss-Seidel) and, at most, to settle their
  /// velocities.
  static constexpr int kPositionPasses = 64;
  static constexpr int kVelocityPasses = 32;
  /// m/s: the velocity passes stop once no update in a pass moved its pair by more.
  static constexpr double kVelocityTolerance = 1e-4;
  /// Rounds of finding and resolving contacts a step (the last only when the first's answers can
  /// have pressed nodes in elsewhere).
  static constexpr int kRounds = 2;
  /// The most edges one edge meets in a step (two bars laid crosswise: each edge crosses two).
  static constexpr int kEdgeHits = 4;
  /// A point whose free nodes carry less of its weight than this counts as held: moving it by
  /// its free nodes alone would take impulses and shifts of 1 / weight times what it needs (two
  /// blocks side by side on a floor, where a node touches the other's bottom edge, exploded).
  static constexpr double kMovable = 0.2;
  /// A touch is of two nodes (see dropTwiceFound()) when each side's point puts at least this
  /// weight on a node.
  static constexpr double kOnTheNode = 0.9;
  /// Under the one problem, a node behind a triangle by no more than this fraction of the pair's
  /// tolerance only touches it (as one in front of it does), and two triangles it touches or is
  /// behind are about as near when their depths differ by less: the node then takes the one it
  /// faces more squarely, not whichever came first (a block's corner on the edge of the one
  /// beside it took its bottom face, pressing down a block that stands on the floor).
  static constexpr double kTie = 1.0;
  /// ... and faces one more squarely only by more than this (in cosines): triangles of one face,
  /// bent a little, keep the first found, so a node keeps its triangle from step to step.
  static constexpr double kFacingTie = 0.1;

  /// A contact found: a point of one body's surface (the node side: a corner, or a point of an
  /// edge) against a point of another's or its own (the triangle side: a triangle's point, or an
  /// edge's), along a normal out of the triangle side.
  struct Contact {
    int node_body = 0, triangle_body = 0;
    /// Of node and triangle; a node's contact is on one corner, edges that meet on two.
    SurfaceCorners node_corners, triangle_corners;
    SurfacePoint node, triangle;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< out of the triangle's body
    double pushed = 0.0;   ///< kg m: the normal shift of the position passes
    double impulse = 0.0;  ///< N s: the normal impulse of the velocity passes
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();  ///< N s: their friction impulse
    double start_gap = 0.0;  ///< m: along the normal, node minus triangle point, at the start
    /// m/s per N s: how the points part per unit impulse on the pair (both bodies' answers).
    Eigen::Matrix3d compliance = Eigen::Matrix3d::Zero();
    /// Each side's part of it (zero for a side that takes no impulses).
    Eigen::Matrix3d node_compliance = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d triangle_compliance = Eigen::Matrix3d::Zero();
    bool local = false;                      ///< answered node by node (see settleVelocities)
    int node_kept = -1, triangle_kept = -1;  ///< each side's ContactParticipant::keep()
    /// Whether each side takes impulses: a point that lies mostly on held nodes does not (see
    /// kMovable); what holds them takes its share.
    bool node_moves = true, triangle_moves = true;
  };

  // As part of one contact problem a step (core/contact/contact_impulses.h), which takes the
  // contacts found here, solves them with the obstacles' and hands back their impulses.
  /// The participant through which body b takes part (nullptr: it does not). The one problem
  /// pushes through it too: a body answers through one participant a step.
  ContactParticipant* participant(int b) const { return participants_[b].get(); }
  /// After every body's free step of dt: begins the participants, finds the contacts (each touch
  /// once: see dropTwiceFound()) and counts them into reports. Allocates nothing.
  void find(BodyList& bodies, double dt, int threads, std::vector<StepReport>& reports);
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The impulse on contact i's node side in the last step (world, N s) where the same corner
  /// touched the same body then, else zero: the solve's start.
  Eigen::Vector3d lastImpulse(int i) const;
  /// Contact i took `impulse` (world, N s) on its node side, the opposite on its triangle side.
  void takeImpulse(int i, const Eigen::Vector3d& impulse);
  /// After the bodies took the impulses (their participants ended): the loads, the impulses kept
  /// for the next step's start, the depths left into reports, and the sweeps' next start.
  void finishStep(const BodyList& bodies, double dt, std::vector<StepReport>& reports);

 private:
  bool touches(int a, int b) const;
  /// After the first round: whether its answers and corrections can have moved a node into a
  /// surface deeper than the position passes leave it (else the last round finds nothing new).
  bool couldHaveMovedIn() const;
  /// Room for a contact per surface corner and kEdgeHits per edge.
  void reserveContacts();
  /// Sweeps the surfaces from the step's start to the bodies' positions now and finds every
  /// contact; `new_step`: the bodies have just stepped (else a later round of the same step).
  void findContacts(BodyList& bodies, bool new_step, int threads);
  /// Keeps one finding of each touch of two nodes: a node on (nearly) a node of the other body
  /// whose own contact is on (nearly) the first (meshes whose nodes meet, as equal blocks
  /// stacked or side by side), and edges that meet at their ends. Found twice, a touch gives the
  /// contact problem rows of W that are equal, or whose normals disagree (one block's side face,
  /// the other's bottom), which no solve can share out: its sweeps crawl, its Newton steps are
  /// singular. Of two node contacts it keeps the one whose node faces its triangle more squarely;
  /// edges at their ends are left to the nodes' contacts.
  void dropTwiceFound();
  void countContacts(std::vector<StepReport>& reports) const;
  /// Starts the step's loads: the contacts just found, where and how deep.
  void startLoads();
  /// Adds the velocity passes' impulses over dt to the loads.
  void addContactForces(double dt);
  /// A triangle a node is behind, as findContact() weighs it.
  struct Candidate {
    /// 0: came through it; 1: ended behind it; 2: touches it, or (one problem) is behind it by
    /// no more than kTie of the tolerance; 3: none yet.
    int rank = 3;
    double depth = std::numeric_limits<double>::infinity();  ///< m, either side
    double facing = -2.0;  ///< how squarely the node faces it: -(its normal . the node's outward)
    bool last = false;     ///< the node touched it last step
  };
  /// Whether a node takes `hit` over `best` (`tie`: see kTie).
  bool prefer(const Candidate& hit, const Candidate& best, double tie) const;
  /// The contact of surface node i of body a, if it ended the step behind some triangle, into
  /// `found`.
  void findContact(int a, int i, std::vector<Contact>& found) const;
  /// The contacts of surface edge e of body a with the edges of bodies after a (and of a itself,
  /// after e) that it ended the step across or near: up to kEdgeHits.
  void findEdgeContacts(int a, int e, std::vector<Contact>& found) const;
  /// Out of body b at its surface edge e, now: the sum of its two triangles' unit normals.
  Eigen::Vector3d outwardAt(int b, const SurfaceEdge& edge) const;
  /// Position passes until every contact is within kTarget of its tolerance; returns the
  /// largest depth left, per body into `left`.
  void separate(std::vector<StepReport>& reports);
  /// Velocity passes (Gauss-Seidel): each pair's normal impulse, then its friction, from last
  /// step's impulses, until they change the velocities by less than kVelocityTolerance.
  void settleVelocities(double dt, int threads);
  /// Body b's part of each contact: its compliance at its point and its kept answers there.
  void prepareAnswers(int b);
  /// Body b's kept answers at a point of its surface, summed from its corners' (each kept once a
  /// round); -1: not kept.
  int keepPoint(int b, const SurfaceCorners& corners);
  /// One Gauss-Seidel update of the pair: its normal impulse, then its friction, applied at once.
  void update(Contact& c, double dt);
  /// What lastImpulse() says of contact c.
  Eigen::Vector3d lastImpulseOf(const Contact& c) const;
  /// Gives a node's contact the impulse it had last step on the same body, if it had one.
  void startFromLastStep(Contact& c);
  /// Keeps the impulses of the node contacts for the next step's start.
  void keepForNextStep();
  double startGap(const Contact& c) const;
  /// How fast the pair's points part along `direction` per unit impulse there.
  double compliance(const Contact& c, const Eigen::Vector3d& direction) const;
  /// Equal and opposite impulses on the pair, their end positions moved with them.
  void apply(Contact& c, const Eigen::Vector3d& impulse);
  double gap(const Contact& c) const;
  /// Sets which sides of a contact just found take impulses, and adds it to `found`.
  void add(Contact c, std::vector<Contact>& found) const;
  void shift(Contact& c, const Eigen::Vector3d& amount);

  ContactSettings settings_;
  double dt_ = 0.0;  ///< of the step being resolved
  std::vector<bool> with_bodies_, with_self_;
  std::vector<std::optional<BodySurface>> surfaces_;
  std::vector<std::unique_ptr<ContactParticipant>> participants_;
  /// At most one per surface node and kEdgeHits per edge: reserved once.
  std::vector<Contact> contacts_;
  std::vector<std::vector<Contact>> found_;  ///< per body, the contacts it found; reserved once
  std::vector<ContactLoad> loads_;           ///< per pair of bodies (see load()), sized once
  /// A node contact's impulse (world, N s) and the body it touched, kept for the next step.
  struct Warm {
    int triangle_body = -1;
    Triangle corners{-1, -1, -1};  ///< of the triangle it touched
    Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  };
  std::vector<std::vector<Warm>> warm_;  ///< per body, per surface corner; sized once
  /// Per body, per surface corner: its ContactParticipant::keep() in this round, kNotKept yet;
  /// and the corners kept (sized once).
  std::vector<std::vector<int>> corner_kept_;
  std::vector<std::vector<int>> kept_corners_;
  static constexpr int kNotKept = -2;
  /// Per body, per surface corner: the index of its node contact in contacts_ (-1: none), while
  /// dropTwiceFound() runs; and per contact, whether it is dropped. Sized once.
  std::vector<std::vector<int>> node_contact_;
  std::vector<char> twice_found_;
  double largest_change_ = 0.0;  ///< m/s, in the current velocity pass
  int passes_ = 0;               ///< velocity passes in the last step
};

}  // namespace deformable_sim::core
