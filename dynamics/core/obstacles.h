#pragma once
// Rigid obstacles for the grid scenes of Wu & de Melo (a table cloth falling on a table, sheets on
// the ground): a ground plane, a box (table) and a sphere, met either by penalty forces (an
// applied Force) or by projection of the contact points after each step, with friction off
// (coefficient 0) or on (Coulomb).

#include <variant>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// The half-space above a plane: free side along `normal`.
struct GroundPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};
/// An axis-aligned box (a table top), solid inside.
struct BoxObstacle {
  Eigen::Vector3d minimum = Eigen::Vector3d::Zero();
  Eigen::Vector3d maximum = Eigen::Vector3d::Ones();
};
/// A solid sphere.
struct SphereObstacle {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 1.0;
};
using Obstacle = std::variant<GroundPlane, BoxObstacle, SphereObstacle>;

/// Throws Error naming the value for a zero or non-finite normal, a box with minimum > maximum,
/// or a radius <= 0.
void check_obstacle(const Obstacle& obstacle);

/// Signed distance from x to the obstacle's surface (negative inside) and the outward unit
/// normal of the nearest surface point.
double signed_distance(const Obstacle& obstacle, const Eigen::Vector3d& x,
                       Eigen::Vector3d* normal = nullptr);

/// Penetration depth of x into the deepest obstacle (0 when outside all).
double penetration_depth(const std::vector<Obstacle>& obstacles, const Eigen::Vector3d& x);

struct ContactSettings {
  double stiffness = 1e4;  ///< penalty k: normal force k * depth
  double damping = 0.0;    ///< normal damping c: -c (v . n) while penetrating
  /// Coulomb coefficient (0: friction off). Penalty: |f_t| = friction |f_n| against the sliding
  /// velocity, regularized below `sliding_velocity`. Projection: the tangential velocity loses
  /// friction times the removed normal velocity (down to zero).
  double friction = 0.0;
  double sliding_velocity = 1e-3;
};

/// Penalty contact of the material points `points` of one model with the obstacles:
/// f = k depth n - c min(v . n, 0) n + friction, applied as L(u)^T f. Throws Error for bad
/// obstacles or settings.
Force penalty_contact(std::vector<Obstacle> obstacles, std::vector<Eigen::Vector2d> points,
                      const ContactSettings& settings);

/// Projection contact, called after each step: every point of model `model_index` that is
/// inside an obstacle is moved to the obstacle's surface along its normal, its inward normal
/// velocity removed and its tangential velocity reduced by friction. Only points that are
/// nodes (L(u) picks three coordinates with weight 1) are projected; nodes with a fixed
/// coordinate are left alone. Returns the deepest penetration found before projecting. The new
/// state goes through System::set_coordinates/set_velocities, so a Newmark integrator recomputes
/// its acceleration on the next step (the central and implicit-Euler schemes and the
/// SemiImplicitStepper need none).
double project_contacts(System& system, int model_index, const std::vector<Obstacle>& obstacles,
                        const std::vector<Eigen::Vector2d>& points,
                        const ContactSettings& settings);

/// The deepest penetration of the points of model `model_index` at the current state.
double max_penetration(const System& system, int model_index,
                       const std::vector<Obstacle>& obstacles,
                       const std::vector<Eigen::Vector2d>& points);

}  // namespace dnurbs
