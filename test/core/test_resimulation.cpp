// Re-simulation of a session's log, without ROS: a log recorded by a Session's listener, with the
// states it went through, is run again and compared step by step.
#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <variant>

#include "deformable_sim/core/elements/box_mesh.h"
#include "deformable_sim/core/session/resimulation.h"
#include "deformable_sim/core/session/session.h"
#include "scene_builder.h"

namespace dc = deformable_sim::core;

namespace {

dc::SceneSpec blockScene() {
  return deformable_sim::test::SceneBuilder().dt(0.01).gravity(9.81).damping(2.0, 0.0).box(
      "block", {0, 0, 0}, {0.1, 0.1, 0.1}, {2, 2, 2}, {5.0e4, 0.3, 200.0});
}

std::vector<dc::Mesh> blockMeshes() {
  const dc::BoxMeshSpec box = *blockScene().bodies[0].box_mesh;
  return {dc::makeBoxMesh(box.min, box.max, box.cells)};
}

// A session that records its own log (through its listener) and its states after every step.
class SessionUnderRecord {
 public:
  SessionUnderRecord() : session_(blockScene(), blockMeshes()) {
    session_.setListener([this](const dc::AppliedCommand& c) { recording_.log.push_back(c); });
  }
  void record() {
    for (const dc::Body& body : session_.simulation().bodies()) {
      const dc::RecordedStateKey key{session_.episode(), session_.simulation().stepCount(),
                                     body.name()};
      recording_.states.emplace(key, dc::RecordedState{body.positions(), body.velocities()});
    }
  }
  void run(int steps) {
    for (int k = 0; k < steps; ++k) {
      session_.step(reports_);
      record();
    }
  }
  void apply(const dc::SessionCommand& command) {
    session_.apply(command);
    if (std::holds_alternative<dc::ResetCommand>(command)) record();
  }
  dc::Recording& recording() { return recording_; }

 private:
  dc::Session session_;
  dc::Recording recording_;
  std::vector<dc::StepReport> reports_;
};

dc::WrenchCommand push(double force_x) {
  dc::WrenchCommand wrench;
  wrench.source = "push";
  wrench.body = "block";
  wrench.nodes.whole_body = true;
  wrench.force = Eigen::Vector3d(force_x, 0.0, 0.0);
  return wrench;
}

// The nodes below the block's rest bottom face.
dc::FixCommand fixBottom() {
  dc::FixCommand fix;
  fix.body = "block";
  fix.nodes.box = dc::Box{{-1.0, -1.0, -1.0}, {1.0, 1.0, 0.001}};  // the block falls
  return fix;
}

dc::TuneCommand soften() {
  dc::TuneCommand tune;
  tune.material = dc::LinearElasticMaterial{2.0e4, 0.3, 200.0};
  return tune;
}

// Episode 0 from the start: a push, fixed bottom, softer material, then let go of the push.
void recordSession(SessionUnderRecord& recorded) {
  recorded.record();
  recorded.apply(push(0.5));
  recorded.run(10);
  recorded.apply(fixBottom());
  recorded.run(10);
  recorded.apply(soften());
  recorded.run(5);
  recorded.apply(dc::ClearWrenchCommand{"push"});
  recorded.run(10);  // states after the last command are compared too
}

dc::ResimulationReport resimulate(dc::Recording recording, dc::SolverOverride solver = {}) {
  dc::Resimulation resimulation(blockScene(), blockMeshes(), std::move(recording), solver);
  return resimulation.run();
}

}  // namespace

TEST(Resimulation, ARecordedLogIsReSimulatedBitForBit) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  const dc::Recording& recording = recorded.recording();
  dc::Resimulation resimulation(blockScene(), blockMeshes(), recording);
  EXPECT_EQ(resimulation.plannedSteps(), 35);
  long observed = 0;
  const dc::ResimulationReport report = resimulation.run([&](const dc::ComparedState& state) {
    ++observed;
    EXPECT_EQ(state.simulation.stepCount(), state.step);
    EXPECT_EQ(state.position_difference, 0.0);
  });
  EXPECT_EQ(report.steps, 35);
  EXPECT_DOUBLE_EQ(report.simulated_time, 0.35);
  EXPECT_EQ(report.compared_states, static_cast<long>(recording.states.size()));
  EXPECT_EQ(observed, report.compared_states);
  EXPECT_EQ(report.max_position_difference, 0.0);
  EXPECT_EQ(report.max_velocity_difference, 0.0);
  EXPECT_EQ(report.first_difference_step, -1);
  EXPECT_EQ(report.refused_commands, 0);
  EXPECT_GT(report.solver_iterations, 0);
  EXPECT_THROW(resimulation.run(), std::logic_error);  // its session is at the end
}

TEST(Resimulation, OtherSolverLimitsGiveAnotherResultFromWhereTheyMatter) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  const dc::ResimulationReport report = resimulate(recorded.recording(), {1.0e-1, 1});
  EXPECT_GT(report.max_position_difference, 0.0);
  EXPECT_GT(report.max_velocity_difference, 0.0);
  EXPECT_EQ(report.first_difference_episode, 0);
  EXPECT_GE(report.first_difference_step, 1);  // the initial state is the scene's
  EXPECT_EQ(report.compared_states, static_cast<long>(recorded.recording().states.size()));
}

TEST(Resimulation, ALogMissingACommandDiffersFromTheStepAfterIt) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  dc::Recording recording = recorded.recording();
  ASSERT_TRUE(std::holds_alternative<dc::TuneCommand>(recording.log[2].command));
  ASSERT_EQ(recording.log[2].step, 20);
  recording.log.erase(recording.log.begin() + 2);
  const dc::ResimulationReport report = resimulate(recording);
  EXPECT_EQ(report.first_difference_episode, 0);
  EXPECT_EQ(report.first_difference_step, 21);
  EXPECT_GT(report.max_position_difference, 0.0);
}

TEST(Resimulation, ALogThatStartsAtAResetIsReSimulatedFromThere) {
  SessionUnderRecord recorded;
  recorded.apply(push(0.5));
  recorded.run(5);
  // The recording starts here, in the middle of episode 0.
  recorded.recording() = dc::Recording{};
  recorded.apply(fixBottom());  // before the reset: not re-simulated
  recorded.run(3);
  const std::size_t before_reset = recorded.recording().states.size();
  recorded.apply(dc::ResetCommand{});
  recorded.apply(push(-0.3));
  recorded.run(8);
  recorded.apply(dc::ResetCommand{});
  recorded.run(4);

  const dc::ResimulationReport report = resimulate(recorded.recording());
  EXPECT_EQ(report.steps, 12);
  EXPECT_EQ(report.compared_states,
            static_cast<long>(recorded.recording().states.size() - before_reset));
  EXPECT_EQ(report.max_position_difference, 0.0);
  EXPECT_EQ(report.max_velocity_difference, 0.0);
}

TEST(Resimulation, ALogThatStartsMidEpisodeWithoutAResetIsRefused) {
  SessionUnderRecord recorded;
  recorded.run(3);
  recorded.recording() = dc::Recording{};
  recorded.apply(push(0.5));
  recorded.run(3);
  try {
    resimulate(recorded.recording());
    FAIL() << "a log without its start was re-simulated";
  } catch (const dc::ResimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("starts at step 4 of episode 0"), std::string::npos)
        << e.what();
  }
}

TEST(Resimulation, ALogWithoutStatesStartsWhereItsCommandsDo) {
  SessionUnderRecord recorded;
  recorded.run(3);
  recorded.apply(dc::ResetCommand{});
  recorded.run(2);
  recorded.recording() = dc::Recording{};  // from here on, in episode 1
  recorded.apply(dc::ResetCommand{});
  recorded.apply(push(0.5));
  recorded.run(6);
  recorded.apply(dc::ClearWrenchCommand{"push"});
  dc::Recording commands_only = recorded.recording();
  commands_only.states.clear();
  const dc::ResimulationReport report = resimulate(commands_only);
  EXPECT_EQ(report.steps, 6);
  EXPECT_EQ(report.refused_commands, 0);
  EXPECT_EQ(report.compared_states, 0);
}

TEST(Resimulation, AnOutOfOrderLogIsAnError) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  dc::Recording recording = recorded.recording();
  std::swap(recording.log[1], recording.log[2]);  // the fix (step 10) before the tune (step 20)
  EXPECT_THROW(resimulate(recording), dc::ResimulationError);

  // A command of an episode that has not begun.
  recording = recorded.recording();
  recording.log[1].episode = 1;
  EXPECT_THROW(resimulate(recording), dc::ResimulationError);
}

TEST(Resimulation, ARecordedStateOfAnotherSizeIsAnError) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  dc::Recording recording = recorded.recording();
  dc::RecordedState& state = recording.states.begin()->second;
  state.positions.conservativeResize(state.positions.size() - 3);
  EXPECT_THROW(resimulate(recording), dc::ResimulationError);
}

TEST(Resimulation, ACommandTheReSimulationRefusesIsCounted) {
  SessionUnderRecord recorded;
  recordSession(recorded);
  dc::Recording recording = recorded.recording();
  recording.log.push_back(dc::AppliedCommand{0, 35, dc::ReleaseGraspCommand{"no such grasp"}});
  const dc::ResimulationReport report = resimulate(recording);
  EXPECT_EQ(report.refused_commands, 1);
  EXPECT_EQ(report.max_position_difference, 0.0);
}
