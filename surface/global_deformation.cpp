#include "dnurbs/surface/global_deformation.h"

#include <cmath>
#include <numbers>

#include "dnurbs/core/error.h"

namespace dnurbs {

DeformationStep<2> taper(const Eigen::Vector3d& p, double t1, double t2, double half_height) {
  const double x = p.x();
  const double y = p.y();
  const double zeta = p.z() / half_height;  // normalized height z/h
  const double f1 = t1 * zeta + 1.0;
  const double f2 = t2 * zeta + 1.0;
  DeformationStep<2> step;
  step.point = {f1 * x, f2 * y, p.z()};
  step.d_point << f1, 0.0, t1 * x / half_height,  //
      0.0, f2, t2 * y / half_height,              //
      0.0, 0.0, 1.0;
  step.d_parameters << zeta * x, 0.0,  //
      0.0, zeta * y,                   //
      0.0, 0.0;
  // d(z/h)/dh = -z/h^2.
  step.d_half_height = {-t1 * zeta * x / half_height, -t2 * zeta * y / half_height, 0.0};
  return step;
}

DeformationStep<3> bend(const Eigen::Vector3d& p, double b1, double b2, double b3,
                        double half_height) {
  const double pi = std::numbers::pi;
  const double shifted = p.z() + b2;
  const double angle = shifted / half_height * pi * b3;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  DeformationStep<3> step;
  step.point = {p.x() + b1 * cosine, p.y(), p.z()};
  // d angle/dz = d angle/db2 = pi b3/h, d angle/db3 = pi (z + b2)/h, d angle/dh = -angle/h.
  const double slope = -b1 * sine;                          // d x'/d angle
  step.d_point << 1.0, 0.0, slope * pi * b3 / half_height,  //
      0.0, 1.0, 0.0,                                        //
      0.0, 0.0, 1.0;
  step.d_parameters << cosine, slope * pi * b3 / half_height, slope * pi * shifted / half_height,
      0.0, 0.0, 0.0,  //
      0.0, 0.0, 0.0;
  step.d_half_height = {-slope * angle / half_height, 0.0, 0.0};
  return step;
}

DeformationStep<1> twist(const Eigen::Vector3d& p, double tau, double half_height) {
  const double x = p.x();
  const double y = p.y();
  const double angle = tau * p.z() / half_height;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  // d(x', y')/d angle = (-x sin - y cos, x cos - y sin): the rotated point turned by 90 degrees.
  const double dx_dangle = -x * sine - y * cosine;
  const double dy_dangle = x * cosine - y * sine;
  DeformationStep<1> step;
  step.point = {x * cosine - y * sine, x * sine + y * cosine, p.z()};
  step.d_point << cosine, -sine, dx_dangle * tau / half_height,  //
      sine, cosine, dy_dangle * tau / half_height,               //
      0.0, 0.0, 1.0;
  step.d_parameters << dx_dangle * p.z() / half_height, dy_dangle * p.z() / half_height, 0.0;
  // d angle/dh = -angle/h.
  step.d_half_height = {-dx_dangle * angle / half_height, -dy_dangle * angle / half_height, 0.0};
  return step;
}

DeformationStep<2> shear(const Eigen::Vector3d& p, double sx, double sy) {
  DeformationStep<2> step;
  step.point = {p.x() + sx * p.z(), p.y() + sy * p.z(), p.z()};
  step.d_point << 1.0, 0.0, sx,  //
      0.0, 1.0, sy,              //
      0.0, 0.0, 1.0;
  step.d_parameters << p.z(), 0.0,  //
      0.0, p.z(),                   //
      0.0, 0.0;
  step.d_half_height.setZero();
  return step;
}

void validate_global_deformation_parameters(const GlobalDeformationParameters& parameters) {
  static constexpr const char* kNames[kGlobalDeformationParameterCount] = {
      "taper t1",          "taper t2",  "bend amplitude b1", "bend offset b2",
      "bend frequency b3", "twist tau", "shear sx",          "shear sy"};
  for (int k = 0; k < kGlobalDeformationParameterCount; ++k) {
    if (!std::isfinite(parameters[k])) {
      throw make_error("global deformation ", kNames[k], " is ", parameters[k],
                       "; it must be finite");
    }
  }
}

namespace {

/// Forward accumulation of the chain rule: after `step` (evaluated at the current point) the
/// composite derivatives become A * previous, plus the step's own columns.
template <int ParameterCount>
void accumulate(const DeformationStep<ParameterCount>& step, int first_parameter,
                DeformationStep<kGlobalDeformationParameterCount>& total) {
  total.point = step.point;
  total.d_point = step.d_point * total.d_point;
  total.d_parameters = step.d_point * total.d_parameters;
  total.d_parameters.template middleCols<ParameterCount>(first_parameter) += step.d_parameters;
  total.d_half_height = step.d_point * total.d_half_height + step.d_half_height;
}

}  // namespace

DeformationStep<kGlobalDeformationParameterCount> apply_global_deformation(
    const GlobalDeformationParameters& parameters, double half_height, const Eigen::Vector3d& p) {
  using G = GlobalDeformationParameter;
  DeformationStep<kGlobalDeformationParameterCount> total;
  total.point = p;
  total.d_point.setIdentity();
  total.d_parameters.setZero();
  total.d_half_height.setZero();
  // T = shear o twist o bend o taper, innermost first.
  accumulate(taper(total.point, parameters[G::kTaper1], parameters[G::kTaper2], half_height),
             G::kTaper1, total);
  accumulate(bend(total.point, parameters[G::kBendAmplitude], parameters[G::kBendOffset],
                  parameters[G::kBendFrequency], half_height),
             G::kBendAmplitude, total);
  accumulate(twist(total.point, parameters[G::kTwist], half_height), G::kTwist, total);
  accumulate(shear(total.point, parameters[G::kShearX], parameters[G::kShearY]), G::kShearX, total);
  return total;
}

// --- Rates: second derivatives of each step contracted with a motion (p_dot, theta_dot, h_dot).

DeformationStepRate<2> taper_rate(const Eigen::Vector3d& p, double t1, double t2,
                                  double half_height, const DeformationMotion<2>& motion) {
  const double h = half_height;
  const double x = p.x();
  const double y = p.y();
  const Eigen::Vector3d& p_dot = motion.point;
  const double t1_dot = motion.parameters[0];
  const double t2_dot = motion.parameters[1];
  const double h_dot = motion.half_height;
  const double zeta = p.z() / h;
  const double zeta_dot = p_dot.z() / h - p.z() * h_dot / (h * h);
  const double f1_dot = t1_dot * zeta + t1 * zeta_dot;
  const double f2_dot = t2_dot * zeta + t2 * zeta_dot;
  // d/dt (t x / h) for the z column of dT/dp.
  const double slope1_dot = (t1_dot * x + t1 * p_dot.x()) / h - t1 * x * h_dot / (h * h);
  const double slope2_dot = (t2_dot * y + t2 * p_dot.y()) / h - t2 * y * h_dot / (h * h);
  DeformationStepRate<2> rate;
  rate.point = {f1_dot * x + (t1 * zeta + 1.0) * p_dot.x(),
                f2_dot * y + (t2 * zeta + 1.0) * p_dot.y(), p_dot.z()};
  rate.d_point << f1_dot, 0.0, slope1_dot,  //
      0.0, f2_dot, slope2_dot,              //
      0.0, 0.0, 0.0;
  rate.d_parameters << zeta_dot * x + zeta * p_dot.x(), 0.0,  //
      0.0, zeta_dot * y + zeta * p_dot.y(),                   //
      0.0, 0.0;
  // d/dt (-t zeta x / h).
  rate.d_half_height = {-(t1_dot * zeta * x + t1 * zeta_dot * x + t1 * zeta * p_dot.x()) / h +
                            t1 * zeta * x * h_dot / (h * h),
                        -(t2_dot * zeta * y + t2 * zeta_dot * y + t2 * zeta * p_dot.y()) / h +
                            t2 * zeta * y * h_dot / (h * h),
                        0.0};
  return rate;
}

DeformationStepRate<3> bend_rate(const Eigen::Vector3d& p, double b1, double b2, double b3,
                                 double half_height, const DeformationMotion<3>& motion) {
  const double pi = std::numbers::pi;
  const double h = half_height;
  const Eigen::Vector3d& p_dot = motion.point;
  const double b1_dot = motion.parameters[0];
  const double b2_dot = motion.parameters[1];
  const double b3_dot = motion.parameters[2];
  const double h_dot = motion.half_height;
  const double shifted = p.z() + b2;
  const double shifted_dot = p_dot.z() + b2_dot;
  const double angle = shifted / h * pi * b3;
  const double angle_dot = pi * (shifted_dot * b3 + shifted * b3_dot) / h - angle * h_dot / h;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  const double slope = -b1 * sine;
  const double slope_dot = -b1_dot * sine - b1 * cosine * angle_dot;
  // d/dt (slope pi b3 / h), the z column of dT/dp and the b2 column of dT/dtheta.
  const double z_column_dot =
      pi * (slope_dot * b3 + slope * b3_dot) / h - slope * pi * b3 * h_dot / (h * h);
  DeformationStepRate<3> rate;
  rate.point = {p_dot.x() + b1_dot * cosine + slope * angle_dot, p_dot.y(), p_dot.z()};
  rate.d_point.setZero();
  rate.d_point(0, 2) = z_column_dot;
  rate.d_parameters.setZero();
  rate.d_parameters(0, 0) = -sine * angle_dot;
  rate.d_parameters(0, 1) = z_column_dot;
  rate.d_parameters(0, 2) =
      pi * (slope_dot * shifted + slope * shifted_dot) / h - slope * pi * shifted * h_dot / (h * h);
  rate.d_half_height = {
      -(slope_dot * angle + slope * angle_dot) / h + slope * angle * h_dot / (h * h), 0.0, 0.0};
  return rate;
}

DeformationStepRate<1> twist_rate(const Eigen::Vector3d& p, double tau, double half_height,
                                  const DeformationMotion<1>& motion) {
  const double h = half_height;
  const double x = p.x();
  const double y = p.y();
  const double z = p.z();
  const Eigen::Vector3d& p_dot = motion.point;
  const double tau_dot = motion.parameters[0];
  const double h_dot = motion.half_height;
  const double angle = tau * z / h;
  const double angle_dot = (tau_dot * z + tau * p_dot.z()) / h - angle * h_dot / h;
  const double cosine = std::cos(angle);
  const double sine = std::sin(angle);
  // X, Y = d(x', y')/d angle and their rates.
  const double dx_dangle = -x * sine - y * cosine;
  const double dy_dangle = x * cosine - y * sine;
  const double dx_dangle_dot = -p_dot.x() * sine - p_dot.y() * cosine - dy_dangle * angle_dot;
  const double dy_dangle_dot = p_dot.x() * cosine - p_dot.y() * sine + dx_dangle * angle_dot;
  // d/dt (W c / h) for W = X or Y and a factor c with rate c_dot.
  const auto scaled_rate = [&](double w, double w_dot, double c, double c_dot) {
    return (w_dot * c + w * c_dot) / h - w * c * h_dot / (h * h);
  };
  DeformationStepRate<1> rate;
  rate.point = {p_dot.x() * cosine - p_dot.y() * sine + dx_dangle * angle_dot,
                p_dot.x() * sine + p_dot.y() * cosine + dy_dangle * angle_dot, p_dot.z()};
  rate.d_point << -sine * angle_dot, -cosine * angle_dot,
      scaled_rate(dx_dangle, dx_dangle_dot, tau, tau_dot),  //
      cosine * angle_dot, -sine * angle_dot,
      scaled_rate(dy_dangle, dy_dangle_dot, tau, tau_dot),  //
      0.0, 0.0, 0.0;
  rate.d_parameters << scaled_rate(dx_dangle, dx_dangle_dot, z, p_dot.z()),
      scaled_rate(dy_dangle, dy_dangle_dot, z, p_dot.z()), 0.0;
  rate.d_half_height = {-scaled_rate(dx_dangle, dx_dangle_dot, angle, angle_dot),
                        -scaled_rate(dy_dangle, dy_dangle_dot, angle, angle_dot), 0.0};
  return rate;
}

DeformationStepRate<2> shear_rate(const Eigen::Vector3d& p, double sx, double sy,
                                  const DeformationMotion<2>& motion) {
  const Eigen::Vector3d& p_dot = motion.point;
  const double sx_dot = motion.parameters[0];
  const double sy_dot = motion.parameters[1];
  DeformationStepRate<2> rate;
  rate.point = {p_dot.x() + sx_dot * p.z() + sx * p_dot.z(),
                p_dot.y() + sy_dot * p.z() + sy * p_dot.z(), p_dot.z()};
  rate.d_point.setZero();
  rate.d_point(0, 2) = sx_dot;
  rate.d_point(1, 2) = sy_dot;
  rate.d_parameters << p_dot.z(), 0.0,  //
      0.0, p_dot.z(),                   //
      0.0, 0.0;
  rate.d_half_height.setZero();
  return rate;
}

namespace {

/// The rate form of accumulate(): differentiates F <- A F, D <- A D (+ P), H <- A H + H_step
/// in time (product rule), using the totals before this step.
template <int ParameterCount>
void accumulate_with_rate(const DeformationStep<ParameterCount>& step,
                          const DeformationStepRate<ParameterCount>& step_rate, int first_parameter,
                          GlobalDeformationWithRate& total) {
  auto& rate = total.rate;
  const auto& value = total.value;
  rate.point = step_rate.point;
  rate.d_point = step_rate.d_point * value.d_point + step.d_point * rate.d_point;
  rate.d_parameters = step_rate.d_point * value.d_parameters + step.d_point * rate.d_parameters;
  rate.d_parameters.template middleCols<ParameterCount>(first_parameter) += step_rate.d_parameters;
  rate.d_half_height = step_rate.d_point * value.d_half_height + step.d_point * rate.d_half_height +
                       step_rate.d_half_height;
  accumulate(step, first_parameter, total.value);
}

/// The motion of one step: the current point's rate, its parameters' rates, h's rate.
template <int ParameterCount>
DeformationMotion<ParameterCount> step_motion(
    const GlobalDeformationWithRate& total,
    const DeformationMotion<kGlobalDeformationParameterCount>& motion, int first_parameter) {
  DeformationMotion<ParameterCount> step;
  step.point = total.rate.point;
  step.parameters = motion.parameters.segment<ParameterCount>(first_parameter);
  step.half_height = motion.half_height;
  return step;
}

}  // namespace

GlobalDeformationWithRate apply_global_deformation_with_rate(
    const GlobalDeformationParameters& parameters, double half_height, const Eigen::Vector3d& p,
    const DeformationMotion<kGlobalDeformationParameterCount>& motion) {
  using G = GlobalDeformationParameter;
  const double h = half_height;
  GlobalDeformationWithRate total;
  total.value.point = p;
  total.value.d_point.setIdentity();
  total.value.d_parameters.setZero();
  total.value.d_half_height.setZero();
  total.rate.point = motion.point;
  total.rate.d_point.setZero();
  total.rate.d_parameters.setZero();
  total.rate.d_half_height.setZero();
  // T = shear o twist o bend o taper, innermost first, as in apply_global_deformation.
  {
    const double t1 = parameters[G::kTaper1];
    const double t2 = parameters[G::kTaper2];
    const Eigen::Vector3d at = total.value.point;
    accumulate_with_rate(taper(at, t1, t2, h),
                         taper_rate(at, t1, t2, h, step_motion<2>(total, motion, G::kTaper1)),
                         G::kTaper1, total);
  }
  {
    const double b1 = parameters[G::kBendAmplitude];
    const double b2 = parameters[G::kBendOffset];
    const double b3 = parameters[G::kBendFrequency];
    const Eigen::Vector3d at = total.value.point;
    accumulate_with_rate(
        bend(at, b1, b2, b3, h),
        bend_rate(at, b1, b2, b3, h, step_motion<3>(total, motion, G::kBendAmplitude)),
        G::kBendAmplitude, total);
  }
  {
    const double tau = parameters[G::kTwist];
    const Eigen::Vector3d at = total.value.point;
    accumulate_with_rate(twist(at, tau, h),
                         twist_rate(at, tau, h, step_motion<1>(total, motion, G::kTwist)),
                         G::kTwist, total);
  }
  {
    const double sx = parameters[G::kShearX];
    const double sy = parameters[G::kShearY];
    const Eigen::Vector3d at = total.value.point;
    accumulate_with_rate(shear(at, sx, sy),
                         shear_rate(at, sx, sy, step_motion<2>(total, motion, G::kShearX)),
                         G::kShearX, total);
  }
  return total;
}

}  // namespace dnurbs
