#include "dnurbs/dynamics/core/forces.h"

#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

Force point_force(const Eigen::Vector2d& u, VectorOfTime force) {
  if (!force) {
    throw make_error("point force at u = (", u.x(), ", ", u.y(), ") has no force function");
  }
  return [u, force = std::move(force)](const Model& model, double t, ConstVectorRef q,
                                       ConstVectorRef /*qd*/, VectorRef generalized) {
    model.add_point_force(q, u, force(t), generalized);
  };
}

Force point_force(const Eigen::Vector2d& u, const Eigen::Vector3d& force) {
  return point_force(u, [force](double) { return force; });
}

Force point_force(double u, VectorOfTime force) {
  return point_force(Eigen::Vector2d(u, 0.0), std::move(force));
}

Force point_force(double u, const Eigen::Vector3d& force) {
  return point_force(Eigen::Vector2d(u, 0.0), force);
}

Force spring_force(const Eigen::Vector2d& u, VectorOfTime target, double stiffness) {
  if (!(stiffness >= 0.0) || !std::isfinite(stiffness)) {
    throw make_error("spring stiffness ", stiffness, " is not a non-negative finite number");
  }
  if (!target) {
    throw make_error("spring at u = (", u.x(), ", ", u.y(), ") has no target function");
  }
  return [u, target = std::move(target), stiffness](const Model& model, double t, ConstVectorRef q,
                                                    ConstVectorRef /*qd*/, VectorRef generalized) {
    const Eigen::Vector3d f = stiffness * (target(t) - model.position(q, u));
    model.add_point_force(q, u, f, generalized);
  };
}

Force spring_force(double u, VectorOfTime target, double stiffness) {
  return spring_force(Eigen::Vector2d(u, 0.0), std::move(target), stiffness);
}

Force control_point_force(std::vector<int> control_points, VectorOfTime force) {
  if (!force) {
    throw make_error("control point force has no force function");
  }
  return [points = std::move(control_points), force = std::move(force)](
             const Model& model, double t, ConstVectorRef /*q*/, ConstVectorRef /*qd*/,
             VectorRef generalized) {
    const Eigen::Vector3d f = force(t);
    for (const int i : points) {
      generalized.segment<3>(model.control_point_offset(i)) += f;
    }
  };
}

Force control_point_force(std::vector<int> control_points, const Eigen::Vector3d& force) {
  return control_point_force(std::move(control_points), [force](double) { return force; });
}

Force coordinate_force(std::vector<int> coordinates, ScalarOfTime value) {
  if (!value) {
    throw make_error("coordinate force has no value function");
  }
  return [indices = std::move(coordinates), value = std::move(value)](
             const Model& model, double t, ConstVectorRef /*q*/, ConstVectorRef /*qd*/,
             VectorRef generalized) {
    const double f = value(t);
    for (const int i : indices) {
      if (i < 0 || i >= model.velocity_count()) {
        throw make_error("coordinate force index ", i, " is outside 0..",
                         model.velocity_count() - 1);
      }
      generalized[i] += f;
    }
  };
}

Force gravity(const Eigen::Vector3d& acceleration) {
  if (!acceleration.allFinite()) {
    throw make_error("gravity (", acceleration.x(), ", ", acceleration.y(), ", ", acceleration.z(),
                     ") is not finite");
  }
  return [acceleration](const Model& model, double /*t*/, ConstVectorRef q, ConstVectorRef /*qd*/,
                        VectorRef generalized) {
    model.add_distributed_force(
        q,
        [&acceleration](const MaterialSample& sample) -> Eigen::Vector3d {
          return sample.mass_density * acceleration;
        },
        generalized);
  };
}

Force pressure(ScalarOfTime pressure) {
  if (!pressure) {
    throw make_error("pressure force has no pressure function");
  }
  return [pressure = std::move(pressure)](const Model& model, double t, ConstVectorRef q,
                                          ConstVectorRef /*qd*/, VectorRef generalized) {
    const double p = pressure(t);
    model.add_distributed_force(
        q,
        [p](const MaterialSample& sample) -> Eigen::Vector3d {
          return p * sample.tangent_u.cross(sample.tangent_v);
        },
        generalized);
  };
}

Force pressure(double value) {
  return pressure([value](double) { return value; });
}

Force wind(VectorOfTime wind_velocity, double drag) {
  if (!(drag >= 0.0) || !std::isfinite(drag)) {
    throw make_error("wind drag ", drag, " is not a non-negative finite number");
  }
  if (!wind_velocity) {
    throw make_error("wind force has no velocity function");
  }
  return [wind_velocity = std::move(wind_velocity), drag](const Model& model, double t,
                                                          ConstVectorRef q, ConstVectorRef qd,
                                                          VectorRef generalized) {
    const Eigen::Vector3d v = wind_velocity(t);
    model.add_distributed_force(
        q,
        [&](const MaterialSample& sample) -> Eigen::Vector3d {
          // Terzopoulos et al. 1987, section 5: drag (n . (v - xdot)) n per unit area, times the
          // area element |x_u x x_v| per unit parametric area
          const Eigen::Vector3d normal = sample.tangent_u.cross(sample.tangent_v);
          const double area_element = normal.norm();
          if (area_element == 0.0) {
            return Eigen::Vector3d::Zero();  // curves and degenerate points
          }
          const Eigen::Vector3d velocity = model.position_jacobian(q, sample.parameter) * qd;
          return (drag * normal.dot(v - velocity) / area_element) * normal;
        },
        generalized);
  };
}

Force wind(const Eigen::Vector3d& wind_velocity, double drag) {
  if (!wind_velocity.allFinite()) {
    throw make_error("wind velocity (", wind_velocity.x(), ", ", wind_velocity.y(), ", ",
                     wind_velocity.z(), ") is not finite");
  }
  return wind([wind_velocity](double) { return wind_velocity; }, drag);
}

Force windowed(Force force, double start, double end) {
  return [force = std::move(force), start, end](const Model& model, double time, ConstVectorRef q,
                                                ConstVectorRef qd, VectorRef f) {
    if (time >= start && time < end) {
      force(model, time, q, qd, f);
    }
  };
}

}  // namespace dnurbs
