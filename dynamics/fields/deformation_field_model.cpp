#include "dnurbs/dynamics/fields/deformation_field_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

void check_settings(const DeformationFieldSettings& settings, int parameters) {
  if (!(settings.mass_density > 0.0) || !std::isfinite(settings.mass_density)) {
    throw make_error("deformation field model: mass density ", settings.mass_density,
                     " is not positive and finite");
  }
  if (!(settings.damping_density >= 0.0) || !std::isfinite(settings.damping_density)) {
    throw make_error("deformation field model: damping density ", settings.damping_density,
                     " is not non-negative and finite");
  }
  if (settings.stiffness.size() != 0 && settings.stiffness.size() != parameters) {
    throw make_error("deformation field model: ", settings.stiffness.size(),
                     " stiffness values for ", parameters, " parameters");
  }
  for (Eigen::Index k = 0; k < settings.stiffness.size(); ++k) {
    if (!(settings.stiffness(k) >= 0.0) || !std::isfinite(settings.stiffness(k))) {
      throw make_error("deformation field model: stiffness ", settings.stiffness(k),
                       " of parameter ", k, " is not non-negative and finite");
    }
  }
  if (settings.quadrature_cells_u < 1 || settings.quadrature_cells_v < 1) {
    throw make_error("deformation field model: quadrature grid ", settings.quadrature_cells_u,
                     " by ", settings.quadrature_cells_v, " cells is below 1 by 1");
  }
  if (settings.quadrature_points < 1 || settings.quadrature_points > kMaxGaussPoints) {
    throw make_error("deformation field model: ", settings.quadrature_points,
                     " quadrature points per direction is outside 1..", kMaxGaussPoints);
  }
  if (!(settings.tessellation_max_error >= 0.0) ||
      !std::isfinite(settings.tessellation_max_error)) {
    throw make_error("deformation field model: tessellation max error ",
                     settings.tessellation_max_error, " is not non-negative and finite");
  }
}

// density * matrix as a sparse matrix without its zeros (P is small: a few modes).
SparseMatrix scaled_sparse(const Eigen::MatrixXd& gram, double density) {
  const Eigen::MatrixXd scaled = density * gram;
  return scaled.sparseView(0.0, 0.0);
}

}  // namespace

DeformationFieldModel::DeformationFieldModel(DeformationField field,
                                             std::optional<ParametricSurface> base,
                                             const ParameterDomain& domain, Eigen::VectorXd initial,
                                             DeformationFieldSettings settings)
    : field_(std::move(field)),
      base_(std::move(base)),
      domain_(base_ ? base_->domain() : domain),
      initial_(std::move(initial)),
      settings_(std::move(settings)) {
  const int parameters = field_.parameter_count();
  if (parameters == 0) {
    throw make_error("deformation field model: the cascade of ", field_.stage_count(),
                     " stages has no parameter (no AddVector stage names one)");
  }
  domain_.validate();
  if (initial_.size() != parameters) {
    throw make_error("deformation field model: ", initial_.size(), " initial values for ",
                     parameters, " parameters");
  }
  for (Eigen::Index k = 0; k < initial_.size(); ++k) {
    if (!std::isfinite(initial_(k))) {
      throw make_error("deformation field model: initial value ", initial_(k), " of parameter ", k,
                       " is not finite");
    }
  }
  check_settings(settings_, parameters);

  // Tensor Gauss-Legendre points over the cells, L at each (Goldenstein et al. 2005, eq. 4)
  const double cell_u = (domain_.u_max - domain_.u_min) / settings_.quadrature_cells_u;
  const double cell_v = (domain_.v_max - domain_.v_min) / settings_.quadrature_cells_v;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(parameters, parameters);
  for (int i = 0; i < settings_.quadrature_cells_u; ++i) {
    const GaussLegendreRule rule_u = gauss_legendre_rule_on(
        settings_.quadrature_points, domain_.u_min + i * cell_u, domain_.u_min + (i + 1) * cell_u);
    for (int j = 0; j < settings_.quadrature_cells_v; ++j) {
      const GaussLegendreRule rule_v =
          gauss_legendre_rule_on(settings_.quadrature_points, domain_.v_min + j * cell_v,
                                 domain_.v_min + (j + 1) * cell_v);
      for (Eigen::Index a = 0; a < rule_u.nodes.size(); ++a) {
        for (Eigen::Index b = 0; b < rule_v.nodes.size(); ++b) {
          QuadraturePoint point;
          point.parameter = Eigen::Vector2d(rule_u.nodes(a), rule_v.nodes(b));
          point.weight = rule_u.weights(a) * rule_v.weights(b);
          point.jacobian = field_.parameter_jacobian(point.parameter.x(), point.parameter.y());
          gram.noalias() += point.weight * (point.jacobian.transpose() * point.jacobian);
          points_.push_back(std::move(point));
        }
      }
    }
  }
  matrices_.mass = scaled_sparse(gram, settings_.mass_density);
  matrices_.damping = scaled_sparse(gram, settings_.damping_density);
  const Eigen::VectorXd stiffness =
      settings_.stiffness.size() == 0 ? Eigen::VectorXd::Zero(parameters) : settings_.stiffness;
  matrices_.stiffness = scaled_sparse(Eigen::MatrixXd(stiffness.asDiagonal()), 1.0);
}

std::unique_ptr<Model> DeformationFieldModel::clone() const {
  return std::make_unique<DeformationFieldModel>(*this);
}

Eigen::Vector3d DeformationFieldModel::input(double u, double v) const {
  return base_ ? base_->point(u, v) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d DeformationFieldModel::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  return field_.apply(q, u.x(), u.y(), input(u.x(), u.y()));
}

SparseMatrix DeformationFieldModel::position_jacobian(ConstVectorRef /*q*/,
                                                      const Eigen::Vector2d& u) const {
  const Eigen::Matrix3Xd jacobian = field_.parameter_jacobian(u.x(), u.y());
  return SparseMatrix(jacobian.sparseView(0.0, 0.0));
}

void DeformationFieldModel::assemble_matrices(ConstVectorRef /*q*/, ModelMatrices& matrices) const {
  matrices = matrices_;
}

void DeformationFieldModel::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                                  VectorRef force) const {
  MaterialSample sample;
  sample.mass_density = settings_.mass_density;
  for (const QuadraturePoint& point : points_) {
    const double u = point.parameter.x();
    const double v = point.parameter.y();
    sample.parameter = point.parameter;
    sample.position = position(q, point.parameter);
    const Eigen::Vector4d d = difference_parameters(point.parameter);
    sample.tangent_u = (position(q, {d(1), v}) - position(q, {d(0), v})) / (d(1) - d(0));
    sample.tangent_v = (position(q, {u, d(3)}) - position(q, {u, d(2)})) / (d(3) - d(2));
    force.noalias() += point.weight * (point.jacobian.transpose() * density(sample));
  }
}

Eigen::Vector4d DeformationFieldModel::difference_parameters(const Eigen::Vector2d& u) const {
  // Central differences, one-sided where a step would leave the domain
  const double step_u = ParametricSurface::kDifferenceStep * (domain_.u_max - domain_.u_min);
  const double step_v = ParametricSurface::kDifferenceStep * (domain_.v_max - domain_.v_min);
  return {std::max(u.x() - step_u, domain_.u_min), std::min(u.x() + step_u, domain_.u_max),
          std::max(u.y() - step_v, domain_.v_min), std::min(u.y() + step_v, domain_.v_max)};
}

void DeformationFieldModel::tangent_kinematics(ConstVectorRef q, ConstVectorRef qd,
                                               const Eigen::Vector2d& u,
                                               TangentKinematics& tangents) const {
  const Eigen::Vector4d d = difference_parameters(u);
  const double v = u.y();
  tangents.su = (position(q, {d(1), v}) - position(q, {d(0), v})) / (d(1) - d(0));
  tangents.sv = (position(q, {u.x(), d(3)}) - position(q, {u.x(), d(2)})) / (d(3) - d(2));
  tangents.ju =
      (field_.parameter_jacobian(d(1), v) - field_.parameter_jacobian(d(0), v)) / (d(1) - d(0));
  tangents.jv = (field_.parameter_jacobian(u.x(), d(3)) - field_.parameter_jacobian(u.x(), d(2))) /
                (d(3) - d(2));
  tangents.columns.resize(static_cast<size_t>(coordinate_count()));
  std::iota(tangents.columns.begin(), tangents.columns.end(), 0);
  tangents.su_rate = tangents.ju * qd;
  tangents.sv_rate = tangents.jv * qd;
  // J_u and J_v do not depend on q (Goldenstein et al. 2005, eq. 4 is affine in q)
  tangents.su_bias.setZero();
  tangents.sv_bias.setZero();
}

ParameterDomain DeformationFieldModel::parameter_domain(ConstVectorRef /*q*/) const {
  return domain_;
}

NormalOrientation DeformationFieldModel::normal_orientation() const {
  return base_ ? base_->orientation() : NormalOrientation::kSuCrossSv;
}

ParametricSurface DeformationFieldModel::parametric_surface(ConstVectorRef q) const {
  if (base_) {
    return deformed_surface(*base_, field_, q);
  }
  return deformation_field_surface(domain_, field_, q);
}

TriangleMesh DeformationFieldModel::tessellate(ConstVectorRef q,
                                               const ModelTessellationSettings& settings,
                                               std::string name) const {
  if (settings.max_error > 0.0 || settings_.tessellation_max_error == 0.0) {
    return Model::tessellate(q, settings, std::move(name));
  }
  ModelTessellationSettings adaptive = settings;
  adaptive.max_error = settings_.tessellation_max_error;
  adaptive.max_level = settings_.tessellation_max_level;
  return Model::tessellate(q, adaptive, std::move(name));
}

}  // namespace dnurbs
