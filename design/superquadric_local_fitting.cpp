#include "dnurbs/design/superquadric_local_fitting.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>

#include "dnurbs/core/error.h"
#include "dnurbs/design/point_set.h"
#include "dnurbs/design/superquadric_radial_distance.h"

namespace dnurbs {

void validate_superquadric_local_fit_settings(const SuperquadricLocalFitSettings& settings) {
  if (settings.mesh_cells_u < 2 || settings.mesh_cells_v < 3) {
    throw make_error("superquadric local fit: mesh cells ", settings.mesh_cells_u, " x ",
                     settings.mesh_cells_v, "; they must be at least 2 x 3");
  }
  if (!(settings.smoothness > 0.0) || !std::isfinite(settings.smoothness)) {
    throw make_error("superquadric local fit: smoothness is ", settings.smoothness,
                     "; it must be finite and positive");
  }
  const FeStiffnessCoefficients& k = settings.stiffness;
  for (const double value : {k.membrane_u, k.membrane_v, k.spring}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw make_error("superquadric local fit: stiffness (membrane_u ", k.membrane_u,
                       ", membrane_v ", k.membrane_v, ", spring ", k.spring,
                       ") must be finite and >= 0");
    }
  }
  if (k.membrane_u + k.membrane_v + k.spring == 0.0) {
    throw make_error("superquadric local fit: the stiffness coefficients are all zero");
  }
}

SuperquadricLocalFitResult fit_superquadric_local_displacements(
    const Eigen::MatrixX3d& points, const SuperquadricShapeParameters& shape,
    const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
    const SuperquadricLocalFitSettings& settings) {
  check_points(points, "points to fit");
  validate_superquadric_local_fit_settings(settings);
  const DeformableSuperquadricShape reference(shape);
  const ParametricFeMesh mesh(settings.mesh_cells_u, settings.mesh_cells_v);
  const auto count = static_cast<double>(points.rows());
  const double kappa = 1.0 / (count * settings.smoothness);

  // Terzopoulos, eq. 1.38 at rest for q_d: (K_d + kappa sum S_k^T S_k) q_d =
  // kappa sum S_k^T (p_k - s_k), all blocks k (x) I_3 (scalar node matrices).
  SuperquadricLocalFitResult result;
  result.mesh_cells_u = settings.mesh_cells_u;
  result.mesh_cells_v = settings.mesh_cells_v;
  result.parameters.resize(points.rows(), 2);
  const int nodes = mesh.node_count();
  std::vector<Eigen::Triplet<double>> data_terms;
  data_terms.reserve(static_cast<size_t>(points.rows()) * FeShapeValues::kMaxActive *
                     FeShapeValues::kMaxActive);
  Eigen::MatrixX3d right_side = Eigen::MatrixX3d::Zero(nodes, 3);
  std::vector<FeShapeValues> shape_values(static_cast<size_t>(points.rows()));
  Eigen::MatrixX3d offsets(points.rows(), 3);  // p_k - s_k, body frame
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Eigen::Vector3d p = rotation.transpose() * (points.row(k).transpose() - centre);
    const Eigen::Vector2d uv = superquadric_radial_projection(shape, p);
    result.parameters.row(k) = uv.transpose();
    const FeShapeValues& fe = shape_values[static_cast<size_t>(k)] =
        mesh.shape_values(uv.x(), uv.y());
    offsets.row(k) = (p - reference.point(uv.x(), uv.y())).transpose();
    for (int a = 0; a < fe.active_count; ++a) {
      const auto na = static_cast<size_t>(a);
      right_side.row(fe.node[na]) += kappa * fe.value[a] * offsets.row(k);
      for (int b = 0; b < fe.active_count; ++b) {
        data_terms.emplace_back(fe.node[na], fe.node[static_cast<size_t>(b)],
                                kappa * fe.value[a] * fe.value[b]);
      }
    }
  }
  Eigen::SparseMatrix<double> data_matrix(nodes, nodes);
  data_matrix.setFromTriplets(data_terms.begin(), data_terms.end());
  const Eigen::SparseMatrix<double> system =
      mesh.scalar_stiffness_matrix(settings.stiffness) + data_matrix;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any()) {
    throw make_error("superquadric local fit: the equilibrium matrix (", nodes,
                     " nodes) is singular: no spring, and no point near some part of the mesh");
  }
  const Eigen::MatrixX3d nodal = solver.solve(right_side);  // node a: row a = d_a^T
  result.displacements.resize(3 * static_cast<Eigen::Index>(nodes));
  for (int a = 0; a < nodes; ++a) {
    result.displacements.segment<3>(3 * static_cast<Eigen::Index>(a)) = nodal.row(a).transpose();
  }

  // Residuals |x_k - x(u_k)| = |p_k - s_k - d(u_k)| (R is orthogonal), with and without d.
  double sum = 0.0;
  double global_sum = 0.0;
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const FeShapeValues& fe = shape_values[static_cast<size_t>(k)];
    Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
    for (int a = 0; a < fe.active_count; ++a) {
      d += fe.value[a] * nodal.row(fe.node[static_cast<size_t>(a)]);
    }
    const double error = (offsets.row(k) - d).norm();
    const double global_error = offsets.row(k).norm();
    sum += error * error;
    global_sum += global_error * global_error;
    result.max_error = std::max(result.max_error, error);
    result.global_max_error = std::max(result.global_max_error, global_error);
  }
  result.rms_error = std::sqrt(sum / count);
  result.global_rms_error = std::sqrt(global_sum / count);
  return result;
}

}  // namespace dnurbs
