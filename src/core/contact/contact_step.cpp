#include "deformable_sim/core/contact/contact_step.h"

#include <algorithm>

#include "deformable_sim/core/base/parallel_for.h"
#include "deformable_sim/core/base/wall_clock.h"

namespace deformable_sim::core {

ContactStep::ContactStep(BodyList& bodies, const ContactSettings& settings) : settings_(settings) {
  states_.resize(bodies.size());
  addBodyContact(bodies);
  std::vector<bool> finite_elements;
  for (const Body& body : bodies) finite_elements.push_back(body.finiteElements() != nullptr);
  if (settings.one_problem) {
    impulses_.emplace(bodies, settings, finite_elements, body_contact_.get());
  } else {
    for (size_t b = 0; b < bodies.size(); ++b) {
      if (finite_elements[b]) states_[b].emplace(bodies[b].mesh());
    }
  }
}

void ContactStep::addBodyContact(BodyList& bodies) {
  if (!settings_.bodies && !settings_.self) return;
  std::vector<bool> with_bodies, with_self;
  for (const Body& body : bodies) {
    const BodyEffects& effects = body.settings().effects;
    with_bodies.push_back(effects.contact_bodies.value_or(settings_.bodies) && settings_.bodies);
    // Only finite elements bend far enough to meet themselves.
    with_self.push_back(effects.contact_self.value_or(settings_.self) && settings_.self &&
                        body.finiteElements());
  }
  const auto count = [](const std::vector<bool>& v) {
    return std::count(v.begin(), v.end(), true);
  };
  if (count(with_bodies) < 2 && count(with_self) == 0) return;
  if (count(with_bodies) < 2) with_bodies.assign(with_bodies.size(), false);
  body_contact_ = std::make_unique<BodyContact>(bodies, settings_, with_bodies, with_self);
}

void ContactStep::embed(int b, const EmbeddedSurface& surface, const Body& body) {
  if (states_[b]) states_[b]->embed(surface);
  if (body_contact_) body_contact_->embed(b, surface, body);
  if (impulses_) impulses_->embed(b, surface, body);
}

void ContactStep::begin(const std::vector<PlacedShape>& obstacles) {
  if (starts_.size() == obstacles.size()) return;
  starts_.resize(obstacles.size());  // allocates only when their number changes
  for (size_t k = 0; k < obstacles.size(); ++k) starts_[k] = obstacles[k].pose;
  for (std::optional<ContactState>& state : states_) {
    if (state) state->forget();
  }
  if (impulses_) impulses_->forgetAll();
}

double ContactStep::hold(int b, Body& body, const std::vector<PlacedShape>& obstacles, double dt) {
  if (!states_[b]) return 0.0;
  const WallClock::time_point start = WallClock::now();
  states_[b]->hold(*body.finiteElements(), obstacles, dt);
  return secondsSince(start);
}

void ContactStep::finish(BodyList& bodies, const std::vector<PlacedShape>& obstacles, double dt,
                         int threads, std::vector<StepReport>& reports) {
  if (impulses_) {
    // One problem: finding contact between bodies is timed as theirs, the rest (the obstacles'
    // detection and the one solve) as the obstacles'.
    const WallClock::time_point start = WallClock::now();
    impulses_->resolve(bodies, obstacles, starts_, dt, threads, reports);
    const double between = impulses_->timeBetweenBodies();
    shareTime(
        secondsSince(start) - between, [&](int b) { return impulses_->takesPart(b); },
        &StepTimes::obstacle_contact, reports);
    if (body_contact_) {
      shareTime(
          between, [&](int b) { return body_contact_->takesPart(b); }, &StepTimes::body_contact,
          reports);
      ++body_steps_;
    }
    for (size_t b = 0; b < bodies.size(); ++b) obstacle_steps_ += impulses_->takesPart(b);
  } else if (body_contact_) {
    resolveBetweenBodies(bodies, dt, threads, reports);
  }
  parallelFor(threads, 0, static_cast<int>(bodies.size()), [&](int b) {
    if (!states_[b]) return;
    const WallClock::time_point start = WallClock::now();
    FiniteElementBody& body = *bodies[b].finiteElements();
    states_[b]->release(body, obstacles, starts_, settings_, dt);
    reports[b].contacts = states_[b]->project(body, obstacles, starts_, settings_, dt);
    reports[b].times.obstacle_contact += secondsSince(start);
  });
  if (body_contact_) body_contact_->measureDepths(bodies);
  for (const std::optional<ContactState>& state : states_) obstacle_steps_ += state.has_value();
  for (size_t k = 0; k < starts_.size(); ++k) starts_[k] = obstacles[k].pose;
}

void ContactStep::resolveBetweenBodies(BodyList& bodies, double dt, int threads,
                                       std::vector<StepReport>& reports) {
  const WallClock::time_point start = WallClock::now();
  body_contact_->resolve(bodies, dt, threads, reports);
  ++body_steps_;
  shareTime(
      secondsSince(start), [&](int b) { return body_contact_->takesPart(b); },
      &StepTimes::body_contact, reports);
}

void ContactStep::forget(int b) {
  if (states_[b]) states_[b]->forget();
  if (impulses_) impulses_->forget(b);
}

const std::vector<ContactLoad>& ContactStep::obstacleContacts(int b) const {
  static const std::vector<ContactLoad> none;
  if (impulses_) return impulses_->takesPart(b) ? impulses_->loads(b) : none;
  return states_[b] ? states_[b]->obstacleContacts() : none;
}

}  // namespace deformable_sim::core
