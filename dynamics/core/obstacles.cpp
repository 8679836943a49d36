#include "dnurbs/dynamics/core/obstacles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

void check_settings(const ContactSettings& settings) {
  const std::array<std::pair<const char*, double>, 4> values{
      {{"contact stiffness", settings.stiffness},
       {"contact damping", settings.damping},
       {"friction coefficient", settings.friction},
       {"sliding velocity", settings.sliding_velocity}}};
  for (const auto& [name, value] : values) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw make_error(name, " ", value, " is not a non-negative finite number");
    }
  }
}

// The deepest obstacle at x: depth (> 0 inside) and its outward normal.
double deepest(const std::vector<Obstacle>& obstacles, const Eigen::Vector3d& x,
               Eigen::Vector3d& normal) {
  double depth = 0.0;
  for (const Obstacle& obstacle : obstacles) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    const double d = -signed_distance(obstacle, x, &n);
    if (d > depth) {
      depth = d;
      normal = n;
    }
  }
  return depth;
}

}  // namespace

void check_obstacle(const Obstacle& obstacle) {
  if (const auto* plane = std::get_if<GroundPlane>(&obstacle)) {
    if (!plane->point.allFinite() || !plane->normal.allFinite() || plane->normal.norm() == 0.0) {
      throw make_error("ground plane normal (", plane->normal.x(), ", ", plane->normal.y(), ", ",
                       plane->normal.z(), ") or point is zero or not finite");
    }
  } else if (const auto* box = std::get_if<BoxObstacle>(&obstacle)) {
    for (int c = 0; c < 3; ++c) {
      if (!(box->minimum[c] <= box->maximum[c]) || !std::isfinite(box->minimum[c]) ||
          !std::isfinite(box->maximum[c])) {
        throw make_error("box minimum ", box->minimum[c], " and maximum ", box->maximum[c],
                         " along axis ", c, " are not finite and ordered");
      }
    }
  } else {
    const auto& sphere = std::get<SphereObstacle>(obstacle);
    if (!(sphere.radius > 0.0) || !std::isfinite(sphere.radius) || !sphere.centre.allFinite()) {
      throw make_error("sphere radius ", sphere.radius, " is not positive and finite");
    }
  }
}

double signed_distance(const Obstacle& obstacle, const Eigen::Vector3d& x,
                       Eigen::Vector3d* normal) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  double distance = 0.0;
  if (const auto* plane = std::get_if<GroundPlane>(&obstacle)) {
    n = plane->normal.normalized();
    distance = (x - plane->point).dot(n);
  } else if (const auto* box = std::get_if<BoxObstacle>(&obstacle)) {
    const Eigen::Vector3d centre = 0.5 * (box->minimum + box->maximum);
    const Eigen::Vector3d half = 0.5 * (box->maximum - box->minimum);
    const Eigen::Vector3d local = x - centre;
    const Eigen::Vector3d outside = local.cwiseAbs() - half;
    if ((outside.array() > 0.0).any()) {
      const Eigen::Vector3d clamped = outside.cwiseMax(0.0);
      distance = clamped.norm();
      n = clamped.cwiseProduct(local.cwiseSign());
      n /= distance;
    } else {
      // Inside: the nearest face.
      int axis = 0;
      distance = outside.maxCoeff(&axis);
      n = Eigen::Vector3d::Zero();
      n[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
    }
  } else {
    const auto& sphere = std::get<SphereObstacle>(obstacle);
    const Eigen::Vector3d offset = x - sphere.centre;
    const double length = offset.norm();
    n = length > 0.0 ? Eigen::Vector3d(offset / length) : Eigen::Vector3d::UnitZ();
    distance = length - sphere.radius;
  }
  if (normal != nullptr) {
    *normal = n;
  }
  return distance;
}

double penetration_depth(const std::vector<Obstacle>& obstacles, const Eigen::Vector3d& x) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  return deepest(obstacles, x, normal);
}

Force penalty_contact(std::vector<Obstacle> obstacles, std::vector<Eigen::Vector2d> points,
                      const ContactSettings& settings) {
  for (const Obstacle& obstacle : obstacles) {
    check_obstacle(obstacle);
  }
  check_settings(settings);
  return [obstacles = std::move(obstacles), points = std::move(points), settings](
             const Model& model, double /*t*/, ConstVectorRef q, ConstVectorRef qd,
             VectorRef generalized) {
    for (const Eigen::Vector2d& u : points) {
      const Eigen::Vector3d x = model.position(q, u);
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      const double depth = deepest(obstacles, x, n);
      if (depth <= 0.0) {
        continue;
      }
      const SparseMatrix jacobian = model.position_jacobian(q, u);
      const Eigen::Vector3d velocity = jacobian * qd;
      const double normal_velocity = velocity.dot(n);
      const double normal_force =
          settings.stiffness * depth - settings.damping * std::min(normal_velocity, 0.0);
      Eigen::Vector3d f = std::max(normal_force, 0.0) * n;
      if (settings.friction > 0.0) {
        const Eigen::Vector3d sliding = velocity - normal_velocity * n;
        const double speed = sliding.norm();
        if (speed > 0.0) {
          // Coulomb, regularized: full strength above the sliding velocity.
          const double scale = std::min(speed / std::max(settings.sliding_velocity, 1e-300), 1.0);
          f -= settings.friction * std::max(normal_force, 0.0) * scale * sliding / speed;
        }
      }
      generalized += jacobian.transpose() * f;
    }
  };
}

double project_contacts(System& system, int model_index, const std::vector<Obstacle>& obstacles,
                        const std::vector<Eigen::Vector2d>& points,
                        const ContactSettings& settings) {
  for (const Obstacle& obstacle : obstacles) {
    check_obstacle(obstacle);
  }
  check_settings(settings);
  const Model& model = system.model(model_index);
  Eigen::VectorXd q = system.coordinates(model_index);
  Eigen::VectorXd qd = system.velocities(model_index);
  if (q.size() != qd.size()) {
    throw make_error("projection contacts need coordinates that are positions (", q.size(),
                     " coordinates, ", qd.size(), " velocities)");
  }
  const std::vector<int>& fixed = model.fixed_coordinates();
  double deepest_found = 0.0;
  bool changed = false;
  for (const Eigen::Vector2d& u : points) {
    const Eigen::Vector3d x = model.position(q, u);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    const double depth = deepest(obstacles, x, n);
    if (depth <= 0.0) {
      continue;
    }
    deepest_found = std::max(deepest_found, depth);
    // The point must be a node: one coordinate with weight 1 per component.
    const SparseMatrix jacobian = model.position_jacobian(q, u);
    std::array<int, 3> column{-1, -1, -1};
    bool node = jacobian.nonZeros() == 3;
    for (Eigen::Index col = 0; col < jacobian.outerSize() && node; ++col) {
      for (SparseMatrix::InnerIterator it(jacobian, col); it; ++it) {
        if (it.value() != 1.0) {
          node = false;
        } else {
          column[static_cast<size_t>(it.row())] = static_cast<int>(col);
        }
      }
    }
    const auto is_fixed = [&fixed](int c) {
      return std::binary_search(fixed.begin(), fixed.end(), c);
    };
    if (!node || std::find(column.begin(), column.end(), -1) != column.end() ||
        std::any_of(column.begin(), column.end(), is_fixed)) {
      continue;  // not a node, or a node with a fixed coordinate (it must not move)
    }
    Eigen::Vector3d velocity;
    for (int c = 0; c < 3; ++c) {
      q[column[static_cast<size_t>(c)]] += depth * n[c];
      velocity[c] = qd[column[static_cast<size_t>(c)]];
    }
    const double normal_velocity = velocity.dot(n);
    if (normal_velocity < 0.0) {
      Eigen::Vector3d tangential = velocity - normal_velocity * n;
      const double speed = tangential.norm();
      if (settings.friction > 0.0 && speed > 0.0) {
        tangential *= std::max(0.0, 1.0 - settings.friction * (-normal_velocity) / speed);
      }
      velocity = tangential;
    }
    for (int c = 0; c < 3; ++c) {
      qd[column[static_cast<size_t>(c)]] = velocity[c];
    }
    changed = true;
  }
  if (changed) {
    system.set_coordinates(model_index, q);
    system.set_velocities(model_index, qd);
  }
  return deepest_found;
}

double max_penetration(const System& system, int model_index,
                       const std::vector<Obstacle>& obstacles,
                       const std::vector<Eigen::Vector2d>& points) {
  const Model& model = system.model(model_index);
  const auto q = system.coordinates(model_index);
  double depth = 0.0;
  for (const Eigen::Vector2d& u : points) {
    depth = std::max(depth, penetration_depth(obstacles, model.position(q, u)));
  }
  return depth;
}

}  // namespace dnurbs
