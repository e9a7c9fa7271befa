#include "deformable_sim/identify/fitted_scene.h"

#include <yaml-cpp/yaml.h>

namespace deformable_sim::identify {

namespace {

YAML::Node bodyNode(YAML::Node& root, const FitParameter& p) {
  YAML::Node bodies = root["bodies"];
  if (bodies.IsSequence()) {
    for (YAML::Node body : bodies) {
      if (body["name"].IsScalar() && body["name"].as<std::string>() == p.body) return body;
    }
  }
  throw FitSpecError(p.key + ".body: the scene file has no body '" + p.body + "'");
}

void set(YAML::Node& root, const FitParameter& p, double value) {
  if (p.parameter == "friction") {
    root["effects"]["contact"]["friction"] = value;
    return;
  }
  YAML::Node body = bodyNode(root, p);
  if (p.parameter.rfind("damping_", 0) != 0) {
    body["material"][p.parameter] = value;
    return;
  }
  const std::string key = p.parameter.substr(std::string("damping_").size());
  // The body's own effects when it has them; with several bodies it gets its own copy.
  const bool shared = !body["effects"].IsDefined() && root["bodies"].size() > 1;
  if (shared) body["effects"] = YAML::Clone(root["effects"]);
  YAML::Node effects = body["effects"].IsDefined() ? body["effects"] : root["effects"];
  effects["damping"][key] = value;
}

}  // namespace

std::string fittedSceneYaml(const std::string& scene_yaml,
                            const std::vector<FitParameter>& parameters,
                            const std::vector<double>& values) {
  YAML::Node root = YAML::Load(scene_yaml);
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (parameters[i].observation < 0) set(root, parameters[i], values[i]);  // not time offsets
  }
  YAML::Emitter out;
  out.SetDoublePrecision(9);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace deformable_sim::identify
