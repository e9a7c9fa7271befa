// Contact with Coulomb friction solved in contact space: n contact points, each with its frame
// (columns: the normal, out of the second body into the first, and two tangents), a friction
// coefficient μ, the relative velocity v_free it would have with no contact impulse (in its frame,
// m/s) and the Delassus operator W (how the relative velocity of point i changes per unit impulse
// at point j, m/s per N s; positive semi-definite, symmetric or nearly, 3x3 blocks, W_ij non-zero
// only where contacts i and j share a body). The impulses λ (N s, in the contacts' frames) and the
// relative velocities v = W λ + v_free meet Signorini's and Coulomb's laws:
//   λ_n >= 0,  v_n >= v_target,  λ_n (v_n - v_target) = 0       (a contact only pushes)
//   |λ_t| <= μ λ_n,  and where it slides (v_t != 0): λ_t = -μ λ_n v_t / |v_t|
// v_target is each contact's least normal velocity: 0 to stop it approaching, -gap / dt to let a
// gap close within the step, +depth / dt to push a pair out (penetration correction).
//
// Method: projected Gauss-Seidel over the contacts (Moreau 1988; Jean 1999, "The non-smooth
// contact dynamics method"), each contact in turn taking the others' impulses as they are, with
// its normal first and then its friction:
//   λ_n <- max(0, λ_n - (v_n - v_target) / W_nn)
//   λ_t <- the projection onto the disc of radius μ λ_n of  λ_t - v_t / w_t
// with w_t the larger eigenvalue of the 2x2 tangential block of W_ii. Why not the other usual
// choice, a 3x3 solve of the block then a projection onto the cone: that projection's fixed point
// is associated friction, whose sliding contacts lift off (v_n = μ |v_t|), and a Euclidean
// projection under an anisotropic W_ii gives friction that does not oppose the slip. The update
// above has as fixed points exactly the law above: the normal step is the complementarity's
// min-map, and a scalar tangential step keeps the friction opposite the slip (λ_t - v_t / w_t
// outside the disc projects onto its rim along λ_t, so v_t = -c λ_t with c >= 0). The scalars only
// set how fast it gets there; w_t >= every tangential eigenvalue keeps each step from
// overshooting.
//
// Where the sweeps stall (contacts leaning on one stiff body couple so strongly that Gauss-Seidel
// gains little a sweep: a stiff block on 9 points took more than 200), a semismooth Newton method
// (Alart & Curnier 1991; Hintermueller et al. 2002) takes over from where they got to: its
// unknowns the impulses, its equations λ = the update above, its Jacobian the update's derivative
// (by active normals and sticking or sliding tangents), solved densely over the contacts that push,
// each step shortened until the error falls. Near the answer it converges quadratically. It ends
// with every contact taking its own update, so the impulses keep to their cones however far it got;
// if it cannot go on (more pushing contacts than kMaxNewtonContacts, or at a kink of the update no
// step that lowers the error), the sweeps resume, and it tries again after as many more.
//
// Storage is reserved once (reserve()); a problem no larger than that allocates nothing. The
// sweeps and Newton's steps run in a fixed order on one thread: the same bits whatever else runs.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

namespace deformable_sim::core {

/// An orthonormal frame (columns: `normal`, then two tangents) for a contact whose unit normal
/// is `normal`; the same normal always gives the same tangents.
Eigen::Matrix3d contactFrameFor(const Eigen::Vector3d& normal);

struct ContactSolveSettings {
  int max_sweeps = 100;     ///< Gauss-Seidel sweeps at most, >= 1
  double tolerance = 1e-6;  ///< m/s: the largest velocity error (see residual) accepted
  /// Newton takes over after this many sweeps without convergence, and again after as many more
  /// each time it stalls (never if > max_sweeps).
  int sweeps_before_newton = 20;
  int max_newton_steps = 30;  ///< Newton steps at most, each time it takes over
};

struct ContactSolveReport {
  int sweeps = 0;         ///< sweeps taken
  int newton_steps = 0;   ///< Newton steps taken
  double residual = 0.0;  ///< m/s: the largest contact's error at the end (see residual())
  bool converged = false;
};

class ContactProblem {
 public:
  /// The most contacts pushing at once that Newton's dense steps take on.
  static constexpr int kMaxNewtonContacts = 64;

  /// Room for `max_contacts` contacts and `max_couplings` coupling blocks W_ij (i != j, each pair
  /// counted once), and for Newton's steps. Allocates; a problem within both sizes allocates
  /// nothing after it.
  void reserve(int max_contacts, int max_couplings);

  /// Starts a problem of `count` contacts, with no coupling and zero impulses (grows the storage
  /// if past the reserve).
  void begin(int count);
  int size() const { return static_cast<int>(frames_.size()); }
  int couplings() const { return static_cast<int>(couplings_.size()); }

  /// Contact i: its frame (see contactFrameFor), μ >= 0, its free relative velocity in that frame
  /// and its least normal velocity (m/s). Its diagonal block starts at zero.
  void setContact(int i, const Eigen::Matrix3d& frame, double friction,
                  const Eigen::Vector3d& free_velocity, double target_normal_velocity = 0.0);
  /// W_ii += block (contact frame of i); call as often as bodies take part.
  void addDiagonal(int i, const Eigen::Matrix3d& block);
  /// W_ij += block and W_ji += block^T (i != j, contact frames of i and j). A pair may be added
  /// more than once (once per body the two contacts share).
  void addCoupling(int i, int j, const Eigen::Matrix3d& block) {
    addCoupling(i, j, block, block.transpose());
  }
  /// W_ij += ij and W_ji += ji, for a body whose answers are not quite symmetric (a
  /// finite-element body's kept from steps whose matrices differed a little): the problem is then
  /// the step the bodies will take.
  void addCoupling(int i, int j, const Eigen::Matrix3d& ij, const Eigen::Matrix3d& ji);
  /// A world block (velocity of point i per impulse at point j) in the frames of i and j.
  Eigen::Matrix3d inContactFrames(int i, int j, const Eigen::Matrix3d& world_block) const;

  /// The first guess of contact i's impulse (the last step's, for a warm start); it is put inside
  /// its cone before the first sweep.
  void setImpulse(int i, const Eigen::Vector3d& impulse) { impulses_[i] = impulse; }

  /// Sweeps until every contact's velocity error is within the tolerance or the sweeps run out.
  ContactSolveReport solve(const ContactSolveSettings& settings);

  /// Contact i's frame (columns: its normal, then its tangents).
  const Eigen::Matrix3d& frame(int i) const { return frames_[i]; }
  /// Contact i's impulse (its frame, N s) and in the world.
  const Eigen::Vector3d& impulse(int i) const { return impulses_[i]; }
  Eigen::Vector3d worldImpulse(int i) const { return frames_[i] * impulses_[i]; }
  /// Contact i's relative velocity W λ + v_free after the last solve (its frame, m/s).
  const Eigen::Vector3d& velocity(int i) const { return velocities_[i]; }
  /// The largest contact's error in the law, m/s (as the natural map of the update: the velocity
  /// change one more update of it alone would make); a contact no impulse can move along its
  /// normal (W_nn = 0, both sides held) keeps a zero impulse and is left out. After solve().
  double residual();

 private:
  struct Coupling {
    int row = 0, col = 0;
    Eigen::Matrix3d block = Eigen::Matrix3d::Zero();  ///< W_row,col
    Eigen::Matrix3d back = Eigen::Matrix3d::Zero();   ///< W_col,row
  };

  /// Orders the couplings by row, both halves of each, once per solve.
  void buildRows();
  /// v_free_i + sum_j W_ij λ_j: contact i's relative velocity with the impulses as they are.
  Eigen::Vector3d velocityOf(int i) const;
  /// Puts contact i's impulse inside its cone.
  void projectIntoCone(int i);
  /// One Gauss-Seidel update of contact i; returns the velocity change it made, m/s.
  double update(int i);
  /// The impulse one update of contact i alone would give, from its velocity v; with `slopes`,
  /// also its derivatives: by the contact's own impulse (first) and by its velocity (second), both
  /// zero where it does not push.
  Eigen::Vector3d updated(int i, const Eigen::Vector3d& impulse, const Eigen::Vector3d& v,
                          std::pair<Eigen::Matrix3d, Eigen::Matrix3d>* slopes = nullptr) const;

  // Newton's method (contact_problem_newton.cpp).
  struct NewtonSystem;
  /// Newton's dense matrix and its factorization, on the heap once (a copy makes its own).
  class NewtonSpace {
   public:
    NewtonSpace();
    NewtonSpace(const NewtonSpace& other);
    NewtonSpace& operator=(const NewtonSpace& other);
    NewtonSpace(NewtonSpace&& other) noexcept;
    NewtonSpace& operator=(NewtonSpace&& other) noexcept;
    ~NewtonSpace();
    /// The system; allocates on the first call.
    NewtonSystem& get();

   private:
    std::unique_ptr<NewtonSystem> system_;
  };
  /// Newton steps from the impulses as they are, up to the settings' number; true when they
  /// converged. Leaves every impulse at its own update (in its cone).
  bool newton(const ContactSolveSettings& settings, ContactSolveReport& report);
  /// Fills next_ and slopes_ from the impulses as they are; returns the sum of the squared
  /// errors W_ii (next - λ) and their largest norm.
  std::pair<double, double> linearize();
  /// The Newton step step_ for the linearization: false when it cannot be taken.
  bool newtonStep();
  /// Every contact takes its update from the same velocities (Jacobi): into its cone.
  void takeUpdates();

  // Per contact.
  std::vector<Eigen::Matrix3d> frames_;
  std::vector<double> friction_;
  std::vector<Eigen::Vector3d> free_velocities_;
  std::vector<double> targets_;
  std::vector<Eigen::Matrix3d> diagonal_;
  std::vector<double> tangent_steps_;  ///< w_t, the larger tangential eigenvalue of W_ii
  std::vector<Eigen::Vector3d> impulses_;
  std::vector<Eigen::Vector3d> velocities_;
  std::vector<int> row_start_;  ///< per contact, its first entry in row_cols_ / row_blocks_
  // Couplings as added, then both halves of each by row.
  std::vector<Coupling> couplings_;
  std::vector<int> row_cols_;
  std::vector<Eigen::Matrix3d> row_blocks_;
  std::vector<int> fill_;  ///< per contact, entries placed so far (buildRows)
  // Newton's: per contact, its update, the update's slopes, its place among the pushing contacts
  // (-1: not pushing), the step, and the impulses before it.
  std::vector<Eigen::Vector3d> next_;
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Matrix3d>> slopes_;
  std::vector<int> slot_;
  std::vector<Eigen::Vector3d> step_, before_step_;
  NewtonSpace newton_space_;
};

}  // namespace deformable_sim::core
