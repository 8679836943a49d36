#include "constraints/surface_constraints.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "constraints/point_constraints.h"
#include "dynamics/dnurbs/dnurbs_curve.h"
#include "dynamics/dnurbs/dnurbs_surface.h"
#include "nurbs/closest_point.h"
#include "core/error.h"
#include "nurbs/jacobian.h"

namespace dnurbs {
namespace {

const DNurbsSurface& dnurbs_surface(const System& system, int model, const char* what) {
  if (model < 0 || model >= system.model_count()) {
    throw make_error(what, ": model index ", model, " is out of range (the system has ",
                     system.model_count(), " models)");
  }
  const auto* surface = dynamic_cast<const DNurbsSurface*>(&system.model(model));
  if (surface == nullptr) {
    throw make_error(what, ": model ", model, " is not a D-NURBS surface");
  }
  return *surface;
}

}  // namespace

SurfaceNormalConstraint::SurfaceNormalConstraint(int model, const Eigen::Vector2d& uv,
                                                 const Eigen::Vector3d& direction)
    : model_(model), uv_(uv), direction_(direction) {
  const double length = direction.norm();
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw make_error("surface normal constraint: direction (", direction.x(), ", ", direction.y(),
                     ", ", direction.z(), ") must be finite and non-zero");
  }
  direction_ /= length;
  // Any unit vector not parallel to the direction seeds the orthonormal pair.
  const Eigen::Vector3d seed =
      std::abs(direction_.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1_ = direction_.cross(seed).normalized();
  e2_ = direction_.cross(e1_);
}

std::unique_ptr<Constraint> SurfaceNormalConstraint::clone() const {
  return std::make_unique<SurfaceNormalConstraint>(*this);
}

std::string SurfaceNormalConstraint::description() const {
  std::ostringstream text;
  text << "normal of model " << model_ << " at (" << uv_.x() << ", " << uv_.y()
       << ") held parallel to (" << direction_.x() << ", " << direction_.y() << ", "
       << direction_.z() << ")";
  return text.str();
}

void SurfaceNormalConstraint::check(const System& system) const {
  dnurbs_surface(system, model_, "surface normal constraint");
  check_material_point(system, model_, uv_, "surface normal constraint");
}

void SurfaceNormalConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                       double /*time*/, ConstraintRows& rows) const {
  const DNurbsSurface& model = dnurbs_surface(system, model_, "surface normal constraint");
  const ModelView view = model_view(system, model_, q, qd);
  const NurbsSurface surface = model.surface(view.q);
  const WeightMode mode = model.weight_mode();
  SurfaceJacobian jacobian;
  surface_jacobian(surface, uv_.x(), uv_.y(), 1, mode, jacobian);
  const auto u_index = static_cast<int>(SurfaceQuantity::kU);
  const auto v_index = static_cast<int>(SurfaceQuantity::kV);
  const Eigen::Vector3d& Su = jacobian.point_derivatives[static_cast<size_t>(u_index)];
  const Eigen::Vector3d& Sv = jacobian.point_derivatives[static_cast<size_t>(v_index)];
  const Eigen::Vector3d normal = Su.cross(Sv);

  // Rates Sdot_u = J_u qd, Sdot_v = J_v qd, and Jdot qd (free weights only).
  const Eigen::MatrixX3d point_rates = model.control_points(view.qd);
  const Eigen::VectorXd weight_rates = mode == WeightMode::kFree
                                           ? model.weights(view.qd)
                                           : Eigen::VectorXd::Zero(model.control_point_count());
  Eigen::Vector3d Su_rate = Eigen::Vector3d::Zero();
  Eigen::Vector3d Sv_rate = Eigen::Vector3d::Zero();
  for (int a = 0; a < jacobian.active_count; ++a) {
    const int point = jacobian.control_point[static_cast<size_t>(a)];
    Su_rate += jacobian.basis(u_index, a) * point_rates.row(point).transpose();
    Sv_rate += jacobian.basis(v_index, a) * point_rates.row(point).transpose();
    if (mode == WeightMode::kFree) {
      Su_rate += jacobian.weight_column[static_cast<size_t>(u_index)].col(a) * weight_rates[point];
      Sv_rate += jacobian.weight_column[static_cast<size_t>(v_index)].col(a) * weight_rates[point];
    }
  }
  Eigen::Vector3d Su_acceleration_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d Sv_acceleration_bias = Eigen::Vector3d::Zero();
  if (mode == WeightMode::kFree) {
    std::array<Eigen::Vector3d, 6> rates;
    surface_jacobian_rate(surface, uv_.x(), uv_.y(), 1, point_rates, weight_rates, rates);
    Su_acceleration_bias = rates[static_cast<size_t>(u_index)];
    Sv_acceleration_bias = rates[static_cast<size_t>(v_index)];
  }
  const Eigen::Vector3d normal_rate = Su_rate.cross(Sv) + Su.cross(Sv_rate);
  const Eigen::Vector3d normal_bias = 2.0 * Su_rate.cross(Sv_rate) +
                                      Su_acceleration_bias.cross(Sv) +
                                      Su.cross(Sv_acceleration_bias);
  const std::array<const Eigen::Vector3d*, 2> basis = {&e1_, &e2_};
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d& e = *basis[static_cast<size_t>(k)];
    const int row = rows.row + k;
    (*rows.value)[row] = e.dot(normal);
    (*rows.rate)[row] = e.dot(normal_rate);
    (*rows.sigma)[row] = -e.dot(normal_bias);
    // e.(dSu x Sv) = dSu.(Sv x e) and e.(Su x dSv) = dSv.(e x Su).
    const Eigen::Vector3d along_u = Sv.cross(e);
    const Eigen::Vector3d along_v = e.cross(Su);
    for (int a = 0; a < jacobian.active_count; ++a) {
      const int point = jacobian.control_point[static_cast<size_t>(a)];
      const int column = view.velocity_offset + model.control_point_offset(point);
      const Eigen::Vector3d coefficient =
          jacobian.basis(u_index, a) * along_u + jacobian.basis(v_index, a) * along_v;
      for (int c = 0; c < 3; ++c) {
        rows.jacobian->emplace_back(row, column + c, coefficient[c]);
      }
      if (mode == WeightMode::kFree) {
        const double weight_coefficient =
            jacobian.weight_column[static_cast<size_t>(u_index)].col(a).dot(along_u) +
            jacobian.weight_column[static_cast<size_t>(v_index)].col(a).dot(along_v);
        rows.jacobian->emplace_back(row, view.velocity_offset + model.weight_offset(point),
                                    weight_coefficient);
      }
    }
  }
}

std::vector<std::unique_ptr<Constraint>> curve_on_surface_constraints(const System& system,
                                                                      int curve_model,
                                                                      int surface_model,
                                                                      int sample_count) {
  const DNurbsSurface& surface_dynamics = dnurbs_surface(system, surface_model, "curve on surface");
  if (curve_model < 0 || curve_model >= system.model_count()) {
    throw make_error("curve on surface: model index ", curve_model, " is out of range");
  }
  const auto* curve_dynamics = dynamic_cast<const DNurbsCurve*>(&system.model(curve_model));
  if (curve_dynamics == nullptr) {
    throw make_error("curve on surface: model ", curve_model, " is not a D-NURBS curve");
  }
  if (sample_count < 1) {
    throw make_error("curve on surface: sample count ", sample_count, " must be at least 1");
  }
  const NurbsCurve curve = curve_dynamics->curve(system.coordinates(curve_model));
  const NurbsSurface surface = surface_dynamics.surface(system.coordinates(surface_model));
  const double start = curve.knots().domain_start();
  const double end = curve.knots().domain_end();
  std::vector<std::unique_ptr<Constraint>> constraints;
  for (int k = 0; k < sample_count; ++k) {
    const double t =
        sample_count == 1 ? 0.5 * (start + end) : start + (end - start) * k / (sample_count - 1);
    const SurfaceProjection projection = closest_point(surface, curve.point(t));
    constraints.push_back(std::make_unique<PointToPointConstraint>(
        curve_model, Eigen::Vector2d(t, 0.0), surface_model, projection.parameter));
  }
  return constraints;
}

}  // namespace dnurbs
