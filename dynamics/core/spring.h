#pragma once
// Springs of interactive sculpting ("mouse springs"): a spring of stiffness k pulls the material
// point u of a model toward a target, with the force f = k (target - x(u)) at the point and the
// generalized force L(u)^T f (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and
// Generalized Formulations, below eq. 1.26: f_q = integral J^T f). Unlike an applied Force, a
// spring added with System::add_spring is implicit in the integrators: its stiffness k L^T L
// enters the step matrix (dynamics/integrators/implicit_springs.h), so that no stiffness or time
// step makes the step unstable. Its energy is (1/2) k |x(u) - target|^2.
//
// A spring is a function of time giving its parameter, target and stiffness: a fixed spring, a
// windowed one (stiffness 0 outside its window) and a drag (parameter and target moving every
// step) are all springs.

#include <functional>

#include <Eigen/Core>

namespace dnurbs {

/// A 3-vector function of time.
using VectorOfTime = std::function<Eigen::Vector3d(double)>;
/// A scalar function of time.
using ScalarOfTime = std::function<double(double)>;
/// A material parameter (u, v) as a function of time (curves use u only).
using ParameterOfTime = std::function<Eigen::Vector2d(double)>;

/// Where a spring acts, where it pulls and how hard, at one time.
struct SpringState {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();  ///< the material point u
  Eigen::Vector3d target = Eigen::Vector3d::Zero();     ///< where x(u) is pulled
  double stiffness = 0.0;                               ///< k >= 0; 0: the spring is off
};

/// A spring: its state at time t.
using Spring = std::function<SpringState(double time)>;

/// A spring of stiffness k at the fixed material point u toward a target that moves in time.
/// Throws Error if k is negative or not finite, u not finite or target empty.
Spring mouse_spring(const Eigen::Vector2d& u, VectorOfTime target, double stiffness);
/// On a curve: the material point is the parameter u alone (as (u, 0)).
Spring mouse_spring(double u, VectorOfTime target, double stiffness);

/// A drag: a spring whose material point and target both move in time. Throws Error as
/// mouse_spring for k and for empty functions.
Spring dragged_spring(ParameterOfTime u, VectorOfTime target, double stiffness);

/// `spring` while start <= t < end, stiffness 0 outside that window (as windowed forces).
Spring windowed_spring(Spring spring, double start, double end);

/// Throws Error naming the spring, the time and the value if `state` has a non-finite parameter
/// or target or a stiffness that is negative or not finite.
void check_spring_state(const SpringState& state, int spring, double time);

}  // namespace dnurbs
