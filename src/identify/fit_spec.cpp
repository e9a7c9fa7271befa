#include "deformable_sim/identify/fit_spec.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "deformable_sim/core/elements/parameter_limits.h"

namespace deformable_sim::identify {

namespace {

// Reads typed values out of YAML nodes; every error names the source, the line and the key.
class Reader {
 public:
  Reader(std::string source, std::string base) : source_(std::move(source)), base_(base) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& message) const {
    std::ostringstream text;
    text << source_;
    if (node.IsDefined() && node.Mark().line >= 0) text << ":" << node.Mark().line + 1;
    text << ": " << key << ": " << message;
    throw FitSpecError(text.str());
  }

  void onlyKeys(const YAML::Node& map, const std::string& key,
                const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, key, "expected a map");
    for (const auto& entry : map) {
      const std::string name = entry.first.as<std::string>();
      if (allowed.count(name) == 0) fail(entry.first, join(key, name), "unknown key");
    }
  }

  static std::string join(const std::string& key, const std::string& name) {
    return key.empty() ? name : key + "." + name;
  }

  YAML::Node required(const YAML::Node& map, const std::string& key,
                      const std::string& name) const {
    const YAML::Node node = map[name];
    if (!node.IsDefined() || node.IsNull()) fail(map, join(key, name), "missing");
    return node;
  }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar() || node.as<std::string>().empty()) fail(node, key, "expected a name");
    return node.as<std::string>();
  }

  double number(const YAML::Node& node, const std::string& key) const {
    double value = 0.0;
    if (!node.IsScalar() || !YAML::convert<double>::decode(node, value) || !std::isfinite(value))
      fail(node, key, "expected a finite number");
    return value;
  }

  double positive(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value > 0.0)) fail(node, key, "must be > 0, not " + node.as<std::string>());
    return value;
  }

  Eigen::Vector3d point(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(node, key, "expected [x, y, z] in m");
    return {number(node[0], key), number(node[1], key), number(node[2], key)};
  }

  std::string path(const YAML::Node& node, const std::string& key) const {
    const std::filesystem::path given = text(node, key);
    return given.is_absolute() ? given.string() : (std::filesystem::path(base_) / given).string();
  }

 private:
  std::string source_;
  std::string base_;
};

// A bound the parameter itself may not take is refused here, in the words the scene reader and
// the bodies use, not at the first re-simulation. Friction is the contact's: finite and >= 0.
void checkBound(const Reader& r, const YAML::Node& node, const std::string& key,
                const std::string& parameter, double bound) {
  const std::optional<core::Parameter> known = core::parameterNamed(parameter);
  const std::string problem = known          ? core::parameterProblem(*known, bound)
                              : bound >= 0.0 ? ""
                                             : "must be finite and >= 0";
  if (!problem.empty()) r.fail(node, key, problem + " (as " + parameter + ")");
}

FitParameter readParameter(const Reader& r, const YAML::Node& node, const std::string& key) {
  r.onlyKeys(node, key, {"body", "parameter", "min", "max"});
  FitParameter p;
  p.key = key;
  p.body = r.text(r.required(node, key, "body"), key + ".body");
  const YAML::Node name = r.required(node, key, "parameter");
  p.parameter = r.text(name, key + ".parameter");
  const std::vector<std::string>& names = fitParameterNames();
  if (std::find(names.begin(), names.end(), p.parameter) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    r.fail(name, key + ".parameter",
           "unknown parameter '" + p.parameter + "' (one of " + list + ")");
  }
  const YAML::Node min = r.required(node, key, "min"), max = r.required(node, key, "max");
  p.min = r.number(min, key + ".min");
  p.max = r.number(max, key + ".max");
  checkBound(r, min, key + ".min", p.parameter, p.min);
  checkBound(r, max, key + ".max", p.parameter, p.max);
  if (!(p.min < p.max)) r.fail(max, key + ".max", "must be greater than min");
  return p;
}

// time_offset: S (fixed) or {min: S, max: S} (fitted from 0); loss: {huber: SIGMAS}.
void readTimingAndLoss(const Reader& r, const YAML::Node& node, const std::string& key,
                       ObservationSpec& o) {
  const YAML::Node offset = node["time_offset"];
  if (offset.IsDefined() && offset.IsMap()) {
    r.onlyKeys(offset, key + ".time_offset", {"min", "max"});
    o.fit_time_offset = true;
    o.offset_min =
        r.number(r.required(offset, key + ".time_offset", "min"), key + ".time_offset.min");
    o.offset_max =
        r.number(r.required(offset, key + ".time_offset", "max"), key + ".time_offset.max");
    if (!(o.offset_min <= 0.0 && 0.0 <= o.offset_max && o.offset_min < o.offset_max)) {
      r.fail(offset, key + ".time_offset",
             "expected min <= 0 <= max, min < max (a fitted offset starts from 0)");
    }
  } else if (offset.IsDefined()) {
    o.time_offset = r.number(offset, key + ".time_offset");
  }
  const YAML::Node loss = node["loss"];
  if (loss.IsDefined()) {
    r.onlyKeys(loss, key + ".loss", {"huber"});
    o.huber = r.positive(r.required(loss, key + ".loss", "huber"), key + ".loss.huber");
  }
}

void readWrenchSigma(const Reader& r, const YAML::Node& node, const std::string& key,
                     ObservationSpec& o) {
  if (!node.IsSequence() || node.size() != 2) r.fail(node, key, "expected [N, N m]");
  o.sigma = r.positive(node[0], key);
  o.torque_sigma = r.positive(node[1], key);
}

void readWrench(const Reader& r, const YAML::Node& node, const std::string& key,
                ObservationSpec& o) {
  r.onlyKeys(node, key, {"wrench", "reactions", "grasp", "link", "sigma", "time_offset", "loss"});
  o.kind = ObservationSpec::Kind::kWrench;
  o.topic = r.text(node["wrench"], key + ".wrench");
  int sources = 0;
  for (const char* name : {"reactions", "grasp", "link"}) {
    if (!node[name].IsDefined()) continue;
    ++sources;
    const std::string value = r.text(node[name], key + "." + name);
    if (std::string(name) == "reactions") o.body = value;
    if (std::string(name) == "grasp") o.source = ObservationSpec::Source::kGrasp, o.name = value;
    if (std::string(name) == "link") o.source = ObservationSpec::Source::kLink, o.name = value;
  }
  if (sources != 1) r.fail(node, key, "give exactly one of reactions, grasp or link");
  readWrenchSigma(r, r.required(node, key, "sigma"), key + ".sigma", o);
  readTimingAndLoss(r, node, key, o);
}

ObservationSpec readObservation(const Reader& r, const YAML::Node& node, const std::string& key) {
  ObservationSpec o;
  o.key = key;
  if (node.IsMap() && node["wrench"].IsDefined()) {
    readWrench(r, node, key, o);
    return o;
  }
  r.onlyKeys(node, key, {"tf", "body", "at", "sigma", "time_offset", "loss"});
  if (!node["tf"].IsDefined()) r.fail(node, key, "expected a tf or a wrench observation");
  o.topic = r.text(node["tf"], key + ".tf");
  o.body = r.text(r.required(node, key, "body"), key + ".body");
  o.at = r.point(r.required(node, key, "at"), key + ".at");
  o.sigma = r.positive(r.required(node, key, "sigma"), key + ".sigma");
  readTimingAndLoss(r, node, key, o);
  return o;
}

template <typename Entry, typename Read>
std::vector<Entry> readList(const Reader& r, const YAML::Node& root, const std::string& name,
                            Read read) {
  const YAML::Node list = r.required(root, "", name);
  if (!list.IsSequence() || list.size() == 0) r.fail(list, name, "expected a non-empty list");
  std::vector<Entry> entries;
  for (std::size_t i = 0; i < list.size(); ++i)
    entries.push_back(read(r, list[i], name + "[" + std::to_string(i) + "]"));
  return entries;
}

}  // namespace

const std::vector<std::string>& fitParameterNames() {
  static const std::vector<std::string> names{"youngs_modulus", "poisson_ratio",     "density",
                                              "damping_mass",   "damping_stiffness", "friction"};
  return names;
}

FitSpec parseFitSpec(const std::string& yaml_text, const std::string& source,
                     const std::string& base_directory) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw FitSpecError(source + ":" + std::to_string(e.mark.line + 1) +
                       ": not valid YAML: " + e.msg);
  }
  const Reader r(source, base_directory);
  r.onlyKeys(root, "", {"bag", "scene", "fit", "observations", "out"});
  FitSpec spec;
  spec.bag = r.path(r.required(root, "", "bag"), "bag");
  if (root["scene"].IsDefined()) spec.scene = r.path(root["scene"], "scene");
  spec.fit = readList<FitParameter>(r, root, "fit", readParameter);
  for (std::size_t i = 0; i < spec.fit.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (spec.fit[i].body == spec.fit[j].body && spec.fit[i].parameter == spec.fit[j].parameter) {
        r.fail(root["fit"][i], "fit[" + std::to_string(i) + "]",
               spec.fit[i].parameter + " of '" + spec.fit[i].body + "' again (as fit[" +
                   std::to_string(j) + "]): a parameter is fitted once");
      }
    }
  }
  spec.observations = readList<ObservationSpec>(r, root, "observations", readObservation);
  for (std::size_t k = 0; k < spec.observations.size(); ++k) {
    const ObservationSpec& o = spec.observations[k];
    if (!o.fit_time_offset) continue;
    FitParameter offset;
    offset.parameter = "time_offset";
    offset.min = o.offset_min;
    offset.max = o.offset_max;
    offset.key = o.key + ".time_offset";
    offset.observation = static_cast<int>(k);
    spec.fit.push_back(offset);
  }
  spec.out = r.path(r.required(root, "", "out"), "out");
  return spec;
}

FitSpec readFitSpec(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw FitSpecError(path + ": cannot open the fit file");
  std::stringstream text;
  text << file.rdbuf();
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return parseFitSpec(text.str(), path, directory.empty() ? "." : directory);
}

}  // namespace deformable_sim::identify
