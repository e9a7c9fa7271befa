// Contact with rigid obstacles (the `contact` effect). After each step, points of a body that
// ended up inside an obstacle are put back on its surface and their velocity into it, relative to
// the obstacle's, removed (friction, up to μ times that impulse, slows their sliding). The points
// are the body's nodes or, for a body made from a surface (core/embedded_surface.h), the vertices
// of that surface, each moving with its cell's nodes: a vertex is moved by moving its cell's free
// nodes alike (the cell shifts, unstrained). A point that touches an obstacle is then held in the
// next step's implicit solve (a node at its point of the obstacle, a vertex by its cell's nodes
// moving with the obstacle, which may move: a robot's finger); if it slides, at the place its
// slip takes it to. So the obstacle carries the body through the solve, sliding or not (a resting
// body is not over-compressed, a squeezed one is lifted by friction). It is let go when the
// constraint would pull it into the obstacle. Coulomb's law is applied to the body's held points
// on one obstacle together (a patch): while their tangential force stays within μ times their
// normal force they stick; otherwise the obstacle exerts μ times the normal force against the
// slip, and what it exerted beyond that in the solve is given back to the body as a whole (or,
// for a body that touches several obstacles or faces or is held otherwise, through its next
// solve: the patch's points slide on the obstacle's plane, held along its normal only, with
// friction and that excess as forces). Stable at any stiffness and step; costs nothing when the
// scene does not enable it.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "deformable_sim/core/bodies/finite_element_body.h"
#include "deformable_sim/core/elements/mesh.h"
#include "deformable_sim/core/geometry/shape.h"
#include "deformable_sim/core/geometry/triangle_separation.h"
#include "deformable_sim/core/surface_bodies/embedded_surface.h"

namespace deformable_sim::core {

struct ContactSettings {
  double friction = 0.5;  ///< Coulomb coefficient μ >= 0; with 0 a node never sticks
  bool bodies = false;    ///< bodies touch one another (core/body_contact.h)
  bool self = false;      ///< a body touches itself
  /// Obstacle contact as one problem a step (core/contact/contact_impulses.h) instead of the
  /// holds below; not yet the default while it does not cover the edges of obstacles.
  bool one_problem = false;
};

/// What a body felt from one obstacle in the last step.
struct ContactLoad {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< on the body, world frame, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< on the body about the world origin, N m
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< mean of the touching points, m
  int points =
      0;  ///< points (nodes, or vertices of an embedded surface) touching it after the step
  /// The deepest a point was found inside it before the step's correction put it back (by the
  /// face it came in through), m: how far the bodies moved into one another within the step.
  double penetration = 0.0;
  /// The deepest a touching point is still inside it at the step's end, m: what one sees (to the
  /// nearest face of the obstacle it touches; a point held by the user or a grasp is not put back).
  double depth = 0.0;
};

/// Which nodes touch which obstacle, from step to step. Sized once per body and per number of
/// obstacles; allocates nothing while that number stays the same.
class ContactState {
 public:
  /// The nodes of the body of `mesh` touch the obstacles, and the edges and corners of box and mesh
  /// obstacles touch its boundary faces.
  explicit ContactState(const Mesh& mesh);
  /// The vertices and triangles of `surface` touch them instead (a body made from a surface): its
  /// nodes lie up to a cell outside the surface. Allocates.
  void embed(const EmbeddedSurface& surface);

  /// Before a step of `dt` s, with the obstacles where they will be at its end: holds the free
  /// points that touch an obstacle at their place on it, moved on by their slip.
  void hold(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles, double dt);
  /// After the step of `dt` s: lets the held points go. Those that push out of their obstacle
  /// stay touching (held in the next step): at rest while the constraint forces of the body's
  /// points held on that obstacle together stay within the friction cone, else sliding.
  /// `start_poses`: the obstacles' poses at the step's start (as for project()).
  void release(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
               const std::vector<Eigen::Isometry3d>& start_poses, const ContactSettings& settings,
               double dt);
  /// Projects the free points out of every obstacle and records them as touching; an obstacle's
  /// velocity is that of its rigid motion from `start_poses[k]` to its pose within the step, and
  /// the body's nodes at the step's start are its stepStart(). Then puts the faces that an
  /// obstacle's edges or corners press into between the points back out of it (see pushFacesOut()).
  /// Returns the number of points and such faces touching an obstacle.
  int project(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
              const std::vector<Eigen::Isometry3d>& start_poses, const ContactSettings& settings,
              double dt);
  /// Per obstacle (as given to project()), what the body felt from it in the last step.
  const std::vector<ContactLoad>& obstacleContacts() const { return contacts_; }
  /// The obstacles were replaced by others: no point touches any.
  void forget();

 private:
  /// A point that touches obstacles: a node (one, weight 1) or a vertex of an embedded surface
  /// (the nodes of its cell that carry weight).
  struct Point {
    std::array<int, 8> nodes{};
    std::array<double, 8> weights{};
    int count = 0;
  };
  /// A body's held points on one obstacle, judged together by Coulomb's law.
  struct Patch {
    double pushing = 0.0, mass = 0.0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< the normals weighed by the push
    Eigen::Vector3d sliding = Eigen::Vector3d::Zero();   ///< tangential constraint force, N
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero();  ///< of the held points' slip
    Eigen::Vector3d friction = Eigen::Vector3d::Zero();  ///< sliding: what the obstacle exerts
    bool slides = false;                                 ///< in the step
    bool sticks = true;                                  ///< at rest on it after the step
    /// Adds a hold's constraint force r on the body, with the obstacle's normal n there and the
    /// mass it holds, if it pushes; whether it did.
    bool add(const Eigen::Vector3d& r, const Eigen::Vector3d& n, double held_mass) {
      const double push = r.dot(n);
      if (!(push > 0.0)) return false;
      pushing += push;
      normal += push * n;
      sliding += r - push * n;
      mass += held_mass;
      return true;
    }
  };

  /// Sizes the per-point state for points_ (allocates).
  void resizePoints();
  /// Sums the held points' constraint forces per obstacle and judges each patch.
  void judgePatches(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                    const ContactSettings& settings, double dt);
  /// Point p's part of a state of the body's nodes (3n): its position or velocity.
  Eigen::Vector3d weighted(const Eigen::VectorXd& state, int p) const;
  /// The weight of point p on nodes free to move.
  double freeWeight(const FiniteElementBody& body, int p) const;
  /// Whether point p can be moved: a free node, or a vertex with at least kMovable of its
  /// weight on free nodes.
  bool movable(const FiniteElementBody& body, int p) const;
  /// Changes of a body's nodes that its vertices ask for (positions or velocities), granted
  /// together; sized once.
  struct Requests {
    explicit Requests(int num_nodes);
    std::vector<double> weight;
    std::vector<Eigen::Vector3d> sum;
    std::vector<int> touched;
  };
  /// Vertex p asks that it change by `change`: its free nodes alike.
  void request(const FiniteElementBody& body, int p, const Eigen::Vector3d& change,
               Requests& requests) const;
  /// Changes each node asked by the weighted mean of what it was asked, and clears the asks.
  void grant(Requests& requests, Eigen::VectorXd& state) const;
  /// Grants the velocity asks from obstacle k, adding the forces they take to its load.
  void grantVelocities(FiniteElementBody& body, int k, double dt);
  /// Judges each patch sliding or not, and what the body gains from those that slide.
  void decideSlides(const FiniteElementBody& body, const ContactSettings& settings, double dt);
  /// The velocity change that the obstacle gives point p as it lands (its velocity into it
  /// removed, its sliding slowed by friction; zero when it rests or leaves); it is held from then
  /// on, sliding at what is left.
  Eigen::Vector3d landingChange(const FiniteElementBody& body, int p,
                                const Eigen::Vector3d& obstacle_velocity,
                                const Eigen::Vector3d& normal, const ContactSettings& settings);
  /// Puts point p, found at x inside its obstacle, at `on_surface` and changes its velocity by
  /// `change` (a vertex: asks it of its nodes), adding the force that takes to the load.
  void putBack(FiniteElementBody& body, int p, const Eigen::Vector3d& x,
               const Eigen::Vector3d& on_surface, const Eigen::Vector3d& change, double dt);
  /// A point found inside `shape` (at `now`, in its frame; nearest surface point and normal
  /// there) that was outside at the step's start (the body's nodes then: `start`) and whose
  /// nearest face is not the one it came in through (it crossed more than half of a thin table)
  /// goes back by that face: `surface` and `normal` become the entry's.
  void enterThroughItsFace(const Shape& shape, const Eigen::Isometry3d& to_start_shape,
                           const Eigen::VectorXd& start, int p, const Eigen::Vector3d& now,
                           Eigen::Vector3d& surface, Eigen::Vector3d& normal) const;
  /// Puts the points of obstacle k that are still inside (their cells share nodes) back out.
  void settleEmbedded(FiniteElementBody& body, const PlacedShape& obstacle, int k);
  /// Where each node of a touching point is in its obstacle's frame: it is held there.
  void recordNodePlaces(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles);
  void resizeForObstacles(size_t count);
  void addForce(int k, const Eigen::Vector3d& at, const Eigen::Vector3d& force);
  Eigen::Vector3d worldNormal(const std::vector<PlacedShape>& obstacles, int p) const;

  /// The velocity at x of the obstacle, moving rigidly from `start_pose` to its pose in the
  /// step of dt.
  static Eigen::Vector3d obstacleVelocity(const PlacedShape& obstacle,
                                          const Eigen::Isometry3d& start_pose,
                                          const Eigen::Vector3d& x, double dt);
  /// A point at x moving at `velocity`: its slip on the obstacle, along the plane of normal n.
  static Eigen::Vector3d slipOn(const PlacedShape& obstacle, const Eigen::Isometry3d& start_pose,
                                const Eigen::Vector3d& x, const Eigen::Vector3d& velocity,
                                const Eigen::Vector3d& n, double dt);
  /// Whether `friction` (zero: none yet) stopped or turned `slip`: then it sticks from now on.
  static bool frictionStopped(const Eigen::Vector3d& friction, const Eigen::Vector3d& slip);
  /// Sliding points go on planes: a body that touches several obstacles or faces, or is held
  /// otherwise.
  bool slidesOnPlanes() const { return !whole_; }
  /// Whether the body touches one face of one obstacle alone (its points' normals on it agree),
  /// nothing else holding it: a slip's correction then moves it whole.
  bool takenWhole(const FiniteElementBody& body) const;
  /// Holds sliding point p's free nodes on its obstacle's plane for the next step, with its
  /// friction (and excess) spread over them by its weights.
  void holdOnPlane(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles, int p);
  /// Releases the nodes held in the step and gives the body its kick.
  void letGo(FiniteElementBody& body);
  /// Counts the touching points, per obstacle too, with their centre; returns them all.
  int countTouching(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles);
  /// After a step on its plane: point p lets go, sticks, or slides on against friction.
  void judgeOnPlane(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                    const std::vector<Eigen::Isometry3d>& start_poses,
                    const ContactSettings& settings, double dt, int p);
  /// A sliding point goes on its plane for the next step, with `friction` (and, found sliding
  /// while held, what it exerted beyond that: `excess`).
  void slideOnPlane(int p, const Eigen::Vector3d& friction,
                    const Eigen::Vector3d& excess = Eigen::Vector3d::Zero());
  /// How a point is held in the present step (point_held_): at its place, or on its plane.
  static constexpr std::uint8_t kInPlace = 1, kOnItsPlane = 2;
  /// How far off its obstacle a point on its plane may end a step and touch on (it slid past an
  /// edge otherwise), m.
  static constexpr double kOffItsFace = 1e-4;
  /// Passes over a body's touching vertices (or faces) on one obstacle: their cells share nodes,
  /// so putting one back moves its neighbours.
  static constexpr int kEmbeddedPasses = 8;
  /// How far inside an obstacle a point put on its surface may be found again (round-off), m.
  static constexpr double kOnTheSurface = 1e-9;
  /// A landed point slipping slower than this along its obstacle is at rest on it, m/s.
  static constexpr double kAtRest = 1e-6;
  /// Points whose normals on an obstacle agree to this cosine touch one face of it.
  static constexpr double kOneFace = 0.99;

  /// A vertex lying mostly on held nodes counts as held: moving it by the rest would take shifts
  /// of 1 / free weight times what it needs.
  static constexpr double kMovable = 0.2;

  // Edges and corners of box and mesh obstacles against the body's faces (obstacle_features.cpp):
  // an obstacle pressed edge first into a face between its points is unseen by the points. Such a
  // face is moved out of the box the least way, or out of a mesh along its own normal as deep as
  // the mesh's triangles reach behind it within its outline (core/geometry/triangle_separation.h;
  // a mesh only while none of the body's points touches it), its way into it stopped, and its
  // nodes held on planes of that direction, moving with the obstacle, in the next step. With
  // friction, a node whose slip on its plane friction stopped or turned is held in its place on
  // the obstacle; the forces of such holds join the obstacle's patch (judgePatches(): with the
  // body's points on a box; a mesh that points touch is left to them), which sticks or slides as
  // one; sliding, the nodes go on their planes with their shares of friction, as the points do.
  // Let go when their springs pull.

  /// After the points' projection: puts the faces that box and mesh obstacles press into back
  /// out, and records the faces touching them and the nodes to hold next step.
  void pushFacesOut(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                    const std::vector<Eigen::Isometry3d>& start_poses, double dt);
  /// Moves the faces that obstacle k presses into out of it, in passes (faces share nodes);
  /// face_pressed_ marks them.
  void separateFaces(FiniteElementBody& body, const PlacedShape& obstacle,
                     const Eigen::Isometry3d& to_obstacle, int k);
  /// How far face t must move to leave the obstacle (a box or a mesh; `to_obstacle` the inverse
  /// of its pose), and which way, from where its points are now.
  TriangleSeparation separateFace(const PlacedShape& obstacle, const Eigen::Isometry3d& to_obstacle,
                                  int t);
  /// Whether any of the body's points touches obstacle k.
  bool pointsTouch(int k) const;
  /// Whether face t is one for obstacle k's features: all its points movable, none touching it
  /// (the points' own contact holds those), and near it.
  bool faceForFeatures(const FiniteElementBody& body, int t, int k,
                       const Eigen::AlignedBox3d& near) const;
  /// Face t touches obstacle k after the step: it was pressed into it, or it was held against it in
  /// the step, pushed, and is still within kOffItsFace.
  bool faceTouches(int t, int k, double depth) const;
  /// Stops face t's way into obstacle k and records its nodes to hold against it, pushing along
  /// `direction`: a node new to it starts on its plane, without friction for the step.
  void touchFace(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                 const std::vector<Eigen::Isometry3d>& start_poses, int t, int k,
                 const Eigen::Vector3d& direction, double dt);
  /// Holds the recorded nodes for the step, in place or on their planes with friction (those held
  /// otherwise excepted).
  void holdFaceNodes(FiniteElementBody& body, const std::vector<PlacedShape>& obstacles);
  /// Adds the pushes and tangential forces of the face nodes held in place to their patches.
  void addFaceNodesToPatches(const FiniteElementBody& body,
                             const std::vector<PlacedShape>& obstacles);
  /// After the patches are judged: each held node's push and friction, added to its obstacle's
  /// load, and whether it sticks or slides in the next step.
  void judgeFaceNodes(const FiniteElementBody& body, const std::vector<PlacedShape>& obstacles,
                      const std::vector<Eigen::Isometry3d>& start_poses,
                      const ContactSettings& settings, double dt);
  /// Face node i, held on its plane in the step: sticks again when friction stopped or turned its
  /// slip, else slides on against it.
  void judgeFaceNodeOnPlane(const FiniteElementBody& body,
                            const std::vector<PlacedShape>& obstacles,
                            const std::vector<Eigen::Isometry3d>& start_poses,
                            const ContactSettings& settings, double dt, int i);

  /// Where each point is now, into point_x_ (after each correction).
  void placePoints(const FiniteElementBody& body);
  std::vector<Eigen::Vector3d> point_x_;    ///< per point: where it is, for the faces
  std::vector<Eigen::Vector3i> faces_;      ///< the body's surface triangles, over its points
  std::vector<std::uint8_t> face_pressed_;  ///< per face: pressed into an obstacle in this step
  struct FaceTouch {
    int face = 0, obstacle = 0;
  };
  std::vector<FaceTouch>
      face_touches_;  ///< faces touching an obstacle after the step; reserved once
  // Per node.
  std::vector<int> face_obstacle_;  ///< the obstacle a face holds it against next step, -1: none
  std::vector<Eigen::Vector3d> face_normal_;      ///< the plane's normal, in the obstacle's frame
  std::vector<Eigen::Vector3d> face_place_;       ///< a point of the plane, in the obstacle's frame
  std::vector<int> face_nodes_;                   ///< the nodes with a face_obstacle_
  std::vector<int> face_held_;                    ///< those held in the present step
  std::vector<std::uint8_t> face_sticks_;         ///< held in place next step (else on its plane)
  std::vector<std::uint8_t> face_held_in_place_;  ///< held in place in the present step
  std::vector<Eigen::Vector3d> face_friction_;    ///< sliding: friction's force on it, N
  /// Found sliding while held in place: what it held beyond friction, taken back in the next step.
  std::vector<Eigen::Vector3d> face_excess_;
  std::vector<int> pushed_by_;       ///< after the step: the obstacle it was held against, -1: none
  std::vector<double> face_push_;    ///< that hold's push, N (negative: it pulled)
  std::vector<int> near_triangles_;  ///< a mesh's triangles near a face, looked at; room reused

  std::vector<Point> points_;
  bool embedded_ = false;
  // Per point.
  std::vector<int> obstacle_;             ///< the obstacle point p touches, -1: none
  std::vector<Eigen::Vector3d> point_;    ///< its place on the obstacle, in the obstacle's frame
  std::vector<Eigen::Vector3d> normal_;   ///< outward normal there, in the obstacle's frame
  std::vector<std::uint8_t> holds_;       ///< touching: held in the next step
  std::vector<Eigen::Vector3d> slip_;     ///< its velocity along the obstacle, relative to it
  std::vector<std::uint8_t> point_held_;  ///< held in the present step: 0, kInPlace or kOnItsPlane
  /// Sliding on an obstacle, a point of a body that touches several (or is held otherwise) is
  /// held on the obstacle's plane only in the next step, with friction as a force.
  std::vector<std::uint8_t> on_plane_;
  std::vector<Eigen::Vector3d> friction_;  ///< that force, N (zero the step it landed)
  /// What the point's patch, held in the step it was found sliding, exerted beyond friction: the
  /// next step takes it back (a force against it), through the body's own solve.
  std::vector<Eigen::Vector3d> excess_;
  std::vector<Eigen::Vector3d> point_force_;  ///< its share of its nodes' constraint forces
  // Per node.
  std::vector<int> node_obstacle_;           ///< the obstacle its place was recorded on
  std::vector<Eigen::Vector3d> node_place_;  ///< that place, in the obstacle's frame
  std::vector<int> held_;                    ///< nodes held in the present step
  std::vector<std::uint8_t> held_flag_;      ///< the same, per node
  std::vector<double> held_weight_;          ///< sum of the weights of the points holding it
  std::vector<std::uint8_t> on_plane_node_;  ///< held on a plane in the present step
  std::vector<double> plane_weight_;         ///< sum of the weights of the points holding it so
  std::vector<int> plane_nodes_;             ///< nodes held on planes in the present step
  std::vector<ContactLoad> contacts_;
  std::vector<Patch> patches_;
  std::vector<Eigen::Isometry3d>
      to_shape_;  ///< per obstacle: world to its frame, at the step's end
  Eigen::Vector3d kick_ = Eigen::Vector3d::Zero();  ///< velocity the whole body gains, m/s
  /// The body's centre, after the solve, when a patch of a body taken whole slides, m/s
  Eigen::Vector3d centre_velocity_ = Eigen::Vector3d::Zero();
  /// One face of one obstacle alone touches the body, and nothing else holds it: a slip's
  /// correction moves it whole.
  bool whole_ = true;
  Requests position_requests_, velocity_requests_;
};

}  // namespace deformable_sim::core
