#include "dnurbs/constraints/curve_on_surface_constraint.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <utility>
#include <variant>

#include <Eigen/Geometry>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/shape.h"
#include "dnurbs/nurbs/surface_projector.h"

namespace dnurbs {
namespace {

constexpr const char* kWhat = "curve on surface";

const Model& checked_model(const System& system, int model, const char* role) {
  if (model < 0 || model >= system.model_count()) {
    throw make_error(kWhat, ": ", role, " model index ", model, " is out of range (the system has ",
                     system.model_count(), " models)");
  }
  return system.model(model);
}

// The exact NURBS shape (Model::exact_shape) of `model` at coordinates q.
template <typename ShapeType>
ShapeType exact_shape_of(const Model& model, ConstVectorRef q, int index, const char* kind) {
  const std::optional<Shape> shape = model.exact_shape(q);
  if (!shape || !std::holds_alternative<ShapeType>(*shape)) {
    throw make_error(kWhat, ": model ", index, " has no exact ", kind, " (Model::exact_shape)");
  }
  return std::get<ShapeType>(*shape);
}

// True if `value` is an end of the domain of an open (non-periodic) knot vector: a foot point
// there is held on the boundary.
bool on_open_boundary(const KnotVector& knots, double value) {
  return !knots.is_periodic() && (value <= knots.domain_start() || value >= knots.domain_end());
}

// The foot point's parameter velocity from H [udot, vdot]^T = b, a held direction's entry zero.
Eigen::Vector2d foot_point_velocity(const Eigen::Matrix2d& H, const Eigen::Vector2d& b, bool held_u,
                                    bool held_v, int sample, double t) {
  const auto degenerate = [&](double pivot) {
    if (!(pivot > 0.0)) {
      throw make_error(kWhat, ": sample ", sample, " (curve parameter ", t,
                       ") has a degenerate nearest surface point (distance Hessian pivot ", pivot,
                       "): the curve point is at a centre of curvature of the surface "
                       "or the surface is singular there");
    }
  };
  if (held_u && held_v) {
    return Eigen::Vector2d::Zero();
  }
  if (held_u) {
    degenerate(H(1, 1));
    return {0.0, b.y() / H(1, 1)};
  }
  if (held_v) {
    degenerate(H(0, 0));
    return {b.x() / H(0, 0), 0.0};
  }
  const double determinant = H.determinant();
  degenerate(determinant);
  return H.inverse() * b;
}

// Appends scale * n^T L (one row) to rows.jacobian at `row`.
void append_normal_row(const SparseMatrix& L, const Eigen::Vector3d& n, int row,
                       int velocity_offset, double scale, ConstraintRows& rows) {
  for (int column = 0; column < L.outerSize(); ++column) {
    for (SparseMatrix::InnerIterator it(L, column); it; ++it) {
      rows.jacobian->emplace_back(row, velocity_offset + column, scale * n[it.row()] * it.value());
    }
  }
}

}  // namespace

CurveOnSurfaceConstraint::CurveOnSurfaceConstraint(int curve_model, int surface_model,
                                                   std::vector<double> curve_parameters)
    : curve_model_(curve_model),
      surface_model_(surface_model),
      curve_parameters_(std::move(curve_parameters)) {
  if (curve_parameters_.size() < 2) {
    throw make_error(kWhat, ": ", curve_parameters_.size(),
                     " curve parameters given, at least 2 are needed");
  }
  for (size_t k = 0; k < curve_parameters_.size(); ++k) {
    const double t = curve_parameters_[k];
    if (!std::isfinite(t)) {
      throw make_error(kWhat, ": curve parameter ", k, " is ", t, ", not finite");
    }
    if (k > 0 && !(t > curve_parameters_[k - 1])) {
      throw make_error(kWhat, ": curve parameter ", k, " (", t,
                       ") does not increase from the one before (", curve_parameters_[k - 1], ")");
    }
  }
}

std::unique_ptr<Constraint> CurveOnSurfaceConstraint::clone() const {
  return std::make_unique<CurveOnSurfaceConstraint>(*this);
}

std::string CurveOnSurfaceConstraint::description() const {
  std::ostringstream text;
  text << "curve of model " << curve_model_ << " on the surface of model " << surface_model_
       << " at " << curve_parameters_.size()
       << " samples following their nearest points (t = " << curve_parameters_.front() << " .. "
       << curve_parameters_.back() << ")";
  return text.str();
}

void CurveOnSurfaceConstraint::check(const System& system) const {
  const Model& curve_model = checked_model(system, curve_model_, "curve");
  const Model& surface_model = checked_model(system, surface_model_, "surface");
  if (curve_model_ == surface_model_) {
    throw make_error(kWhat, ": the curve and the surface are the same model (", curve_model_, ")");
  }
  const auto curve = exact_shape_of<NurbsCurve>(curve_model, system.coordinates(curve_model_),
                                                curve_model_, "NURBS curve");
  exact_shape_of<NurbsSurface>(surface_model, system.coordinates(surface_model_), surface_model_,
                               "NURBS surface");
  const double start = curve.knots().domain_start();
  const double end = curve.knots().domain_end();
  if (curve_parameters_.front() < start || curve_parameters_.back() > end) {
    throw make_error(kWhat, ": curve parameters ", curve_parameters_.front(), " .. ",
                     curve_parameters_.back(), " leave the domain [", start, ", ", end,
                     "] of model ", curve_model_);
  }
}

void CurveOnSurfaceConstraint::evaluate(const System& system, ConstVectorRef q, ConstVectorRef qd,
                                        double /*time*/, ConstraintRows& rows) const {
  const ModelView curve = model_view(system, curve_model_, q, qd);
  const ModelView surface = model_view(system, surface_model_, q, qd);
  const auto shape =
      exact_shape_of<NurbsSurface>(surface.model, surface.q, surface_model_, "NURBS surface");
  const SurfaceProjector projector(shape);
  SurfaceDerivatives derivatives;
  TangentKinematics tangents;
  for (int k = 0; k < row_count(); ++k) {
    const int row = rows.row + k;
    const double t = curve_parameters_[static_cast<size_t>(k)];
    const Eigen::Vector2d at_curve(t, 0.0);
    // The foot point (u_k, v_k): the nearest surface point at these coordinates.
    const Eigen::Vector3d c = curve.model.position(curve.q, at_curve);
    const Eigen::Vector2d uv = projector.closest_point(c).parameter;
    shape.derivatives(uv.x(), uv.y(), 2, derivatives);
    surface.model.tangent_kinematics(surface.q, surface.qd, uv, tangents);
    const Eigen::Vector3d& S_u = derivatives(1, 0);
    const Eigen::Vector3d& S_v = derivatives(0, 1);
    const Eigen::Vector3d& S_uu = derivatives(2, 0);
    const Eigen::Vector3d& S_uv = derivatives(1, 1);
    const Eigen::Vector3d& S_vv = derivatives(0, 2);
    const Eigen::Vector3d N = S_u.cross(S_v);
    const double length = N.norm();
    if (!(length > 0.0)) {
      throw make_error(kWhat, ": the surface normal at the foot point (", uv.x(), ", ", uv.y(),
                       ") of sample ", k, " (curve parameter ", t, ") is degenerate");
    }
    const Eigen::Vector3d n = N / length;
    const Eigen::Vector3d r = c - derivatives(0, 0);

    // C_q = n^T [L_c, -L_s] and Cdot = n.w with w the relative material velocity.
    const SparseMatrix L_c = curve.model.position_jacobian(curve.q, at_curve);
    const SparseMatrix L_s = surface.model.position_jacobian(surface.q, uv);
    const Eigen::Vector3d w = L_c * curve.qd - L_s * surface.qd;
    (*rows.value)[row] = n.dot(r);
    (*rows.rate)[row] = n.dot(w);
    append_normal_row(L_c, n, row, curve.velocity_offset, 1.0, rows);
    append_normal_row(L_s, n, row, surface.velocity_offset, -1.0, rows);

    // The foot point's velocity (derivative of S_u.r = S_v.r = 0) and the normal's rate.
    Eigen::Matrix2d H;
    H << S_u.dot(S_u) - S_uu.dot(r), S_u.dot(S_v) - S_uv.dot(r), S_u.dot(S_v) - S_uv.dot(r),
        S_v.dot(S_v) - S_vv.dot(r);
    const Eigen::Vector2d b(tangents.su_rate.dot(r) + S_u.dot(w),
                            tangents.sv_rate.dot(r) + S_v.dot(w));
    const Eigen::Vector2d uv_rate =
        foot_point_velocity(H, b, on_open_boundary(shape.knots_u(), uv.x()),
                            on_open_boundary(shape.knots_v(), uv.y()), k, t);
    const Eigen::Vector3d N_rate =
        (tangents.su_rate + S_uu * uv_rate.x() + S_uv * uv_rate.y()).cross(S_v) +
        S_u.cross(tangents.sv_rate + S_uv * uv_rate.x() + S_vv * uv_rate.y());
    const Eigen::Vector3d n_rate = (N_rate - n * n.dot(N_rate)) / length;
    // sigma = -(ndot.w + n.(Ldot_c qd - Ldot_s qd) - n.(Sdot_u udot + Sdot_v vdot)).
    const Eigen::Vector3d bias =
        curve.model.jacobian_rate_times_velocity(curve.q, curve.qd, at_curve) -
        surface.model.jacobian_rate_times_velocity(surface.q, surface.qd, uv) -
        tangents.su_rate * uv_rate.x() - tangents.sv_rate * uv_rate.y();
    (*rows.sigma)[row] = -(n_rate.dot(w) + n.dot(bias));
  }
}

CurveOnSurfaceConstraint evenly_sampled_curve_on_surface(const System& system, int curve_model,
                                                         int surface_model, int sample_count) {
  if (sample_count < 2) {
    throw make_error(kWhat, ": sample count ", sample_count, " must be at least 2");
  }
  const auto curve =
      exact_shape_of<NurbsCurve>(checked_model(system, curve_model, "curve"),
                                 system.coordinates(curve_model), curve_model, "NURBS curve");
  const double start = curve.knots().domain_start();
  const double end = curve.knots().domain_end();
  std::vector<double> parameters(static_cast<size_t>(sample_count));
  for (int k = 0; k < sample_count; ++k) {
    parameters[static_cast<size_t>(k)] = start + (end - start) * k / (sample_count - 1);
  }
  CurveOnSurfaceConstraint constraint(curve_model, surface_model, std::move(parameters));
  constraint.check(system);
  return constraint;
}

Eigen::VectorXd curve_to_surface_distances(const System& system, int curve_model, int surface_model,
                                           const std::vector<double>& curve_parameters) {
  const auto curve =
      exact_shape_of<NurbsCurve>(checked_model(system, curve_model, "curve"),
                                 system.coordinates(curve_model), curve_model, "NURBS curve");
  const SurfaceProjector projector(exact_shape_of<NurbsSurface>(
      checked_model(system, surface_model, "surface"), system.coordinates(surface_model),
      surface_model, "NURBS surface"));
  Eigen::VectorXd distances(static_cast<Eigen::Index>(curve_parameters.size()));
  for (size_t k = 0; k < curve_parameters.size(); ++k) {
    const Eigen::Vector3d c = curve.point(curve_parameters[k]);
    const SurfaceProjection foot = projector.closest_point(c);
    const Eigen::Vector3d n =
        projector.surface().unit_normal(foot.parameter.x(), foot.parameter.y());
    distances[static_cast<Eigen::Index>(k)] =
        n.dot(c - foot.point) < 0.0 ? -foot.distance : foot.distance;
  }
  return distances;
}

}  // namespace dnurbs
