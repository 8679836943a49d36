#include "dnurbs/surface/deformation_field.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// The cell index and the fraction within it of parameter `x` along one direction with `cells`
// cells over [lo, hi]: wrapped for a periodic direction, clamped for an open one.
std::pair<int, double> locate(double x, double lo, double hi, int cells, bool periodic) {
  double t = (x - lo) / (hi - lo) * cells;
  if (periodic) {
    t = std::fmod(t, static_cast<double>(cells));
    if (t < 0.0) {
      t += cells;
    }
  } else {
    t = std::clamp(t, 0.0, static_cast<double>(cells));
  }
  const int index = std::min(static_cast<int>(std::floor(t)), cells - 1);
  return {index, t - index};
}

}  // namespace

SampledVectorField::SampledVectorField(const ParameterDomain& domain, int count_u, int count_v,
                                       Eigen::MatrixX3d samples)
    : domain_(domain), count_u_(count_u), count_v_(count_v), samples_(std::move(samples)) {
  domain_.validate();
  const int minimum_u = domain_.periodic_u ? 3 : 2;
  const int minimum_v = domain_.periodic_v ? 3 : 2;
  if (count_u < minimum_u || count_v < minimum_v) {
    throw make_error("sampled vector field: ", count_u, " by ", count_v,
                     " nodes is below the minimum ", minimum_u, " by ", minimum_v);
  }
  if (samples_.rows() != static_cast<Eigen::Index>(count_u) * count_v) {
    throw make_error("sampled vector field: ", samples_.rows(), " samples for ", count_u, " by ",
                     count_v, " nodes");
  }
  if (!samples_.allFinite()) {
    throw make_error("sampled vector field: a sample is not finite");
  }
}

SampledVectorField SampledVectorField::sample(const ParameterDomain& domain, int count_u,
                                              int count_v, const VectorField& field) {
  domain.validate();
  const int cells_u = domain.periodic_u ? count_u : count_u - 1;
  const int cells_v = domain.periodic_v ? count_v : count_v - 1;
  if (cells_u < 1 || cells_v < 1 || !field) {
    throw make_error("sampled vector field: cannot sample ", count_u, " by ", count_v, " nodes",
                     field ? "" : " of an empty field");
  }
  Eigen::MatrixX3d samples(static_cast<Eigen::Index>(count_u) * count_v, 3);
  for (int i = 0; i < count_u; ++i) {
    const double u = domain.u_at(static_cast<double>(i) / cells_u);
    for (int j = 0; j < count_v; ++j) {
      const double v = domain.v_at(static_cast<double>(j) / cells_v);
      samples.row(i * count_v + j) = field(u, v).transpose();
    }
  }
  return SampledVectorField(domain, count_u, count_v, std::move(samples));
}

Eigen::Vector3d SampledVectorField::operator()(double u, double v) const {
  const int cells_u = domain_.periodic_u ? count_u_ : count_u_ - 1;
  const int cells_v = domain_.periodic_v ? count_v_ : count_v_ - 1;
  const auto [i, a] = locate(u, domain_.u_min, domain_.u_max, cells_u, domain_.periodic_u);
  const auto [j, b] = locate(v, domain_.v_min, domain_.v_max, cells_v, domain_.periodic_v);
  const int i1 = (i + 1) % count_u_;
  const int j1 = (j + 1) % count_v_;
  auto node = [&](int p, int r) { return samples_.row(p * count_v_ + r).transpose(); };
  // Bilinear interpolation of the four nodes of the cell (Goldenstein et al. 2005, eq. 2: the
  // continuous field from the discretized geometry image)
  return (1.0 - a) * ((1.0 - b) * node(i, j) + b * node(i, j1)) +
         a * ((1.0 - b) * node(i1, j) + b * node(i1, j1));
}

DeformationField& DeformationField::constant(VectorField field) {
  if (!field) {
    throw make_error("deformation field: the constant stage's vector field is empty");
  }
  stages_.push_back({DeformationKind::kConstant, std::move(field), -1});
  return *this;
}

DeformationField& DeformationField::add_vector(VectorField field, int parameter) {
  if (!field) {
    throw make_error("deformation field: the AddVector stage's vector field is empty");
  }
  if (parameter < 0) {
    throw make_error("deformation field: AddVector parameter index ", parameter, " is negative");
  }
  stages_.push_back({DeformationKind::kAddVector, std::move(field), parameter});
  parameter_count_ = std::max(parameter_count_, parameter + 1);
  return *this;
}

DeformationField& DeformationField::add_vector(VectorField field) {
  if (!field) {
    throw make_error("deformation field: the AddVector stage's vector field is empty");
  }
  stages_.push_back({DeformationKind::kAddVector, std::move(field), -1});
  return *this;
}

DeformationKind DeformationField::stage_kind(int stage) const {
  if (stage < 0 || stage >= stage_count()) {
    throw make_error("deformation field: stage ", stage, " is outside [0, ", stage_count(), ")");
  }
  return stages_[static_cast<size_t>(stage)].kind;
}

Eigen::Vector3d DeformationField::apply(const Eigen::VectorXd& q, double u, double v,
                                        const Eigen::Vector3d& input) const {
  if (q.size() < parameter_count_) {
    throw make_error("deformation field: ", q.size(), " parameters for a cascade that uses ",
                     parameter_count_);
  }
  // Goldenstein et al. 2005, eq. 1: the cascade of basic operations at (u, v)
  Eigen::Vector3d p = input;
  for (const Stage& stage : stages_) {
    const Eigen::Vector3d field = stage.field(u, v);
    if (stage.kind == DeformationKind::kConstant) {
      p = field;  // eqs 2-3
    } else {
      p += (stage.parameter < 0 ? 1.0 : q(stage.parameter)) * field;  // eq 4
    }
  }
  return p;
}

Eigen::Matrix3Xd DeformationField::parameter_jacobian(double u, double v) const {
  Eigen::Matrix3Xd jacobian = Eigen::Matrix3Xd::Zero(3, parameter_count_);
  for (const Stage& stage : stages_) {
    if (stage.kind == DeformationKind::kConstant) {
      jacobian.setZero();  // a constant stage forgets everything before it
    } else if (stage.parameter >= 0) {
      jacobian.col(stage.parameter) += stage.field(u, v);
    }
  }
  return jacobian;
}

ParametricSurface deformed_surface(const ParametricSurface& base, DeformationField field,
                                   Eigen::VectorXd q) {
  if (q.size() < field.parameter_count()) {
    throw make_error("deformed surface: ", q.size(), " parameters for a cascade that uses ",
                     field.parameter_count());
  }
  return ParametricSurface(
      base.domain(),
      [base, field = std::move(field), q = std::move(q)](double u, double v) {
        return field.apply(q, u, v, base.point(u, v));
      },
      {}, base.orientation());
}

ParametricSurface deformation_field_surface(const ParameterDomain& domain, DeformationField field,
                                            Eigen::VectorXd q, NormalOrientation orientation) {
  if (q.size() < field.parameter_count()) {
    throw make_error("deformation field surface: ", q.size(),
                     " parameters for a cascade that uses ", field.parameter_count());
  }
  return ParametricSurface(
      domain,
      [field = std::move(field), q = std::move(q)](double u, double v) {
        return field.apply(q, u, v);
      },
      {}, orientation);
}

}  // namespace dnurbs
