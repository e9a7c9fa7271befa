#include "deformable_sim/perf/bullet_peer.h"

// Bullet's headers instantiate btModifiedGramSchmidt here, in which GCC sees a vector that may be
// uninitialized where Bullet fills it (depending on what GCC inlines into this file).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableCorotatedForce.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableLinearElasticityForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#pragma GCC diagnostic pop

#include <stdexcept>

#include "deformable_sim/core/elements/material.h"
#include "deformable_sim/core/elements/mesh.h"

#ifndef BT_USE_DOUBLE_PRECISION
#error "the peer is built against Bullet's double-precision (-float64) libraries"
#endif

namespace deformable_sim::perf {
namespace {

// Bullet keeps its CG and Newton limits protected; a subclass is the only way to set them.
class PeerSolver : public btDeformableBodySolver {
 public:
  void setLimits(const BulletPeerSettings& settings, double cg_tolerance) {
    m_cg.setTolerance(cg_tolerance);
    m_cg.m_maxIterations = settings.cg_max_iterations;
    m_maxNewtonIterations = settings.max_newton_iterations;
    m_newtonTolerance = settings.newton_tolerance;
  }
};

// Counts CG work without touching Bullet's solver: btConjugateGradient::solve preconditions its
// first direction p once, the initial residual r once, then r once per iteration, always in its own
// member vectors. A call on the vector seen first (p) therefore starts a solve, and
// iterations = calls - 2 per solve.
class CountingMassPreconditioner : public MassPreconditioner {
 public:
  explicit CountingMassPreconditioner(const btAlignedObjectArray<btSoftBody*>& bodies)
      : MassPreconditioner(bodies) {}

  void operator()(const TVStack& x, TVStack& b) override {
    if (first_ == nullptr) first_ = &x;
    if (&x == first_) ++solves;
    ++calls;
    MassPreconditioner::operator()(x, b);
  }

  long solves = 0;
  long calls = 0;

 private:
  const TVStack* first_ = nullptr;
};

btVector3 toBullet(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d fromBullet(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

}  // namespace

struct BulletPeer::World {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  PeerSolver solver;
  btDeformableMultiBodyConstraintSolver constraint_solver;
  std::unique_ptr<btDeformableMultiBodyDynamicsWorld> world;
  std::unique_ptr<btSoftBody> body;
  std::unique_ptr<btDeformableLagrangianForce> elasticity;
  std::unique_ptr<btDeformableGravityForce> gravity;
  CountingMassPreconditioner* counter = nullptr;  // owned by the solver's objective
  std::vector<double> lumped;                     // kg per node, clamped nodes included
  int tetrahedra = 0;
  double h = 0.0;  // Bullet's step, s
  int substeps = 1;
  double mass_damping = 0.0;

  ~World() {
    if (world && body) world->removeSoftBody(body.get());
  }

  void createWorld(const btVector3& g);
  void addBody(const Cantilever& cantilever);
  void addForces(const Cantilever& cantilever, const BulletPeerSettings& settings,
                 const btVector3& g);
  void countPreconditionerCalls();
};

void BulletPeer::World::createWorld(const btVector3& g) {
  constraint_solver.setDeformableSolver(&solver);
  world = std::make_unique<btDeformableMultiBodyDynamicsWorld>(
      &dispatcher, &broadphase, &constraint_solver, &configuration, &solver);
  world->setGravity(g);
  world->getWorldInfo().m_gravity = g;
  // The world hands these to the solver at every step (its own setImplicit would be overwritten).
  world->setImplicit(true);
  world->setLineSearch(false);
  world->setUseProjection(true);  // zero-inverse-mass nodes are projected out of the solve
  solver.setImplicit(true);
}

void BulletPeer::World::addBody(const Cantilever& cantilever) {
  const core::Mesh& mesh = cantilever.mesh;
  // Lumped masses exactly as the core computes them (rho V / 4 per corner); Bullet's density
  // helpers would give four times that. A clamped node gets zero inverse mass.
  lumped = core::lumpedMasses(mesh, cantilever.material.density);
  std::vector<btVector3> x(mesh.numNodes());
  std::vector<btScalar> m(lumped.begin(), lumped.end());
  for (int i = 0; i < mesh.numNodes(); ++i) x[i] = toBullet(mesh.positions[i]);
  for (int i : cantilever.clamped) m[i] = 0.0;  // btSoftBody reads mass 0 as inverse mass 0
  body = std::make_unique<btSoftBody>(&world->getWorldInfo(), mesh.numNodes(), x.data(), m.data());
  for (const core::Tetrahedron& t : mesh.tetrahedra) body->appendTetra(t[0], t[1], t[2], t[3]);
  body->initializeDmInverse();  // rest shape matrices and volumes of the tetrahedra
  // Per-tetrahedron deformation scratch; Bullet fills it before use (GCC cannot see that).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
  body->m_tetraScratches.resize(body->m_tetras.size());
  body->m_tetraScratchesTn.resize(body->m_tetras.size());
#pragma GCC diagnostic pop
  // Nothing to collide with: no collision work beyond what the world always does.
  body->m_cfg.collisions = 0;
  body->setSelfCollision(false);
  body->setActivationState(DISABLE_DEACTIVATION);  // a settling body must not fall asleep
  world->addSoftBody(body.get());
}

void BulletPeer::World::addForces(const Cantilever& cantilever, const BulletPeerSettings& settings,
                                  const btVector3& g) {
  const double mu = core::lameMu(cantilever.material);
  const double lambda = core::lameLambda(cantilever.material);
  if (settings.elasticity == BulletElasticity::kCorotatedForce) {
    elasticity = std::make_unique<btDeformableCorotatedForce>(mu, lambda);
  } else {
    // Its default damping (0.01 on both terms) is off: the cantilever has none.
    elasticity = std::make_unique<btDeformableLinearElasticityForce>(mu, lambda, 0.0, 0.0);
  }
  world->addForce(body.get(), elasticity.get());
  gravity = std::make_unique<btDeformableGravityForce>(g);
  world->addForce(body.get(), gravity.get());
}

void BulletPeer::World::countPreconditionerCalls() {
  btDeformableBackwardEulerObjective& objective = *solver.m_objective;
  counter = new CountingMassPreconditioner(objective.m_softBodies);
  delete objective.m_massPreconditioner;
  objective.m_massPreconditioner = counter;
  objective.m_preconditioner = counter;
}

BulletPeer::BulletPeer(const Cantilever& cantilever, const BulletPeerSettings& settings)
    : world_(std::make_unique<World>()) {
  World& w = *world_;
  if (settings.substeps < 1) throw std::invalid_argument("BulletPeer: substeps must be >= 1");
  w.substeps = settings.substeps;
  w.h = cantilever.dt / settings.substeps;
  w.mass_damping = settings.mass_damping;
  w.tetrahedra = cantilever.mesh.numTetrahedra();
  const btVector3 g = toBullet(cantilever.effects.gravity.value_or(Eigen::Vector3d::Zero()));
  w.createWorld(g);
  w.addBody(cantilever);
  w.addForces(cantilever, settings, g);
  // The core stops at |r| <= tol |b|; Bullet at r.z <= tol_b min(1, b.z0) with z the
  // preconditioned residual. Bullet 3.24 never initializes its mass preconditioner (it acts as the
  // identity, z = r), so tol_b = tol^2 is the core's test whenever |b| <= 1 (it is here).
  const double tol = cantilever.solver.tolerance;
  w.solver.setLimits(settings, settings.cg_tolerance >= 0.0 ? settings.cg_tolerance : tol * tol);
  w.countPreconditionerCalls();
}

BulletPeer::~BulletPeer() = default;

BulletStepReport BulletPeer::step() {
  World& w = *world_;
  const long solves = w.counter->solves;
  const long calls = w.counter->calls;
  for (int s = 0; s < w.substeps; ++s) {
    w.world->stepSimulation(w.h, 0);  // maxSubSteps 0: exactly one step of h
    if (w.mass_damping > 0.0) {
      const double keep = 1.0 - w.mass_damping * w.h;
      for (int i = 0; i < w.body->m_nodes.size(); ++i) {
        btSoftBody::Node& n = w.body->m_nodes[i];
        n.m_v *= keep;
        n.m_vn = n.m_v;  // the implicit step starts from m_vn
      }
    }
  }
  BulletStepReport report;
  report.newton_iterations = static_cast<int>(w.counter->solves - solves);
  report.cg_iterations =
      static_cast<int>((w.counter->calls - calls) - 2 * (w.counter->solves - solves));
  return report;
}

int BulletPeer::numNodes() const { return world_->body->m_nodes.size(); }
int BulletPeer::numTetrahedra() const { return world_->tetrahedra; }

Eigen::Vector3d BulletPeer::position(int node) const {
  return fromBullet(world_->body->m_nodes[node].m_x);
}

Eigen::Vector3d BulletPeer::velocity(int node) const {
  return fromBullet(world_->body->m_nodes[node].m_v);
}

double BulletPeer::mass(int node) const {
  const btScalar im = world_->body->m_nodes[node].m_im;
  return im > 0.0 ? 1.0 / im : 0.0;
}

double BulletPeer::builtMass() const {
  double sum = 0.0;
  for (int i = 0; i < numNodes(); ++i) sum += mass(i) > 0.0 ? mass(i) : world_->lumped[i];
  return sum;
}

Eigen::Vector3d BulletPeer::meanPosition(const std::vector<int>& nodes) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i : nodes) sum += position(i);
  return sum / static_cast<double>(nodes.size());
}

}  // namespace deformable_sim::perf
