#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/swung/swung_element_assembly.h"
#include "dnurbs/dynamics/swung/swung_gauge.h"
#include "dnurbs/dynamics/swung/swung_parametric_surface.h"
#include "dnurbs/nurbs/gauss_legendre.h"

namespace dnurbs {
namespace {

// force[coordinate] += sign J^T f over the Jacobian's columns.
void add_transposed(const SwungJacobian& jacobian, int quantity, const Eigen::Vector3d& f,
                    VectorRef force) {
  const auto& columns = jacobian.columns[static_cast<size_t>(quantity)];
  for (int c = 0; c < jacobian.column_count; ++c) {
    force[jacobian.coordinate[static_cast<size_t>(c)]] += columns.col(c).dot(f);
  }
}

// Copies the dense matrix into `matrix`, which gets the pattern's structure (storage reused when
// it already has it).
void fill_from_dense(const SparseMatrix& pattern, const Eigen::MatrixXd& dense,
                     SparseMatrix& matrix) {
  if (matrix.rows() != pattern.rows() || matrix.nonZeros() != pattern.nonZeros() ||
      !matrix.isCompressed()) {
    matrix = pattern;
  }
  for (Eigen::Index j = 0; j < pattern.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      it.valueRef() = dense(it.row(), j);
    }
  }
}

// The coordinates of every (p + 1)-point window of a curve's spans.
std::vector<std::vector<int>> span_coordinates(const KnotVector& knots, int offset, int per) {
  std::vector<std::vector<int>> result;
  for (const int span : knots.non_empty_spans()) {
    std::vector<int> coordinates;
    for (int a = 0; a <= knots.degree(); ++a) {
      for (int c = 0; c < per; ++c) {
        coordinates.push_back(offset + per * knots.control_point_index(span, a) + c);
      }
    }
    result.push_back(std::move(coordinates));
  }
  return result;
}

// Gauss points per span of one curve's direction (DNurbsSwungSettings::quadrature_points).
int points_per_span(const NurbsCurve& curve, const DNurbsSwungSettings& settings) {
  if (settings.quadrature_points > 0) {
    return settings.quadrature_points;
  }
  int points = curve.degree() + 1;
  if (settings.weight_mode == WeightMode::kFree) {
    const auto spans = static_cast<int>(curve.knots().non_empty_spans().size());
    const int coordinates = 3 * curve.control_point_count();
    points = std::max(points, (coordinates + 2 * spans - 1) / (2 * spans));
  }
  return std::min(points, kMaxGaussPoints);
}

// The symmetric pattern of M, D, K: each curve's span windows, and every profile coordinate
// with every trajectory one.
SparseMatrix coupling_pattern(const SwungSurface& surface, const SwungLayout& layout) {
  const int per = layout.per_control_point;
  const int n = layout.coordinate_count();
  const int trajectory_start = layout.trajectory_offset(0);
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& windows :
       {span_coordinates(surface.profile().knots(), 0, per),
        span_coordinates(surface.trajectory().knots(), trajectory_start, per)}) {
    for (const std::vector<int>& window : windows) {
      for (const int i : window) {
        for (const int j : window) {
          triplets.emplace_back(i, j, 0.0);
        }
      }
    }
  }
  for (int i = 0; i < trajectory_start; ++i) {
    for (int j = trajectory_start; j < n; ++j) {
      triplets.emplace_back(i, j, 0.0);
      triplets.emplace_back(j, i, 0.0);
    }
  }
  SparseMatrix pattern(n, n);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  pattern.makeCompressed();
  return pattern;
}

}  // namespace

DNurbsSwungSurface::DNurbsSwungSurface(const SwungSurface& surface,
                                       const DNurbsSurfaceMaterial& material,
                                       const DNurbsSwungSettings& settings)
    : surface_(surface),
      material_(material),
      settings_(settings),
      layout_(swung_layout(surface, settings.weight_mode)),
      minimum_weight_(settings.minimum_weight),
      geometric_stiffness_(settings.geometric_stiffness),
      profile_weights_(surface.profile().weights()),
      trajectory_weights_(surface.trajectory().weights()),
      initial_coordinates_(swung_coordinates(surface, settings.weight_mode)) {
  // Settings and weights ------------------------------------------------------------------------
  if (!(minimum_weight_ > 0.0) || !std::isfinite(minimum_weight_)) {
    throw make_error("minimum weight ", minimum_weight_, " is not a positive finite number");
  }
  if (settings.quadrature_points < 0 || settings.quadrature_points > kMaxGaussPoints) {
    throw make_error("quadrature points per span ", settings.quadrature_points, " is outside 0..",
                     kMaxGaussPoints, " (0 = degree + 1)");
  }
  const bool free = layout_.mode == WeightMode::kFree;
  for (const auto& [weights, name] :
       {std::pair{&profile_weights_, "profile"}, std::pair{&trajectory_weights_, "trajectory"}}) {
    for (Eigen::Index i = 0; i < weights->size(); ++i) {
      if (free && (*weights)[i] < minimum_weight_) {
        throw make_error("free ", name, " weight ", i, " is ", (*weights)[i],
                         ", below the minimum weight ", minimum_weight_);
      }
    }
  }

  // Quadrature and material (Terzopoulos, eq. 1.25: Gauss sums over the non-empty spans) -------
  quadrature_ = SwungQuadrature(surface, points_per_span(surface.profile(), settings),
                                points_per_span(surface.trajectory(), settings), material);
  weight_inertia_ = settings.weight_inertia;
  if (!(weight_inertia_ >= 0.0) || !std::isfinite(weight_inertia_)) {
    throw make_error("weight inertia ", weight_inertia_, " is not a non-negative finite number");
  }

  // Separable fast path: fixed weights make the Gauss-point samples independent of q --------
  separable_ = settings.separable_assembly && !free && material.mass_density.is_constant() &&
               material.damping_density.is_constant() && material.a10.is_constant() &&
               material.a01.is_constant() && material.b20.is_constant() &&
               material.b11.is_constant() && material.b02.is_constant();
  if (separable_) {
    std::vector<PlanarCurveSample> profile;
    std::vector<PlanarCurveSample> trajectory;
    quadrature_samples(initial_coordinates_, profile, trajectory);
    separable_forms_ = SwungSeparableForms(quadrature_, layout_, surface.alpha(), profile,
                                           trajectory, quadrature_.material(0, 0));
  }

  // Pattern: each curve's span windows, and every profile coordinate with every trajectory one --
  pattern_ = coupling_pattern(surface, layout_);

  // Gauges: the scaling (fix the profile x of largest magnitude) and each curve's weight scale -
  if (settings.fix_gauge) {
    gauge_coordinate_ = swung_scaling_gauge_coordinate(layout_, initial_coordinates_);
    fix_coordinate(gauge_coordinate_);
    if (free) {
      fix_coordinate(layout_.profile_offset(0) + 2);
      fix_coordinate(layout_.trajectory_offset(0) + 2);
    }
  }

  // The outward side of the initial surface (after the gauge: its error names the axis profile)
  orientation_ = swung_normal_orientation(surface);

  // Rest shape and plastic flow (file comment of the header)
  if (settings.initial_shape_at_rest) {
    set_rest_shape(initial_coordinates_);
  }
  set_plastic_flow(settings.plastic_flow);
}

// -----------------------------------------------------------------------------------------------
// Samples and kinematics

void DNurbsSwungSurface::check_size(const ConstVectorRef& q, const char* what) const {
  if (q.size() != coordinate_count()) {
    throw make_error(what, " vector has ", q.size(), " entries, the swung surface has ",
                     coordinate_count());
  }
}

void DNurbsSwungSurface::samples_at(const ConstVectorRef& q, const Eigen::Vector2d& u,
                                    PlanarCurveSample& profile,
                                    PlanarCurveSample& trajectory) const {
  check_size(q, "coordinate");
  planar_curve_basis(surface_.profile().knots(), u.x(), profile);
  planar_curve_basis(surface_.trajectory().knots(), u.y(), trajectory);
  planar_curve_rational(swung_profile_net(layout_, q.data(), profile_weights_.data()), profile);
  planar_curve_rational(swung_trajectory_net(layout_, q.data(), trajectory_weights_.data()),
                        trajectory);
}

void DNurbsSwungSurface::quadrature_samples(const ConstVectorRef& q,
                                            std::vector<PlanarCurveSample>& profile,
                                            std::vector<PlanarCurveSample>& trajectory) const {
  check_size(q, "coordinate");
  quadrature_.sample(layout_, q.data(), profile_weights_.data(), trajectory_weights_.data(),
                     profile, trajectory);
}

Eigen::Vector3d DNurbsSwungSurface::change_from_rest(const SwungJacobian& jacobian, int i, int j,
                                                     int quantity) const {
  const Eigen::Vector3d& value = jacobian.point_derivatives[static_cast<size_t>(quantity)];
  if (rest_points_.empty()) {
    return value;
  }
  return value - rest_points_.derivative(i, j, surface_.alpha(), quantity);
}

void DNurbsSwungSurface::jacobian(const ConstVectorRef& q, const Eigen::Vector2d& u, int order,
                                  SwungJacobian& jacobian) const {
  PlanarCurveSample profile;
  PlanarCurveSample trajectory;
  samples_at(q, u, profile, trajectory);
  swung_jacobian(profile, trajectory, surface_.alpha(), layout_, order, jacobian);
}

void DNurbsSwungSurface::jacobian_rate(const ConstVectorRef& q, const ConstVectorRef& qd,
                                       const Eigen::Vector2d& u, int order,
                                       std::array<Eigen::Vector3d, 6>& rates) const {
  check_size(qd, "velocity");
  PlanarCurveSample profile;
  PlanarCurveSample trajectory;
  samples_at(q, u, profile, trajectory);
  swung_jacobian_rate(profile, trajectory, surface_.alpha(), layout_, qd.data(), order, rates);
}

Eigen::Vector3d DNurbsSwungSurface::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  SwungJacobian point;
  jacobian(q, u, 0, point);
  return point.point_derivatives[0];
}

SparseMatrix DNurbsSwungSurface::position_jacobian(ConstVectorRef q,
                                                   const Eigen::Vector2d& u) const {
  SwungJacobian point;
  jacobian(q, u, 0, point);
  return to_sparse_matrix(point, SurfaceQuantity::kPoint, coordinate_count());
}

Eigen::Vector3d DNurbsSwungSurface::jacobian_rate_times_velocity(ConstVectorRef q,
                                                                 ConstVectorRef qd,
                                                                 const Eigen::Vector2d& u) const {
  std::array<Eigen::Vector3d, 6> rates;
  jacobian_rate(q, qd, u, 0, rates);
  return rates[0];
}

// -----------------------------------------------------------------------------------------------
// Matrices

void DNurbsSwungSurface::assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const {
  check_size(q, "coordinate");
  const int n = coordinate_count();
  const bool with_damping = quadrature_.has_damping();
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd damping = Eigen::MatrixXd::Zero(with_damping ? n : 0, with_damping ? n : 0);
  Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(n, n);
  if (separable_) {
    separable_forms_.matrices(q, geometric_stiffness_, mass, damping, stiffness);
  } else {
    std::vector<PlanarCurveSample> profile;
    std::vector<PlanarCurveSample> trajectory;
    quadrature_samples(q, profile, trajectory);
    SwungElementAssembly assembly(quadrature_, rest_points_, layout_, surface_.alpha(),
                                  surface_.profile().degree(), surface_.trajectory().degree(),
                                  geometric_stiffness_);
    assembly.assemble(profile, trajectory, mass, damping, stiffness);
  }
  if (layout_.mode == WeightMode::kFree) {
    for (int k = 2; k < n; k += 3) {
      mass(k, k) += weight_inertia_;
    }
  }
  fill_from_dense(pattern_, mass, matrices.mass);
  fill_from_dense(pattern_, stiffness, matrices.stiffness);
  if (with_damping) {
    fill_from_dense(pattern_, damping, matrices.damping);
  } else {
    matrices.damping = SparseMatrix(n, n);
  }
}

// -----------------------------------------------------------------------------------------------
// Forces and energy

void DNurbsSwungSurface::add_internal_force(ConstVectorRef q, VectorRef force) const {
  const int order = quadrature_.stiffness_order();
  if (order == 0) {
    return;
  }
  if (separable_) {
    check_size(q, "coordinate");
    separable_forms_.add_internal_force(q, force);
    return;
  }
  std::vector<PlanarCurveSample> profile;
  std::vector<PlanarCurveSample> trajectory;
  quadrature_samples(q, profile, trajectory);
  SwungJacobian jacobian;
  for (int i = 0; i < quadrature_.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature_.trajectory_point_count(); ++j) {
      swung_jacobian(profile[static_cast<size_t>(i)], trajectory[static_cast<size_t>(j)],
                     surface_.alpha(), layout_, order, jacobian);
      const double* m = quadrature_.material(i, j);
      // f_int = -dE/dq = -integral sum_Q k_Q J_Q^T (S^Q - S^Q(q_r)).
      for (int quantity = 1; quantity < kQuantityCount; ++quantity) {
        if (quadrature_.has_stiffness(quantity)) {
          add_transposed(jacobian, quantity,
                         -quadrature_.weight(i, j) * m[1 + quantity] *
                             change_from_rest(jacobian, i, j, quantity),
                         force);
        }
      }
    }
  }
}

double DNurbsSwungSurface::potential_energy(ConstVectorRef q) const {
  const int order = quadrature_.stiffness_order();
  if (order == 0) {
    return 0.0;
  }
  if (separable_) {
    check_size(q, "coordinate");
    return separable_forms_.energy(q);
  }
  std::vector<PlanarCurveSample> profile;
  std::vector<PlanarCurveSample> trajectory;
  quadrature_samples(q, profile, trajectory);
  SwungJacobian jacobian;
  double energy = 0.0;
  for (int i = 0; i < quadrature_.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature_.trajectory_point_count(); ++j) {
      swung_jacobian(profile[static_cast<size_t>(i)], trajectory[static_cast<size_t>(j)],
                     surface_.alpha(), layout_, order, jacobian);
      const double* m = quadrature_.material(i, j);
      double density = 0.0;
      for (int quantity = 1; quantity < kQuantityCount; ++quantity) {
        if (quadrature_.has_stiffness(quantity)) {
          density += m[1 + quantity] * change_from_rest(jacobian, i, j, quantity).squaredNorm();
        }
      }
      energy += 0.5 * quadrature_.weight(i, j) * density;
    }
  }
  return energy;
}

void DNurbsSwungSurface::add_inertial_force(ConstVectorRef q, ConstVectorRef qd,
                                            VectorRef force) const {
  check_size(qd, "velocity");
  if (separable_) {
    check_size(q, "coordinate");
    separable_forms_.add_inertial_force(q, qd, force);
    return;
  }
  std::vector<PlanarCurveSample> profile;
  std::vector<PlanarCurveSample> trajectory;
  quadrature_samples(q, profile, trajectory);
  SwungJacobian jacobian;
  std::array<Eigen::Vector3d, 6> rates;
  for (int i = 0; i < quadrature_.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature_.trajectory_point_count(); ++j) {
      const PlanarCurveSample& p = profile[static_cast<size_t>(i)];
      const PlanarCurveSample& t = trajectory[static_cast<size_t>(j)];
      swung_jacobian(p, t, surface_.alpha(), layout_, 0, jacobian);
      swung_jacobian_rate(p, t, surface_.alpha(), layout_, qd.data(), 0, rates);
      // g = -integral mu J^T (Jdot qd).
      const double mu = quadrature_.material(i, j)[0] * quadrature_.weight(i, j);
      add_transposed(jacobian, 0, -mu * rates[0], force);
    }
  }
}

void DNurbsSwungSurface::add_point_force(ConstVectorRef q, const Eigen::Vector2d& u,
                                         const Eigen::Vector3d& f, VectorRef force) const {
  SwungJacobian point;
  jacobian(q, u, 0, point);
  add_transposed(point, 0, f, force);
}

void DNurbsSwungSurface::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                               VectorRef force) const {
  // f_q = integral J^T f(u, v) du dv (Terzopoulos, below eq. 1.26) by the model's Gauss rule.
  std::vector<PlanarCurveSample> profile;
  std::vector<PlanarCurveSample> trajectory;
  quadrature_samples(q, profile, trajectory);
  SwungJacobian jacobian;
  MaterialSample sample;
  for (int i = 0; i < quadrature_.profile_point_count(); ++i) {
    for (int j = 0; j < quadrature_.trajectory_point_count(); ++j) {
      swung_jacobian(profile[static_cast<size_t>(i)], trajectory[static_cast<size_t>(j)],
                     surface_.alpha(), layout_, 1, jacobian);
      sample.parameter = quadrature_.parameter(i, j);
      sample.position = jacobian.point_derivatives[0];
      sample.tangent_u = jacobian.point_derivatives[1];
      sample.tangent_v = jacobian.point_derivatives[2];
      sample.mass_density = quadrature_.material(i, j)[0];
      add_transposed(jacobian, 0, quadrature_.weight(i, j) * density(sample), force);
    }
  }
}

void DNurbsSwungSurface::project_state(Eigen::Ref<Eigen::VectorXd> q,
                                       Eigen::Ref<Eigen::VectorXd> qd) const {
  if (layout_.mode != WeightMode::kFree) {
    return;
  }
  const int count = layout_.profile_count + layout_.trajectory_count;
  for (int i = 0; i < count; ++i) {
    const int index = 3 * i + 2;
    if (q[index] < minimum_weight_) {
      q[index] = minimum_weight_;
      qd[index] = std::max(qd[index], 0.0);
    }
  }
}

// -----------------------------------------------------------------------------------------------
// Coordinates

int DNurbsSwungSurface::profile_offset(int i) const {
  if (i < 0 || i >= layout_.profile_count) {
    throw make_error("profile control point index ", i, " is outside 0..",
                     layout_.profile_count - 1);
  }
  return layout_.profile_offset(i);
}

int DNurbsSwungSurface::trajectory_offset(int j) const {
  if (j < 0 || j >= layout_.trajectory_count) {
    throw make_error("trajectory control point index ", j, " is outside 0..",
                     layout_.trajectory_count - 1);
  }
  return layout_.trajectory_offset(j);
}

SwungSurface DNurbsSwungSurface::surface(const ConstVectorRef& q) const {
  check_size(q, "coordinate");
  return swung_surface_at(surface_, layout_.mode, q);
}

double DNurbsSwungSurface::parametric_measure() const {
  return (surface_.u_end() - surface_.u_start()) * (surface_.v_end() - surface_.v_start());
}

}  // namespace dnurbs
