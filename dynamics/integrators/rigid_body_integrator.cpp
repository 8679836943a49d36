#include "dnurbs/dynamics/integrators/rigid_body_integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "dnurbs/core/error.h"
#include "dnurbs/core/rotation.h"

namespace dnurbs {

namespace {

/// One body's data and its step unknowns.
struct Body {
  int coordinate_offset = 0;
  int velocity_offset = 0;
  double mass = 0.0;
  Eigen::Vector3d centre_offset;  ///< centre of mass in the body frame
  Eigen::Matrix3d inertia;        ///< about the centre of mass, body frame
  double alpha = 0.0;
  // State at t: centre of mass x, its velocity v, orientation, body angular velocity.
  Eigen::Vector3d x, v, omega;
  Eigen::Quaterniond orientation;
  // Unknowns at t + h.
  Eigen::Vector3d v_new, omega_new;
  // Applied force resultant (world) and torque about the centre of mass (body frame).
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

}  // namespace

RigidBodyIntegrator::RigidBodyIntegrator(RigidBodyIntegratorSettings settings)
    : settings_(settings) {
  if (!(settings_.tolerance > 0.0) || !std::isfinite(settings_.tolerance)) {
    throw make_error("rigid body integrator tolerance ", settings_.tolerance,
                     " must be positive and finite");
  }
  if (settings_.max_iterations < 1) {
    throw make_error("rigid body integrator iteration limit ", settings_.max_iterations,
                     " must be at least 1");
  }
}

namespace {

// The bodies of the system: centre-of-mass state from (c, quaternion, cdot, w).
std::vector<Body> gather_bodies(const System& system) {
  const Eigen::VectorXd& q = system.coordinates();
  const Eigen::VectorXd& qd = system.velocities();
  std::vector<Body> bodies(static_cast<size_t>(system.model_count()));
  for (int i = 0; i < system.model_count(); ++i) {
    const std::optional<RigidBodyProperties> rigid = system.model(i).rigid_body();
    if (!rigid) {
      throw make_error("model ", i,
                       " is not a free rigid body (a rigid model with free translation and "
                       "rotation): the rigid body integrator cannot step it");
    }
    Body& body = bodies[static_cast<size_t>(i)];
    body.coordinate_offset = system.coordinate_offset(i);
    body.velocity_offset = system.velocity_offset(i);
    body.mass = rigid->mass.mass;
    body.centre_offset = rigid->mass.centre_of_mass;
    body.inertia = rigid->mass.inertia_about_centre;
    body.alpha = rigid->damping_alpha;
    const auto qi = q.segment<7>(body.coordinate_offset);
    const auto vi = qd.segment<6>(body.velocity_offset);
    body.orientation = unit_quaternion(qi.segment<4>(3));
    const Eigen::Matrix3d rotation = body.orientation.toRotationMatrix();
    body.omega = vi.segment<3>(3);
    body.x = qi.head<3>() + rotation * body.centre_offset;
    body.v = vi.head<3>() + rotation * body.omega.cross(body.centre_offset);
    body.v_new = body.v;
    body.omega_new = body.omega;
  }
  return bodies;
}

// A body's midpoint state (c, quaternion; cdot, w) written into the stacked q_mid, v_mid;
// returns its rotation there.
Eigen::Matrix3d fill_midpoint(const Body& body, double h, Eigen::VectorXd& q_mid,
                              Eigen::VectorXd& v_mid) {
  const Eigen::Vector3d omega_mid = 0.5 * (body.omega + body.omega_new);
  const Eigen::Vector3d v_com = 0.5 * (body.v + body.v_new);
  const Eigen::Quaterniond orientation = body.orientation * cayley(0.5 * h * omega_mid);
  Eigen::Matrix3d rotation = orientation.toRotationMatrix();
  const Eigen::Vector3d x = body.x + 0.5 * h * v_com;
  q_mid.segment<3>(body.coordinate_offset) = x - rotation * body.centre_offset;
  q_mid.segment<4>(body.coordinate_offset + 3) << orientation.w(), orientation.x(), orientation.y(),
      orientation.z();
  v_mid.segment<3>(body.velocity_offset) = v_com - rotation * omega_mid.cross(body.centre_offset);
  v_mid.segment<3>(body.velocity_offset + 3) = omega_mid;
  return rotation;
}

// The applied forces at the midpoint state (time t + h/2): each body's resultant and its torque
// about the centre of mass (body frame). L^T f has the world force on c and the body torque
// about c: shift it to the centre of mass, tau_com = tau_c - c_m x (R^T f).
void midpoint_forces(const System& system, double t, double h, std::vector<Body>& bodies) {
  Eigen::VectorXd q_mid = system.coordinates();
  Eigen::VectorXd v_mid = system.velocities();
  std::vector<Eigen::Matrix3d> rotations;
  rotations.reserve(bodies.size());
  for (const Body& body : bodies) {
    rotations.push_back(fill_midpoint(body, h, q_mid, v_mid));
  }
  Eigen::VectorXd generalized = Eigen::VectorXd::Zero(system.velocity_count());
  system.add_applied_forces(t + 0.5 * h, q_mid, v_mid, generalized);
  for (size_t i = 0; i < bodies.size(); ++i) {
    Body& body = bodies[i];
    body.force = generalized.segment<3>(body.velocity_offset);
    body.torque = generalized.segment<3>(body.velocity_offset + 3) -
                  body.centre_offset.cross(rotations[i].transpose() * body.force);
  }
}

// Body angular velocity at t + h: Newton on the midpoint rule for Euler's equations; `iterations`
// is raised to the iterations used.
Eigen::Vector3d solve_rotation(const Body& body, double h,
                               const RigidBodyIntegratorSettings& settings, int& iterations,
                               double t, double dt) {
  // Newton on r(w') = I (w' - w) + h w_m x I w_m + h alpha I w_m - h tau.
  Eigen::Vector3d omega_new = body.omega_new;
  double previous = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= settings.max_iterations; ++k) {
    const Eigen::Vector3d omega_mid = 0.5 * (body.omega + omega_new);
    const Eigen::Vector3d momentum = body.inertia * omega_mid;
    const Eigen::Vector3d residual = body.inertia * (omega_new - body.omega) +
                                     h * omega_mid.cross(momentum) + h * body.alpha * momentum -
                                     h * body.torque;
    const Eigen::Matrix3d tangent =
        body.inertia + 0.5 * h *
                           (cross_matrix(omega_mid) * body.inertia - cross_matrix(momentum) +
                            body.alpha * body.inertia);
    const Eigen::Vector3d delta = tangent.partialPivLu().solve(residual);
    omega_new -= delta;
    iterations = std::max(iterations, k);
    // Converged at the tolerance, or at round-off (the update stopped shrinking).
    const double size = delta.norm();
    if (size <= settings.tolerance * std::max(omega_new.norm(), 1e-300) ||
        (k >= 3 && size >= previous && size <= 1e3 * settings.tolerance * omega_new.norm())) {
      return omega_new;
    }
    previous = size;
  }
  throw make_error(
      "rigid body integrator: Newton on the angular velocity did not converge "
      "in ",
      settings.max_iterations, " iterations at t = ", t, " with dt = ", dt,
      "; the state is unchanged");
}

}  // namespace

void RigidBodyIntegrator::step(System& system, double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) {
    throw make_error("time step dt = ", dt, " must be positive and finite");
  }
  if (!system.fixed_coordinates().empty()) {
    throw make_error("the rigid body integrator does not support fixed coordinates (",
                     system.fixed_coordinates().size(), " are fixed)");
  }
  const double h = dt;
  const double t = system.time();
  std::vector<Body> bodies = gather_bodies(system);

  // Fixed point on the applied forces (one pass without forces), Newton on each body's w'
  last_iterations_ = 0;
  const bool forces = system.has_forces();
  bool converged = false;
  for (int outer = 0; outer < settings_.max_iterations && !converged; ++outer) {
    if (forces) {
      midpoint_forces(system, t, h, bodies);
    }
    converged = true;
    for (Body& body : bodies) {
      // Translation (closed form): m (v' - v) = h (f - alpha m (v + v')/2).
      const double damping = 0.5 * h * body.alpha;
      const Eigen::Vector3d v_new =
          ((1.0 - damping) * body.v + (h / body.mass) * body.force) / (1.0 + damping);
      const Eigen::Vector3d omega_new = solve_rotation(body, h, settings_, last_iterations_, t, dt);
      const double change = (omega_new - body.omega_new).norm() + (v_new - body.v_new).norm();
      const double scale = omega_new.norm() + v_new.norm();
      if (forces && change > 1e3 * settings_.tolerance * std::max(scale, 1e-300)) {
        converged = false;
      }
      body.v_new = v_new;
      body.omega_new = omega_new;
    }
    if (forces && !converged && outer + 1 == settings_.max_iterations) {
      throw make_error(
          "rigid body integrator: the applied forces' fixed point did not converge "
          "in ",
          settings_.max_iterations, " iterations at t = ", t, " with dt = ", dt,
          "; the state is unchanged");
    }
  }

  // New state: R' = R cay(h w_m), x' = x + h v_m, back to (c, quaternion; cdot, w)
  Eigen::VectorXd q_new = system.coordinates();
  Eigen::VectorXd v_new = system.velocities();
  for (const Body& body : bodies) {
    const Eigen::Vector3d omega_mid = 0.5 * (body.omega + body.omega_new);
    const Eigen::Quaterniond orientation = (body.orientation * cayley(h * omega_mid)).normalized();
    const Eigen::Matrix3d rotation = orientation.toRotationMatrix();
    const Eigen::Vector3d x = body.x + 0.5 * h * (body.v + body.v_new);
    q_new.segment<3>(body.coordinate_offset) = x - rotation * body.centre_offset;
    q_new.segment<4>(body.coordinate_offset + 3) << orientation.w(), orientation.x(),
        orientation.y(), orientation.z();
    v_new.segment<3>(body.velocity_offset) =
        body.v_new - rotation * body.omega_new.cross(body.centre_offset);
    v_new.segment<3>(body.velocity_offset + 3) = body.omega_new;
  }
  if (!q_new.allFinite() || !v_new.allFinite()) {
    throw make_error("rigid body integrator step from t = ", t, " with dt = ", dt,
                     " produced a non-finite state; the state is unchanged");
  }
  system.set_state(q_new, v_new, t + dt);
}

}  // namespace dnurbs
