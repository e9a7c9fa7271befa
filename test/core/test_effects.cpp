// Only the effects a scene calls for are simulated: each effect's code counts the steps it ran,
// and an effect that is off keeps its count at zero. Effects and models are chosen per body.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "deformable_sim/core/bodies/body.h"
#include "deformable_sim/core/bodies/reduced_body.h"
#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/simulation.h"
#include "scene_builder.h"

namespace dc = deformable_sim::core;

namespace {

const dc::LinearElasticMaterial kFoam{1.0e5, 0.3, 100.0};
constexpr int kSteps = 5;

dc::Mesh bar() { return dc::makeBoxMesh({0, -0.05, -0.05}, {0.4, 0.05, 0.05}, {4, 1, 1}); }

std::vector<long> countsOf(const dc::EffectCounters& c) {
  return {c.warping, c.gravity, c.damping, c.plasticity, c.reactions};
}

// A clamped bar stepped kSteps times with `effects`.
dc::EffectCounters stepped(const dc::BodyEffects& effects, dc::BodyModel model) {
  const std::unique_ptr<dc::Body> body =
      dc::makeBody("bar", bar(), dc::BodySettings{model, kFoam, effects, dc::SolverSettings{}});
  std::vector<int> clamp;
  for (int i = 0; i < body->numNodes(); ++i) {
    if (body->mesh().positions[i].x() < 1e-9) clamp.push_back(i);
  }
  body->fixNodes(clamp);
  for (int k = 0; k < kSteps; ++k) body->step(0.01);
  return body->effectCounters();
}

dc::BodyEffects nothing() {
  dc::BodyEffects effects;
  effects.reactions = false;
  return effects;
}

TEST(Effects, EachRunsOnlyWhenEnabled) {
  for (dc::BodyModel model :
       {dc::BodyModel::kFiniteElement, dc::BodyModel::kPseudoRigid, dc::BodyModel::kRigid}) {
    const std::string name = dc::modelName(model);
    EXPECT_EQ(countsOf(stepped(nothing(), model)), std::vector<long>(5, 0)) << name;

    dc::BodyEffects warping = nothing();
    warping.warping = true;
    // A rigid body has no deformation to take the rotation out of: warping is not its effect.
    const long rotations = model == dc::BodyModel::kRigid ? 0 : kSteps;
    EXPECT_EQ(countsOf(stepped(warping, model)), (std::vector<long>{rotations, 0, 0, 0, 0}))
        << name;

    dc::BodyEffects gravity = nothing();
    gravity.gravity = Eigen::Vector3d(0, 0, -9.81);
    EXPECT_EQ(countsOf(stepped(gravity, model)), (std::vector<long>{0, kSteps, 0, 0, 0})) << name;

    dc::BodyEffects damping = nothing();
    damping.damping = dc::RayleighDamping{1.0, 0.01};
    EXPECT_EQ(countsOf(stepped(damping, model)), (std::vector<long>{0, 0, kSteps, 0, 0})) << name;

    dc::BodyEffects reactions = nothing();
    reactions.reactions = true;
    EXPECT_EQ(countsOf(stepped(reactions, model)), (std::vector<long>{0, 0, 0, 0, kSteps})) << name;
  }
  dc::BodyEffects plasticity = nothing();
  plasticity.plasticity = dc::PlasticitySettings{};
  EXPECT_EQ(countsOf(stepped(plasticity, dc::BodyModel::kFiniteElement)),
            (std::vector<long>{0, 0, 0, kSteps, 0}));
}

TEST(Effects, ContactRunsOnlyWithTheEffectAndOnFiniteElementBodies) {
  dc::SceneSpec scene;
  for (dc::BodyModel model : {dc::BodyModel::kFiniteElement, dc::BodyModel::kRigid}) {
    dc::BodySpec body;
    body.name = dc::modelName(model);
    body.model = model;
    body.box_mesh = dc::BoxMeshSpec{{0, 0, 0}, {0.1, 0.1, 0.1}, {1, 1, 1}};
    body.material = kFoam;
    scene.bodies.push_back(body);
  }
  const auto meshes = [&] {
    std::vector<dc::Mesh> m;
    for (const dc::BodySpec& b : scene.bodies) {
      m.push_back(dc::makeBoxMesh(b.box_mesh->min, b.box_mesh->max, b.box_mesh->cells));
    }
    return m;
  };
  std::vector<dc::StepReport> reports;
  dc::Simulation without(scene, meshes());
  for (int k = 0; k < kSteps; ++k) without.step(reports);
  EXPECT_EQ(without.contactSteps(), 0);

  scene.contact = dc::ContactSettings{};
  scene.obstacles.push_back(deformable_sim::test::floorBox({1, 1, 0.1}, ""));
  dc::Simulation with(scene, meshes());
  for (int k = 0; k < kSteps; ++k) with.step(reports);
  EXPECT_EQ(with.contactSteps(), kSteps);  // the finite-element body only
}

TEST(Effects, BodiesOfOneSceneHaveTheirOwnModelsAndEffects) {
  // Three blocks side by side: a finite-element one under the scene's gravity, a pseudo-rigid
  // one that turns gravity off, and a rigid one with its own damping and a lighter material.
  dc::SceneSpec scene;
  scene.effects.gravity = Eigen::Vector3d(0, 0, -9.81);
  const dc::BodyModel models[] = {dc::BodyModel::kFiniteElement, dc::BodyModel::kPseudoRigid,
                                  dc::BodyModel::kRigid};
  std::vector<dc::Mesh> meshes;
  for (int b = 0; b < 3; ++b) {
    dc::BodySpec body;
    body.name = dc::modelName(models[b]);
    body.model = models[b];
    body.material = kFoam;
    const Eigen::Vector3d offset(0.2 * b, 0, 0);
    body.box_mesh = dc::BoxMeshSpec{offset, offset + Eigen::Vector3d(0.1, 0.1, 0.1), {1, 1, 1}};
    meshes.push_back(dc::makeBoxMesh(body.box_mesh->min, body.box_mesh->max, {1, 1, 1}));
    scene.bodies.push_back(body);
  }
  scene.bodies[1].effects = scene.effects;
  scene.bodies[1].effects->gravity.reset();
  scene.bodies[2].effects = scene.effects;
  scene.bodies[2].effects->damping = dc::RayleighDamping{2.0, 0.0};
  scene.bodies[2].material.density = 50.0;
  dc::Simulation simulation(scene, meshes);
  std::vector<dc::StepReport> reports;
  for (int k = 0; k < kSteps; ++k) simulation.step(reports);
  const auto& bodies = simulation.bodies();
  ASSERT_EQ(bodies.size(), 3u);
  for (int b = 0; b < 3; ++b) EXPECT_EQ(bodies[b].settings().model, models[b]);
  EXPECT_EQ(bodies[0].effectCounters().gravity, kSteps);
  EXPECT_EQ(bodies[1].effectCounters().gravity, 0);
  EXPECT_EQ(bodies[2].effectCounters().damping, kSteps);
  EXPECT_EQ(bodies[0].effectCounters().damping, 0);
  // Falling: the free finite-element and rigid blocks; at rest: the one without gravity.
  EXPECT_LT(bodies[0].velocities()[2], -0.4);
  EXPECT_EQ(bodies[1].velocities().norm(), 0.0);
  EXPECT_NEAR(dynamic_cast<const dc::ReducedBody&>(bodies[2]).reduced().massProperties().mass,
              50.0 * 1e-3, 1e-15);
  // Implicit Euler with mass damping alpha: v_k = -g h sum_j (1 + h alpha)^-j, j = 1..k.
  double expected = 0.0;
  for (int j = 1; j <= kSteps; ++j) expected -= 9.81 * 0.01 * std::pow(1.0 + 0.01 * 2.0, -j);
  EXPECT_NEAR(bodies[2].velocities()[2], expected, 1e-12);
}

}  // namespace
