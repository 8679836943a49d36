#include "dnurbs/io/scene_obstacles.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene.h"

namespace dnurbs {
namespace {

Obstacle read_obstacle(const SceneReader& reader, const JsonValue& value, const std::string& path) {
  if (!value.is_object()) {
    reader.fail(path, "expected an obstacle object, got " + describe_json_value(value));
  }
  const std::string type = reader.choice(reader.require(value, path, "type", "an obstacle type"),
                                         join_json_path(path, "type"), {"plane", "box", "sphere"});
  const auto point = [&](const char* key, const char* what) {
    return reader.point(reader.require(value, path, key, what), join_json_path(path, key));
  };
  if (type == "plane") {
    reader.object(value, path, {"type", "point", "normal"});
    GroundPlane plane;
    plane.point = point("point", "a point of the plane [x, y, z]");
    plane.normal = point("normal", "the normal [x, y, z] of the free side");
    if (plane.normal.norm() == 0.0) {
      reader.fail(join_json_path(path, "normal"), "expected a non-zero normal, got [0, 0, 0]");
    }
    return plane;
  }
  if (type == "box") {
    reader.object(value, path, {"type", "min", "max"});
    BoxObstacle box;
    box.minimum = point("min", "the box's lowest corner [x, y, z]");
    box.maximum = point("max", "the box's highest corner [x, y, z]");
    for (int c = 0; c < 3; ++c) {
      if (!(box.maximum[c] > box.minimum[c])) {
        reader.fail(join_json_path(path, "max"),
                    "expected a corner above min in every coordinate, got " +
                        format_json_number(box.maximum[c]) + " <= " +
                        format_json_number(box.minimum[c]) + " in coordinate " + std::to_string(c));
      }
    }
    return box;
  }
  reader.object(value, path, {"type", "centre", "radius"});
  SphereObstacle sphere;
  sphere.centre = point("centre", "the centre [x, y, z]");
  sphere.radius = reader.bounded(reader.require(value, path, "radius", "a radius > 0"),
                                 join_json_path(path, "radius"), 0.0, true);
  return sphere;
}

JsonOut obstacle_json(const Obstacle& obstacle) {
  if (const auto* plane = std::get_if<GroundPlane>(&obstacle)) {
    return {{"type", "plane"},
            {"point", json_array<3>(plane->point)},
            {"normal", json_array<3>(plane->normal)}};
  }
  if (const auto* box = std::get_if<BoxObstacle>(&obstacle)) {
    return {{"type", "box"},
            {"min", json_array<3>(box->minimum)},
            {"max", json_array<3>(box->maximum)}};
  }
  const auto& sphere = std::get<SphereObstacle>(obstacle);
  return {{"type", "sphere"}, {"centre", json_array<3>(sphere.centre)}, {"radius", sphere.radius}};
}

// True if L(u) picks one point's three coordinates with weight 1 (a node), to within `tolerance`
// (a chain's node parameter k h may round off the node: weights 1 - 4e-16 and 4e-16); `empty` is
// set when L(u) is zero (a node that is not simulated, outside a PDE surface's regions).
bool is_node(const Model& model, ConstVectorRef q, const Eigen::Vector2d& u, bool& empty,
             double tolerance) {
  const SparseMatrix jacobian = model.position_jacobian(q, u);
  empty = jacobian.nonZeros() == 0;
  int ones = 0;
  for (Eigen::Index col = 0; col < jacobian.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(jacobian, col); it; ++it) {
      if (std::abs(it.value() - 1.0) <= tolerance) {
        ++ones;
      } else if (std::abs(it.value()) > tolerance) {
        return false;
      }
    }
  }
  return ones == 3;
}

}  // namespace

void read_scene_obstacles(const SceneReader& reader, const JsonValue& root,
                          std::vector<Obstacle>& obstacles, SceneContact& contact) {
  const JsonValue* list = reader.find(root, "obstacles");
  const JsonValue* settings = reader.find(root, "contact");
  if (list == nullptr) {
    if (settings != nullptr) {
      reader.fail("contact", "expected no contact settings without \"obstacles\" to meet");
    }
    return;
  }
  reader.array(*list, "obstacles", "obstacles");
  for (size_t i = 0; i < list->size(); ++i) {
    obstacles.push_back(read_obstacle(reader, (*list)[i], json_index_path("obstacles", i)));
  }
  if (settings == nullptr) {
    return;
  }
  const std::string path = "contact";
  reader.object(*settings, path, {"method", "stiffness", "damping", "friction"});
  if (const JsonValue* method = reader.find(*settings, "method")) {
    contact.method = reader.choice(*method, "contact.method", {"projection", "penalty"});
  }
  reader.number_key(*settings, path, "stiffness", contact.settings.stiffness, 0.0, false);
  reader.number_key(*settings, path, "damping", contact.settings.damping, 0.0, false);
  reader.number_key(*settings, path, "friction", contact.settings.friction, 0.0, false);
}

void write_scene_obstacles(const std::vector<Obstacle>& obstacles, const SceneContact& contact,
                           JsonOut& root) {
  if (obstacles.empty()) {
    return;
  }
  root["obstacles"] = JsonOut::array();
  for (const Obstacle& obstacle : obstacles) {
    root["obstacles"].push_back(obstacle_json(obstacle));
  }
  root["contact"] = {{"method", contact.method},
                     {"stiffness", contact.settings.stiffness},
                     {"damping", contact.settings.damping},
                     {"friction", contact.settings.friction}};
}

std::vector<Eigen::Vector2d> contact_nodes(const Model& model, ConstVectorRef q) {
  std::vector<Eigen::Vector2d> candidates;
  if (model.parametric_dimension() == 2) {
    // Grid surfaces tessellate as one vertex per node with uv the node's parameter; the few
    // cells asked for keep the mesh of any other surface small
    ModelTessellationSettings settings;
    settings.segments_u = 4;
    settings.segments_v = 4;
    const TriangleMesh mesh = model.tessellate(q, settings, "contact");
    for (Eigen::Index k = 0; k < mesh.uv.rows(); ++k) {
      candidates.emplace_back(mesh.uv.row(k).transpose());
    }
  } else {
    // A chain of N nodes over [s0, s1]: node k at s0 + k (s1 - s0) / (N - 1), or / N when closed
    const ParameterDomain domain = model.parameter_domain(q);
    const int count = model.coordinate_count() / 3;
    const int intervals = domain.periodic_u ? count : count - 1;
    const double spacing = intervals > 0 ? (domain.u_max - domain.u_min) / intervals : 0.0;
    for (int k = 0; k < count && intervals > 0; ++k) {
      candidates.emplace_back(domain.u_min + k * spacing, 0.0);  // as NodeChain::parameter
    }
  }
  std::vector<Eigen::Vector2d> nodes;
  for (const Eigen::Vector2d& u : candidates) {
    bool empty = false;
    if (is_node(model, q, u, empty, 1e-12)) {
      nodes.push_back(u);
    } else if (!empty) {
      return {};  // a material point that blends several coordinates: not a node model
    }
  }
  return nodes;
}

std::vector<Eigen::Vector2d> contact_samples(const Model& model, ConstVectorRef q,
                                             int surface_count, int curve_count) {
  const ParameterDomain domain = model.parameter_domain(q);
  const bool surface = model.parametric_dimension() == 2;
  const int nu = surface ? surface_count : curve_count;
  const int nv = surface ? surface_count : 1;
  // Closed directions: the samples k / n of the period (the end repeats the start)
  const auto at = [](double lo, double hi, bool periodic, int k, int n) {
    if (n == 1) {
      return lo;
    }
    return lo + (hi - lo) * k / (periodic ? n : n - 1);
  };
  std::vector<Eigen::Vector2d> samples;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      samples.emplace_back(
          at(domain.u_min, domain.u_max, domain.periodic_u, i, nu),
          surface ? at(domain.v_min, domain.v_max, domain.periodic_v, j, nv) : 0.0);
    }
  }
  return samples;
}

SceneContacts::SceneContacts(const Scene& scene, System& system)
    : obstacles_(scene.obstacles), contact_(scene.contact) {
  if (obstacles_.empty()) {
    return;
  }
  const bool projection = contact_.method == "projection";
  for (int m = 0; m < system.model_count(); ++m) {
    const Model& model = system.model(m);
    const std::string label = "model " + std::to_string(m) + " (" +
                              scene.models[static_cast<size_t>(m)].name + ", a " +
                              scene_model_type(scene.models[static_cast<size_t>(m)]) + ")";
    std::vector<Eigen::Vector2d> points;
    try {
      points = contact_nodes(model, system.coordinates(m));
      if (points.empty() && projection) {
        throw SceneKeyError(".method",
                            "expected \"penalty\": " + label +
                                " has no nodes to project (its material points blend control "
                                "points); projection works on grid surfaces and snakes");
      }
      if (points.empty()) {
        points = contact_samples(model, system.coordinates(m));
      }
      for (const Eigen::Vector2d& u : projection ? points : std::vector<Eigen::Vector2d>()) {
        bool empty = false;
        if (!is_node(model, system.coordinates(m), u, empty, 0.0)) {
          throw SceneKeyError(".method", "expected \"penalty\": the node of " + label +
                                             " at parameter " + format_json_number(u.x()) +
                                             " is not picked exactly by its parameter (k h "
                                             "rounds off it), so projection cannot move it");
        }
      }
      if (!projection) {
        system.add_force(m, penalty_contact(obstacles_, points, contact_.settings));
      }
    } catch (const SceneKeyError& error) {
      throw SceneKeyError("contact" + error.key(), error.what());
    } catch (const Error& error) {
      throw SceneKeyError("obstacles", label + ": " + error.what());
    }
    points_.push_back(std::move(points));
  }
}

double SceneContacts::project(System& system) const {
  double deepest = 0.0;
  if (contact_.method != "projection") {
    return deepest;
  }
  for (size_t m = 0; m < points_.size(); ++m) {
    deepest = std::max(deepest, project_contacts(system, static_cast<int>(m), obstacles_,
                                                 points_[m], contact_.settings));
  }
  return deepest;
}

double SceneContacts::max_penetration(const System& system) const {
  double deepest = 0.0;
  for (size_t m = 0; m < points_.size(); ++m) {
    deepest = std::max(
        deepest, dnurbs::max_penetration(system, static_cast<int>(m), obstacles_, points_[m]));
  }
  return deepest;
}

}  // namespace dnurbs
