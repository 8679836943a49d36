// The shape side of the triangular D-NURBS model's contract (dynamics/core/model.h): domain,
// parametric surface, tessellation and the kinematics of the parametric tangents.

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/dynamics/triangular/triangular_dnurbs_surface.h"
#include "dnurbs/dynamics/triangular/triangular_tessellation.h"

namespace dnurbs {

namespace {

// Second directional derivatives along the coordinate rates (dP_a, dw_a) of the point and of
// one parametric derivative alpha (1: u, 2: v) of a rational surface, from the homogeneous
// forms A = sum_a N_a w_a P_a = x W and W = sum_a N_a w_a differentiated twice along the rates
// (D2 W = 0, as W is linear in the weights) and once in the parameter (Piegl & Tiller, The
// NURBS Book, eq. 4.8):
//   D2x       = (D2A - 2 DW Dx) / W,
//   D2x_alpha = (D2A_alpha - 2 Dx_alpha DW - 2 Dx DW_alpha - D2x W_alpha) / W.
struct HomogeneousRates {
  double w = 0.0;   // W (or W_alpha)
  double dw = 0.0;  // DW
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d da = Eigen::Vector3d::Zero();
  Eigen::Vector3d d2a = Eigen::Vector3d::Zero();
};

HomogeneousRates homogeneous_rates(const TriangularBasisValues& values, int alpha,
                                   const TriangularControlNet& net, ConstVectorRef qd,
                                   int per_point) {
  HomogeneousRates h;
  for (int a = 0; a < values.count; ++a) {
    const int i = values.function[static_cast<size_t>(a)];
    const double N = values.value(alpha, a);
    const double w = net.weights[static_cast<std::ptrdiff_t>(i) * net.weight_stride];
    const double dw = per_point == 4 ? qd[4 * i + 3] : 0.0;
    const Eigen::Vector3d P = Eigen::Map<const Eigen::Vector3d>(
        net.positions + static_cast<std::ptrdiff_t>(i) * net.position_stride);
    const Eigen::Vector3d dP = qd.segment<3>(per_point * i);
    h.w += N * w;
    h.dw += N * dw;
    h.a += N * w * P;
    h.da += N * (dw * P + w * dP);
    h.d2a += 2.0 * N * dw * dP;
  }
  return h;
}

// The second directional derivatives of x_u and x_v (Jdot_u qd, Jdot_v qd).
std::array<Eigen::Vector3d, 2> tangent_biases(const TriangularBasisValues& values,
                                              const TriangularControlNet& net, ConstVectorRef qd,
                                              int per_point) {
  const HomogeneousRates h0 = homogeneous_rates(values, 0, net, qd, per_point);
  const Eigen::Vector3d x = h0.a / h0.w;
  const Eigen::Vector3d dx = (h0.da - h0.dw * x) / h0.w;
  const Eigen::Vector3d d2x = (h0.d2a - 2.0 * h0.dw * dx) / h0.w;
  std::array<Eigen::Vector3d, 2> bias;
  for (int alpha = 1; alpha <= 2; ++alpha) {
    const HomogeneousRates h = homogeneous_rates(values, alpha, net, qd, per_point);
    const Eigen::Vector3d x_alpha = (h.a - h.w * x) / h0.w;
    const Eigen::Vector3d dx_alpha = (h.da - x_alpha * h0.dw - dx * h.w - x * h.dw) / h0.w;
    bias[static_cast<size_t>(alpha - 1)] =
        (h.d2a - 2.0 * dx_alpha * h0.dw - 2.0 * dx * h.dw - d2x * h.w) / h0.w;
  }
  return bias;
}

}  // namespace

ParameterDomain TriangularDNurbsSurface::parameter_domain(ConstVectorRef q) const {
  check_coordinates(q);
  const Eigen::MatrixX2d& vertices = surface_.basis().triangulation().vertices();
  ParameterDomain domain;
  domain.u_min = vertices.col(0).minCoeff();
  domain.u_max = vertices.col(0).maxCoeff();
  domain.v_min = vertices.col(1).minCoeff();
  domain.v_max = vertices.col(1).maxCoeff();
  return domain;
}

ParametricSurface TriangularDNurbsSurface::parametric_surface(ConstVectorRef q) const {
  const ParameterDomain domain = parameter_domain(q);
  const double box = (domain.u_max - domain.u_min) * (domain.v_max - domain.v_min);
  const double area = parametric_measure();
  if (std::abs(box - area) > 1e-12 * box) {
    throw make_error("the triangulated domain (area ", area,
                     ") does not fill its bounding box (area ", box,
                     "): no rectangular parameterization; tessellate the model instead");
  }
  const TriangularNurbsSurface shape = surface(q);
  return {domain,
          [shape](double u, double v) {
            return shape.point({u, v});
          },
          [shape](double u, double v) {
            return shape.unit_normal({u, v});
          },
          NormalOrientation::kSuCrossSv};
}

TriangleMesh TriangularDNurbsSurface::tessellate(ConstVectorRef q,
                                                 const ModelTessellationSettings& settings,
                                                 std::string name) const {
  if (settings.max_error > 0.0) {
    return tessellate_triangular_surface_adaptive(surface(q), settings.max_error,
                                                  settings.max_level, std::move(name));
  }
  if (settings_.tessellation_max_error > 0.0) {
    return tessellate_triangular_surface_adaptive(surface(q), settings_.tessellation_max_error,
                                                  settings_.tessellation_max_level,
                                                  std::move(name));
  }
  int subdivisions = settings_.tessellation_subdivisions;
  if (subdivisions == 0) {
    // The fewest subdivisions that make every mesh edge at most width / segments per direction
    if (settings.segments_u < 1 || settings.segments_v < 1) {
      throw make_error("model tessellation: resolution ", settings.segments_u, " by ",
                       settings.segments_v, " is below 1");
    }
    const Triangulation& triangulation = surface_.basis().triangulation();
    const ParameterDomain domain = parameter_domain(q);
    double longest = 0.0;
    for (int t = 0; t < triangulation.triangle_count(); ++t) {
      for (int c = 0; c < 3; ++c) {
        longest = std::max(
            longest, (triangulation.corner(t, c) - triangulation.corner(t, (c + 1) % 3)).norm());
      }
    }
    const double density = std::max(settings.segments_u / (domain.u_max - domain.u_min),
                                    settings.segments_v / (domain.v_max - domain.v_min));
    subdivisions = std::clamp(static_cast<int>(std::ceil(longest * density - 1e-9)), 1, 1024);
  }
  return tessellate_triangular_surface(surface(q), subdivisions, std::move(name));
}

void TriangularDNurbsSurface::tangent_kinematics(ConstVectorRef q, ConstVectorRef qd,
                                                 const Eigen::Vector2d& u,
                                                 TangentKinematics& tangents) const {
  check_velocity(qd);
  const bool free = mode_ == WeightMode::kFree;
  const TriangularControlNet net = control_net(q);
  TriangularBasisValues values;
  TriangularRationalJacobian jacobian;
  jacobian_at(u, net, 1, free, jacobian, values);
  tangents.su = jacobian.point[1];
  tangents.sv = jacobian.point[2];
  // Columns of every listed B-spline (ascending: the basis lists them in index order), their
  // blocks of J_u and J_v, and the rates J_u qd, J_v qd
  start_tangent_columns(values.count, tangents);
  const Eigen::Vector3d no_weight_column = Eigen::Vector3d::Zero();
  for (int a = 0; a < values.count; ++a) {
    add_tangent_columns(a, values.function[static_cast<size_t>(a)], jacobian.rational(1, a),
                        jacobian.rational(2, a),
                        free ? Eigen::Vector3d(jacobian.weight_column[1].col(a)) : no_weight_column,
                        free ? Eigen::Vector3d(jacobian.weight_column[2].col(a)) : no_weight_column,
                        qd, tangents);
  }
  if (free) {
    const std::array<Eigen::Vector3d, 2> bias = tangent_biases(values, net, qd, 4);
    tangents.su_bias = bias[0];
    tangents.sv_bias = bias[1];
  }
}

}  // namespace dnurbs
