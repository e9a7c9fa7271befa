#include "deformable_sim/core/outputs/contact_pairs.h"

#include <algorithm>

namespace deformable_sim::core {

namespace {

/// `total` gains `part`: forces and torques add, the centre is the points' mean.
void merge(ContactLoad& total, const ContactLoad& part) {
  const int points = total.points + part.points;
  if (points > 0) total.centre = (total.points * total.centre + part.points * part.centre) / points;
  total.points = points;
  total.force += part.force;
  total.torque += part.torque;
  total.penetration = std::max(total.penetration, part.penetration);
  total.depth = std::max(total.depth, part.depth);
}

bool touched(const ContactLoad& load) { return load.points > 0 || !load.force.isZero(0.0); }

}  // namespace

void touchingPairs(const Simulation& sim, std::vector<ContactPair>& pairs) {
  pairs.clear();
  const std::vector<PlacedShape>& obstacles = sim.obstacles();
  for (int b = 0; b < static_cast<int>(sim.bodies().size()); ++b) {
    const std::vector<ContactLoad>& loads = sim.obstacleContacts(b);
    const size_t first = pairs.size();
    for (size_t k = 0; k < loads.size() && k < obstacles.size(); ++k) {
      if (!touched(loads[k])) continue;
      auto same = std::find_if(pairs.begin() + first, pairs.end(),
                               [&](const ContactPair& p) { return p.other == obstacles[k].name; });
      if (same == pairs.end()) {
        pairs.push_back({b, ContactPair::Kind::kObstacle, obstacles[k].name, loads[k]});
      } else {
        merge(same->load, loads[k]);
      }
    }
    const BodyContact* between = sim.bodyContact();
    if (!between) continue;
    for (int o = 0; o < static_cast<int>(sim.bodies().size()); ++o) {
      const ContactLoad& load = between->load(b, o);
      if (load.points == 0) continue;
      pairs.push_back({b, o == b ? ContactPair::Kind::kSelf : ContactPair::Kind::kBody,
                       sim.bodies()[o].name(), load});
    }
  }
}

ContactLoad loadOnObstacle(const std::vector<ContactPair>& pairs, const std::string& name) {
  ContactLoad total;
  for (const ContactPair& p : pairs) {
    if (p.kind != ContactPair::Kind::kObstacle || p.other != name) continue;
    ContactLoad opposite = p.load;
    opposite.force = -opposite.force;
    opposite.torque = -opposite.torque;
    merge(total, opposite);
  }
  return total;
}

}  // namespace deformable_sim::core
