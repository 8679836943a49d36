#include "dnurbs/constraints/surface_constraints.h"

#include <cmath>
#include <sstream>
#include <variant>

#include <Eigen/Geometry>

#include "dnurbs/constraints/point_constraints.h"
#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/closest_point.h"

namespace dnurbs {
namespace {

const Model& checked_model(const System& system, int model, const char* what) {
  if (model < 0 || model >= system.model_count()) {
    throw make_error(what, ": model index ", model, " is out of range (the system has ",
                     system.model_count(), " models)");
  }
  return system.model(model);
}

// The exact NURBS shape (Model::exact_shape) of model `model` at the system's current state.
template <typename ShapeType>
ShapeType exact(const System& system, int model, const char* what, const char* kind) {
  const std::optional<Shape> shape =
      checked_model(system, model, what).exact_shape(system.coordinates(model));
  if (!shape || !std::holds_alternative<ShapeType>(*shape)) {
    throw make_error(what, ": model ", model, " has no exact ", kind);
  }
  return std::get<ShapeType>(*shape);
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
  const Model& model = checked_model(system, model_, "surface normal constraint");
  check_material_point(system, model_, uv_, "surface normal constraint");
  if (model.parametric_dimension() != 2) {
    throw make_error("surface normal constraint: model ", model_, " is not a surface");
  }
  TangentKinematics tangents;
  try {
    model.tangent_kinematics(system.coordinates(model_), system.velocities(model_), uv_, tangents);
  } catch (const Error& error) {
    throw make_error("surface normal constraint: model ", model_, ": ", error.what());
  }
}

void SurfaceNormalConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                       double /*time*/, ConstraintRows& rows) const {
  const ModelView view = model_view(system, model_, q, qd);
  TangentKinematics tangents;
  view.model.tangent_kinematics(view.q, view.qd, uv_, tangents);
  const Eigen::Vector3d& Su = tangents.su;
  const Eigen::Vector3d& Sv = tangents.sv;
  const Eigen::Vector3d normal = Su.cross(Sv);
  const Eigen::Vector3d normal_rate = tangents.su_rate.cross(Sv) + Su.cross(tangents.sv_rate);
  const Eigen::Vector3d normal_bias = 2.0 * tangents.su_rate.cross(tangents.sv_rate) +
                                      tangents.su_bias.cross(Sv) + Su.cross(tangents.sv_bias);
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
    for (size_t j = 0; j < tangents.columns.size(); ++j) {
      const auto column = static_cast<Eigen::Index>(j);
      rows.jacobian->emplace_back(
          row, view.velocity_offset + tangents.columns[j],
          tangents.ju.col(column).dot(along_u) + tangents.jv.col(column).dot(along_v));
    }
  }
}

std::vector<std::unique_ptr<Constraint>> curve_on_surface_constraints(const System& system,
                                                                      int curve_model,
                                                                      int surface_model,
                                                                      int sample_count) {
  const auto surface = exact<NurbsSurface>(system, surface_model, "curve on surface",
                                           "NURBS surface (Model::exact_shape)");
  const auto curve = exact<NurbsCurve>(system, curve_model, "curve on surface",
                                       "NURBS curve (Model::exact_shape)");
  if (sample_count < 1) {
    throw make_error("curve on surface: sample count ", sample_count, " must be at least 1");
  }
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
