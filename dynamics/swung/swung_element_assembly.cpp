#include "dnurbs/dynamics/swung/swung_element_assembly.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace dnurbs {

SwungElementAssembly::SwungElementAssembly(const SwungQuadrature& quadrature,
                                           const SwungRestPoints& rest, const SwungLayout& layout,
                                           double alpha, int profile_degree, int trajectory_degree,
                                           bool geometric_stiffness)
    : quadrature_(quadrature),
      rest_(rest),
      layout_(layout),
      alpha_(alpha),
      geometric_stiffness_(geometric_stiffness),
      order_(quadrature.stiffness_order()),
      profile_columns_(layout.per_control_point * (profile_degree + 1)),
      columns_(layout.per_control_point * (profile_degree + trajectory_degree + 2)) {
  const Eigen::Index points = static_cast<Eigen::Index>(quadrature.profile_points_per_span()) *
                              quadrature.trajectory_points_per_span();
  const Eigen::Index quantities = kQuantityCount - 1;
  mass_stack_.resize(3 * points, columns_);
  damping_stack_.resize(quadrature.has_damping() ? 3 * points : 0, columns_);
  stiffness_stack_.resize(3 * quantities * points, columns_);
  profile_factors_.resize(quantities * points, profile_columns_);
  trajectory_factors_.resize(quantities * points, columns_ - profile_columns_);
  profile_weights_.resize(static_cast<size_t>(quadrature.profile_points_per_span()));
  trajectory_weights_.resize(static_cast<size_t>(quadrature.trajectory_points_per_span()));
  for (Eigen::MatrixXd* m : {&mass_, &damping_, &gram_, &hessian_}) {
    m->resize(columns_, columns_);
  }
}

void SwungElementAssembly::add_point(const PlanarCurveSample& profile,
                                     const PlanarCurveSample& trajectory, int i, int j) {
  const int gu = i % quadrature_.profile_points_per_span();
  const int gv = j % quadrature_.trajectory_points_per_span();
  const double weight = quadrature_.weight(i, j);
  const double* material = quadrature_.material(i, j);
  swung_jacobian(profile, trajectory, alpha_, layout_, order_, jacobian_);
  // M and D: mu J^T J and gamma J^T J (Terzopoulos, eq. 1.25), as rows sqrt(w mu) J.
  mass_stack_.middleRows(mass_rows_, 3) = std::sqrt(weight * material[0]) * jacobian_.columns[0];
  if (quadrature_.has_damping()) {
    damping_stack_.middleRows(mass_rows_, 3) =
        std::sqrt(weight * material[1]) * jacobian_.columns[0];
  }
  mass_rows_ += 3;
  // K: sum_Q k_Q (J_Q^T J_Q + sum_c (S^Q_c - S^Q_c(q_r)) d^2 S^Q_c / dq^2) (Terzopoulos,
  // eq. 1.20; the rest term of dnurbs_swung_surface.h).
  for (int quantity = 1; quantity < kQuantityCount; ++quantity) {
    if (!quadrature_.has_stiffness(quantity)) {
      continue;
    }
    const double k = weight * material[1 + quantity];
    stiffness_stack_.middleRows(stiffness_rows_, 3) =
        std::sqrt(k) * jacobian_.columns[static_cast<size_t>(quantity)];
    stiffness_rows_ += 3;
    if (!geometric_stiffness_) {
      continue;
    }
    Eigen::Vector3d change = jacobian_.point_derivatives[static_cast<size_t>(quantity)];
    if (!rest_.empty()) {
      change -= rest_.derivative(i, j, alpha_, quantity);
    }
    swung_hessian_terms(profile, trajectory, alpha_, layout_,
                        static_cast<SurfaceQuantity>(quantity), k * change, terms_);
    profile_factors_.row(factor_rows_) = terms_.profile_gradient.transpose();
    trajectory_factors_.row(factor_rows_) = terms_.trajectory_gradient.transpose();
    ++factor_rows_;
    profile_weights_[static_cast<size_t>(gu)].col(terms_.profile_order) += terms_.profile_weight;
    trajectory_weights_[static_cast<size_t>(gv)].col(terms_.trajectory_order) +=
        terms_.trajectory_weight;
  }
}

void SwungElementAssembly::finish(const std::vector<PlanarCurveSample>& profile,
                                  const std::vector<PlanarCurveSample>& trajectory, int su, int sv,
                                  Eigen::MatrixXd& mass, Eigen::MatrixXd& damping,
                                  Eigen::MatrixXd& stiffness) {
  // J^T J sums as symmetric rank updates of the stacks (upper triangles).
  const bool with_damping = quadrature_.has_damping();
  for (auto [element, stack, rows] :
       {std::tuple{&mass_, &mass_stack_, mass_rows_},
        std::tuple{&damping_, &damping_stack_, with_damping ? mass_rows_ : 0},
        std::tuple{&gram_, &stiffness_stack_, stiffness_rows_}}) {
    element->setZero();
    if (rows > 0) {
      element->selfadjointView<Eigen::Upper>().rankUpdate(stack->topRows(rows).transpose());
    }
  }
  // Second derivatives: the cross block once, added to both sides (exactly symmetric), and each
  // curve's own terms once per Gauss point of the curve (free weights).
  hessian_.setZero();
  if (factor_rows_ > 0) {
    const Eigen::MatrixXd cross = profile_factors_.topRows(factor_rows_).transpose() *
                                  trajectory_factors_.topRows(factor_rows_);
    hessian_.topRightCorner(profile_columns_, columns_ - profile_columns_) = cross;
    hessian_.bottomLeftCorner(columns_ - profile_columns_, profile_columns_) = cross.transpose();
  }
  if (geometric_stiffness_ && layout_.mode == WeightMode::kFree) {
    const int per_u = quadrature_.profile_points_per_span();
    const int per_v = quadrature_.trajectory_points_per_span();
    for (int g = 0; g < per_u; ++g) {
      const int point = su * per_u + g;
      for (int d = 0; d < 3; ++d) {
        add_planar_curve_hessian(profile[static_cast<size_t>(point)], d,
                                 profile_weights_[static_cast<size_t>(g)].col(d), 0, hessian_);
      }
    }
    for (int g = 0; g < per_v; ++g) {
      const int point = sv * per_v + g;
      for (int d = 0; d < 3; ++d) {
        add_planar_curve_hessian(trajectory[static_cast<size_t>(point)], d,
                                 trajectory_weights_[static_cast<size_t>(g)].col(d),
                                 profile_columns_, hessian_);
      }
    }
  }
  // Scatter into the global matrices at the element's coordinates.
  for (int j = 0; j < columns_; ++j) {
    const int column = jacobian_.coordinate[static_cast<size_t>(j)];
    for (int i = 0; i < columns_; ++i) {
      const int row = jacobian_.coordinate[static_cast<size_t>(i)];
      const int low = std::min(i, j);
      const int high = std::max(i, j);
      mass(row, column) += mass_(low, high);
      if (with_damping) {
        damping(row, column) += damping_(low, high);
      }
      stiffness(row, column) += gram_(low, high) + hessian_(i, j);
    }
  }
}

void SwungElementAssembly::assemble(const std::vector<PlanarCurveSample>& profile,
                                    const std::vector<PlanarCurveSample>& trajectory,
                                    Eigen::MatrixXd& mass, Eigen::MatrixXd& damping,
                                    Eigen::MatrixXd& stiffness) {
  const int per_u = quadrature_.profile_points_per_span();
  const int per_v = quadrature_.trajectory_points_per_span();
  for (int su = 0; su < quadrature_.profile_point_count() / per_u; ++su) {
    for (int sv = 0; sv < quadrature_.trajectory_point_count() / per_v; ++sv) {
      mass_rows_ = 0;
      stiffness_rows_ = 0;
      factor_rows_ = 0;
      for (auto* weights : {&profile_weights_, &trajectory_weights_}) {
        for (Eigen::Matrix<double, 2, 3>& w : *weights) {
          w.setZero();
        }
      }
      for (int gu = 0; gu < per_u; ++gu) {
        for (int gv = 0; gv < per_v; ++gv) {
          const int i = su * per_u + gu;
          const int j = sv * per_v + gv;
          add_point(profile[static_cast<size_t>(i)], trajectory[static_cast<size_t>(j)], i, j);
        }
      }
      finish(profile, trajectory, su, sv, mass, damping, stiffness);
    }
  }
}

}  // namespace dnurbs
