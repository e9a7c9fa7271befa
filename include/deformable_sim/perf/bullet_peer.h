// The performance benchmark's cantilever (perf/cantilever.h) in Bullet's deformable solver: the
// same tetrahedra, nodes, material, step, clamp and lumped masses, stepped by
// btDeformableMultiBodyDynamicsWorld with implicit integration and projected (fixed) clamp nodes.
// Written against Bullet 3.24 (Debian 12), whose behaviour the comments below describe.
// Bullet stays behind this interface (its headers need BT_USE_DOUBLE_PRECISION to match the
// library), so only deformable_sim_bullet_peer links it.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "deformable_sim/perf/cantilever.h"

namespace deformable_sim::perf {

/// Which of Bullet's elastic forces carries the material (mu, lambda from E, nu). Their names
/// mislead: the one that matches the core's warped stiffness is the "linear elasticity" force.
enum class BulletElasticity {
  /// btDeformableLinearElasticityForce (damping off): linear elasticity in each tetrahedron's
  /// rotated frame, f = R P(R^T F) with R from an approximate polar decomposition, and its
  /// differential with R held, so the implicit step's CG solves with R K R^T: the core's model
  /// and scheme.
  kLinearElasticityForce,
  /// btDeformableCorotatedForce: P = 2 mu (F - R) + lambda (J - 1) J F^-T ("fixed corotated",
  /// hyperelastic). Bullet 3.24 gives it no force differential, so even the implicit step treats
  /// its elasticity explicitly: stable only for steps far below the cantilever's 0.01 s.
  kCorotatedForce,
};

struct BulletPeerSettings {
  BulletElasticity elasticity = BulletElasticity::kLinearElasticityForce;
  int substeps = 1;  ///< Bullet steps per cantilever.dt
  /// Newton iterations per Bullet step (Bullet's default 5). Bullet's stopping test includes the
  /// clamped nodes' unbalanced force, so with a clamp it always takes them all.
  int max_newton_iterations = 5;
  double newton_tolerance = 1e-4;  ///< Bullet's default: norm of the momentum residual, N s
  double cg_tolerance = -1.0;      ///< < 0: the cantilever's relative tolerance, squared
  int cg_max_iterations = 1000;    ///< the cantilever's cap
  double mass_damping = 0.0;       ///< 1/s: v *= 1 - mass_damping h after each Bullet step
};

struct BulletStepReport {
  int newton_iterations = 0;  ///< CG solves (one per Newton iteration), all Bullet steps
  int cg_iterations = 0;      ///< CG iterations over all of them
};

class BulletPeer {
 public:
  BulletPeer(const Cantilever& cantilever, const BulletPeerSettings& settings = {});
  ~BulletPeer();
  BulletPeer(const BulletPeer&) = delete;
  BulletPeer& operator=(const BulletPeer&) = delete;

  /// Advances by cantilever.dt (settings.substeps Bullet steps).
  BulletStepReport step();

  int numNodes() const;
  int numTetrahedra() const;
  Eigen::Vector3d position(int node) const;  ///< m, node numbering of the cantilever's mesh
  Eigen::Vector3d velocity(int node) const;  ///< m/s
  double mass(int node) const;               ///< kg; 0 for a clamped node (infinite mass)
  /// Sum of the lumped masses as built (clamped nodes included), kg.
  double builtMass() const;
  /// Mean position of the given nodes, m.
  Eigen::Vector3d meanPosition(const std::vector<int>& nodes) const;

 private:
  struct World;
  std::unique_ptr<World> world_;
};

}  // namespace deformable_sim::perf
