#include "deformable_sim/ros/session_messages.h"

#include <stdexcept>
#include <variant>

#include "deformable_sim/core/elements/mesh_arrays.h"
#include "deformable_sim/io/scene_file.h"
#include "deformable_sim/ros/conversions.h"
#include "deformable_sim/ros/obstacle_mesh_messages.h"

namespace deformable_sim::ros_layer {

namespace {

// Gives each mesh its id and lists those the message must carry.
struct MeshIds {
  core::MeshCatalogue& catalogue;
  std::vector<core::MeshCatalogue::Entry> unrecorded;
  std::string idFor(const core::MeshCatalogue::Mesh& mesh) {
    return catalogue.idFor(mesh, unrecorded);
  }
};

// Obstacle's shape codes are core::Shape::Kind's values, in its order.
static_assert(Obstacle::BOX == static_cast<int>(core::Shape::Kind::kBox) &&
              Obstacle::SPHERE == static_cast<int>(core::Shape::Kind::kSphere) &&
              Obstacle::CYLINDER == static_cast<int>(core::Shape::Kind::kCylinder) &&
              Obstacle::MESH == static_cast<int>(core::Shape::Kind::kMesh));

Obstacle toMessage(const core::PlacedShape& placed, MeshIds& ids) {
  Obstacle m;
  m.name = placed.name;
  m.shape = static_cast<uint8_t>(placed.shape.kind);
  if (placed.shape.kind == core::Shape::Kind::kMesh) m.mesh_id = ids.idFor(placed.shape.mesh);
  m.size = toVector3(placed.shape.size);
  m.radius = placed.shape.radius;
  m.length = placed.shape.length;
  m.pose = toTransform(placed.pose);
  return m;
}

core::PlacedShape fromMessage(const Obstacle& m, const core::MeshCatalogue& catalogue) {
  if (m.shape > Obstacle::MESH) {
    throw core::CommandError("obstacle '" + m.name + "': unknown shape " + std::to_string(m.shape));
  }
  core::PlacedShape placed;
  placed.name = m.name;
  placed.shape.kind = static_cast<core::Shape::Kind>(m.shape);
  if (m.shape == Obstacle::MESH) placed.shape.mesh = catalogue.find(m.mesh_id);
  placed.shape.size = toEigen(m.size);
  placed.shape.radius = m.radius;
  placed.shape.length = m.length;
  placed.pose = toEigen(m.pose);
  return placed;
}

AppliedNodes toMessage(const core::NodeTarget& t, MeshIds& ids) {
  AppliedNodes m;
  m.node_ids.assign(t.node_numbers.begin(), t.node_numbers.end());
  m.group = t.group;
  m.has_box = t.box.has_value();
  if (t.box) {
    m.box_min = toPoint(t.box->min);
    m.box_max = toPoint(t.box->max);
  }
  m.has_sphere = t.sphere.has_value();
  if (t.sphere) {
    m.sphere_center = toPoint(t.sphere->center);
    m.sphere_radius = t.sphere->radius;
  }
  m.region_pose = toTransform(t.region_pose);
  for (const core::PlacedShape& s : t.shapes) m.shapes.push_back(toMessage(s, ids));
  m.shape_margin = t.shape_margin;
  m.whole_body = t.whole_body;
  return m;
}

core::NodeTarget fromMessage(const AppliedNodes& m, const core::MeshCatalogue& catalogue) {
  core::NodeTarget t;
  t.node_numbers.assign(m.node_ids.begin(), m.node_ids.end());
  t.group = m.group;
  if (m.has_box) t.box = core::Box{toEigen(m.box_min), toEigen(m.box_max)};
  if (m.has_sphere) t.sphere = core::Sphere{toEigen(m.sphere_center), m.sphere_radius};
  t.region_pose = toEigen(m.region_pose);
  for (const Obstacle& s : m.shapes) t.shapes.push_back(fromMessage(s, catalogue));
  t.shape_margin = m.shape_margin;
  t.whole_body = m.whole_body;
  return t;
}

// Each command's fields into the message (its kind and what that kind uses).
void record(const core::WrenchCommand& c, Applied& m, MeshIds& ids) {
  m.kind = Applied::WRENCH;
  m.name = c.source;
  m.body = c.body;
  m.nodes = toMessage(c.nodes, ids);
  m.force = toVector3(c.force);
  m.torque = toVector3(c.torque);
  m.has_point = c.point.has_value();
  if (c.point) m.point = toPoint(*c.point);
}

void record(const core::ClearWrenchCommand& c, Applied& m, MeshIds&) {
  m.kind = Applied::CLEAR_WRENCH;
  m.name = c.source;
}

void record(const core::FixCommand& c, Applied& m, MeshIds& ids) {
  m.kind = c.fix ? Applied::FIX : Applied::RELEASE;
  m.body = c.body;
  m.nodes = toMessage(c.nodes, ids);
  for (const Eigen::Vector3d& p : c.targets) m.targets.push_back(toPoint(p));
  m.has_translation = c.translation.has_value();
  if (c.translation) m.translation = toVector3(*c.translation);
}

void record(const core::GraspCommand& c, Applied& m, MeshIds& ids) {
  m.kind = Applied::GRASP;
  m.name = c.name;
  m.body = c.body;
  m.nodes = toMessage(c.nodes, ids);
  m.frame = toTransform(c.frame);
}

void record(const core::ReleaseGraspCommand& c, Applied& m, MeshIds&) {
  m.kind = Applied::RELEASE_GRASP;
  m.name = c.name;
}

void record(const core::MoveGraspCommand& c, Applied& m, MeshIds&) {
  m.kind = Applied::MOVE_GRASP;
  m.name = c.name;
  m.frame = toTransform(c.frame);
}

void record(const core::SetObstaclesCommand& c, Applied& m, MeshIds& ids) {
  m.kind = Applied::OBSTACLES;
  for (const core::PlacedShape& s : c.obstacles) m.obstacles.push_back(toMessage(s, ids));
}

void record(const core::TuneCommand& c, Applied& m, MeshIds&) {
  m.kind = Applied::TUNE;
  m.body = c.body;
  m.has_material = c.material.has_value();
  if (c.material) {
    m.youngs_modulus = c.material->youngs_modulus;
    m.poisson_ratio = c.material->poisson_ratio;
    m.density = c.material->density;
  }
  m.has_damping = c.damping.has_value();
  if (c.damping) {
    m.damping_mass = c.damping->mass;
    m.damping_stiffness = c.damping->stiffness;
  }
  m.has_solver_tolerance = c.solver_tolerance.has_value();
  m.solver_tolerance = c.solver_tolerance.value_or(0.0);
  m.has_solver_max_iterations = c.solver_max_iterations.has_value();
  m.solver_max_iterations = c.solver_max_iterations.value_or(0);
  m.has_dt = c.dt.has_value();
  m.dt = c.dt.value_or(0.0);
}

void record(const core::ResetCommand&, Applied& m, MeshIds&) { m.kind = Applied::RESET; }

}  // namespace

Applied toMessage(const core::SessionCommand& command, core::MeshCatalogue& catalogue) {
  Applied m;
  m.frame.rotation.w = 1.0;
  MeshIds ids{catalogue, {}};
  std::visit([&m, &ids](const auto& c) { record(c, m, ids); }, command);
  for (const core::MeshCatalogue::Entry& e : ids.unrecorded) {
    m.meshes.push_back(toMessage(e.id, *e.mesh));
  }
  return m;
}

core::SessionCommand fromMessage(const Applied& m, core::MeshCatalogue& catalogue) {
  receive(m.meshes, catalogue);
  switch (m.kind) {
    case Applied::WRENCH: {
      core::WrenchCommand c;
      c.source = m.name;
      c.body = m.body;
      c.nodes = fromMessage(m.nodes, catalogue);
      c.force = toEigen(m.force);
      c.torque = toEigen(m.torque);
      if (m.has_point) c.point = toEigen(m.point);
      return c;
    }
    case Applied::CLEAR_WRENCH:
      return core::ClearWrenchCommand{m.name};
    case Applied::FIX:
    case Applied::RELEASE: {
      core::FixCommand c;
      c.fix = m.kind == Applied::FIX;
      c.body = m.body;
      c.nodes = fromMessage(m.nodes, catalogue);
      for (const geometry_msgs::Point& p : m.targets) c.targets.push_back(toEigen(p));
      if (m.has_translation) c.translation = toEigen(m.translation);
      return c;
    }
    case Applied::GRASP: {
      core::GraspCommand c;
      c.name = m.name;
      c.body = m.body;
      c.nodes = fromMessage(m.nodes, catalogue);
      c.frame = toEigen(m.frame);
      return c;
    }
    case Applied::RELEASE_GRASP:
      return core::ReleaseGraspCommand{m.name};
    case Applied::MOVE_GRASP:
      return core::MoveGraspCommand{m.name, toEigen(m.frame)};
    case Applied::OBSTACLES: {
      core::SetObstaclesCommand c;
      for (const Obstacle& o : m.obstacles) c.obstacles.push_back(fromMessage(o, catalogue));
      return c;
    }
    case Applied::TUNE: {
      core::TuneCommand c;
      c.body = m.body;
      if (m.has_material) c.material = {m.youngs_modulus, m.poisson_ratio, m.density};
      if (m.has_damping) c.damping = core::RayleighDamping{m.damping_mass, m.damping_stiffness};
      if (m.has_solver_tolerance) c.solver_tolerance = m.solver_tolerance;
      if (m.has_solver_max_iterations) c.solver_max_iterations = m.solver_max_iterations;
      if (m.has_dt) c.dt = m.dt;
      return c;
    }
    case Applied::RESET:
      return core::ResetCommand{};
    default:
      throw core::CommandError("applied command of unknown kind " + std::to_string(m.kind));
  }
}

Scene toSceneMessage(const std::string& path, const std::string& yaml, double dt, int substeps,
                     const std::vector<core::Mesh>& meshes,
                     const std::vector<std::optional<core::EmbeddedSurface>>& surfaces,
                     const std::vector<std::string>& body_names,
                     const std::vector<core::PlacedShape>& obstacles,
                     const std::vector<core::PlacedShape>& link_shapes,
                     core::MeshCatalogue& catalogue) {
  Scene m;
  MeshIds ids{catalogue, {}};
  for (size_t k = 0; k < obstacles.size(); ++k) {
    if (obstacles[k].shape.kind != core::Shape::Kind::kMesh) continue;
    const std::string id = io::sceneObstacleKey(static_cast<int>(k));
    catalogue.addRecorded(id, obstacles[k].shape.mesh);
    ids.unrecorded.push_back({id, obstacles[k].shape.mesh});
  }
  for (const core::PlacedShape& shape : link_shapes) {
    if (shape.shape.kind == core::Shape::Kind::kMesh) ids.idFor(shape.shape.mesh);
  }
  for (const core::MeshCatalogue::Entry& e : ids.unrecorded) {
    m.obstacle_meshes.push_back(toMessage(e.id, *e.mesh));
    catalogue.markRecorded(e.id);
  }
  m.path = path;
  m.yaml = yaml;
  m.dt = dt;
  m.substeps = static_cast<uint32_t>(substeps);
  for (size_t b = 0; b < meshes.size(); ++b) {
    core::MeshArrays arrays = core::toArrays(meshes[b]);
    MeshData data;
    data.body = body_names[b];
    data.node_ids = std::move(arrays.node_numbers);
    data.rest_positions = std::move(arrays.rest_positions);
    data.tetrahedra = std::move(arrays.tetrahedra);
    data.cell_types = std::move(arrays.cell_types);
    data.cells = std::move(arrays.cells);
    data.cell_fractions = std::move(arrays.cell_fractions);
    data.incompatible_modes = arrays.incompatible_modes;
    if (b < surfaces.size() && surfaces[b]) {
      const core::TriangleMesh surface{surfaces[b]->restPositions(), surfaces[b]->triangles()};
      core::flatten(surface, data.surface_vertices, data.surface_triangles);
    }
    m.meshes.push_back(std::move(data));
  }
  return m;
}

std::vector<core::Mesh> meshesFromMessage(
    const Scene& message, std::vector<std::optional<core::EmbeddedSurface>>* surfaces) {
  std::vector<core::Mesh> meshes;
  if (surfaces) surfaces->assign(message.meshes.size(), std::nullopt);
  for (size_t b = 0; b < message.meshes.size(); ++b) {
    const MeshData& data = message.meshes[b];
    const core::MeshArrays arrays{data.node_ids,
                                  data.rest_positions,
                                  data.tetrahedra,
                                  data.cell_types,
                                  data.cells,
                                  data.cell_fractions,
                                  data.incompatible_modes != 0};
    const std::string what = "scene message: the mesh of body '" + data.body + "'";
    meshes.push_back(core::fromArrays(arrays, what));
    if (surfaces && !data.surface_triangles.empty()) {
      const core::TriangleMesh surface =
          core::unflatten(data.surface_vertices, data.surface_triangles, what + ": its surface");
      (*surfaces)[b] = core::embedInGrid(surface, meshes.back(), what);
    }
  }
  return meshes;
}

}  // namespace deformable_sim::ros_layer
