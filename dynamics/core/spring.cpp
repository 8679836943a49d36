#include "dnurbs/dynamics/core/spring.h"

#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

void check_stiffness(double stiffness) {
  if (!(stiffness >= 0.0) || !std::isfinite(stiffness)) {
    throw make_error("spring stiffness ", stiffness, " is not a non-negative finite number");
  }
}

}  // namespace

Spring mouse_spring(const Eigen::Vector2d& u, VectorOfTime target, double stiffness) {
  check_stiffness(stiffness);
  if (!u.allFinite()) {
    throw make_error("spring parameter (", u.x(), ", ", u.y(), ") is not finite");
  }
  if (!target) {
    throw make_error("spring at u = (", u.x(), ", ", u.y(), ") has no target function");
  }
  return [u, target = std::move(target), stiffness](double t) {
    return SpringState{u, target(t), stiffness};
  };
}

Spring mouse_spring(double u, VectorOfTime target, double stiffness) {
  return mouse_spring(Eigen::Vector2d(u, 0.0), std::move(target), stiffness);
}

Spring dragged_spring(ParameterOfTime u, VectorOfTime target, double stiffness) {
  check_stiffness(stiffness);
  if (!u || !target) {
    throw make_error("dragged spring has no ", !u ? "parameter" : "target", " function");
  }
  return [u = std::move(u), target = std::move(target), stiffness](double t) {
    return SpringState{u(t), target(t), stiffness};
  };
}

Spring windowed_spring(Spring spring, double start, double end) {
  if (!spring) {
    throw make_error("windowed spring has no spring function");
  }
  return [spring = std::move(spring), start, end](double t) {
    SpringState state = spring(t);
    if (!(t >= start && t < end)) {
      state.stiffness = 0.0;
    }
    return state;
  };
}

void check_spring_state(const SpringState& state, int spring, double time) {
  if (!state.parameter.allFinite()) {
    throw make_error("spring ", spring, " at t = ", time, ": parameter (", state.parameter.x(),
                     ", ", state.parameter.y(), ") is not finite");
  }
  if (!state.target.allFinite()) {
    throw make_error("spring ", spring, " at t = ", time, ": target (", state.target.x(), ", ",
                     state.target.y(), ", ", state.target.z(), ") is not finite");
  }
  if (!(state.stiffness >= 0.0) || !std::isfinite(state.stiffness)) {
    throw make_error("spring ", spring, " at t = ", time, ": stiffness ", state.stiffness,
                     " is not a non-negative finite number");
  }
}

}  // namespace dnurbs
