#include "dnurbs/dynamics/grid/terzopoulos_surface.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/dynamics/core/node_interpolation.h"

namespace dnurbs {

const char* to_string(NormalApproximation normal) {
  switch (normal) {
    case NormalApproximation::kClassic:
      return "classic";
    case NormalApproximation::kChristoffel:
      return "christoffel";
    case NormalApproximation::kChristoffelUnnormalized:
      return "christoffel_unnormalized";
  }
  return "classic";
}

NormalApproximation parse_normal_approximation(const std::string& name) {
  for (const auto normal : {NormalApproximation::kClassic, NormalApproximation::kChristoffel,
                            NormalApproximation::kChristoffelUnnormalized}) {
    if (name == to_string(normal)) {
      return normal;
    }
  }
  throw make_error("normal is \"", name,
                   "\", must be classic, christoffel or christoffel_unnormalized");
}

namespace {

using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

void check_weights(const Eigen::Matrix2d& weights, const char* name, int node) {
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      if (!(weights(a, b) >= 0.0) || !std::isfinite(weights(a, b))) {
        throw make_error(name, "_", a + 1, b + 1, " = ", weights(a, b), " at node ", node,
                         " is not a non-negative finite number");
      }
    }
  }
  if (weights(0, 1) != weights(1, 0)) {
    throw make_error(name, "_12 = ", weights(0, 1), " differs from ", name, "_21 = ", weights(1, 0),
                     " at node ", node, " (the weights must be symmetric)");
  }
}

// (11, 12, 22) of a node's symmetric 2 by 2 weights.
Eigen::RowVector3d packed(const Eigen::Matrix2d& weights) {
  return {weights(0, 0), weights(0, 1), weights(1, 1)};
}

// Row-wise dot products of two #nodes by 3 fields.
Eigen::VectorXd dots(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return (a.array() * b.array()).rowwise().sum();
}

SparseMatrix scaled_identity(int n, double value) {
  SparseMatrix result(n, n);
  result.reserve(Eigen::VectorXi::Constant(n, 1));
  for (int k = 0; k < n; ++k) {
    result.insert(k, k) = value;
  }
  result.makeCompressed();
  return result;
}

// Column of a packed (11, 12, 22) field for the index pair (i, j), i, j in {0, 1}.
int packed_column(int i, int j) {
  return i + j;
}

}  // namespace

// Derivative estimates and tensors at one state.
struct TerzopoulosSurface::Geometry {
  std::array<Eigen::MatrixX3d, 2> forward;  // D+_1 r, D+_2 r
  std::array<Eigen::MatrixX3d, 3> second;   // D+_11 r, D+_12 r, D+_22 r (packed order)
  std::array<Eigen::MatrixX3d, 2> tangent;  // central tangents
  Eigen::MatrixX3d normal;                  // unit normal (zero where degenerate)
  Eigen::MatrixX3d metric;                  // G_ij of the forward differences
  Eigen::MatrixX3d curvature;               // B_ij = n . D+_ij r
};

TerzopoulosSurface::Geometry TerzopoulosSurface::geometry(
    const Eigen::Ref<const NodePositions>& r) const {
  Geometry g;
  g.forward[0] = operators_.d1 * r;
  g.forward[1] = operators_.d2 * r;
  g.second[0] = operators_.d11 * r;
  g.second[1] = operators_.d12 * r;
  g.second[2] = operators_.d22 * r;
  g.tangent[0] = operators_.t1 * r;
  g.tangent[1] = operators_.t2 * r;
  const int n = grid_.node_count();
  g.normal.resize(n, 3);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d cross =
        g.tangent[0].row(k).transpose().cross(g.tangent[1].row(k).transpose());
    const double length = cross.norm();
    g.normal.row(k) = length > 0.0 ? Eigen::RowVector3d((cross / length).transpose())
                                   : Eigen::RowVector3d::Zero();
  }
  // Wu & de Melo, eq. 3: G_ij = r_i . r_j; eq 6: B_ij = n . r_ij.
  g.metric.resize(n, 3);
  g.metric.col(0) = dots(g.forward[0], g.forward[0]);
  g.metric.col(1) = dots(g.forward[0], g.forward[1]);
  g.metric.col(2) = dots(g.forward[1], g.forward[1]);
  g.curvature.resize(n, 3);
  for (int c = 0; c < 3; ++c) {
    g.curvature.col(c) = dots(g.normal, g.second[static_cast<size_t>(c)]);
  }
  return g;
}

TerzopoulosSurface::TerzopoulosSurface(const Grid& grid, const NodePositions& rest,
                                       const TerzopoulosMaterial& material,
                                       const TerzopoulosSettings& settings)
    : grid_(grid), material_(material), settings_(settings) {
  if (grid.nu() < 3 || grid.nv() < 3) {
    throw make_error("Terzopoulos surface grid of ", grid.nu(), " by ", grid.nv(),
                     " nodes is smaller than the 3 by 3 nodes its second differences need");
  }
  check_grid_positions(grid, rest, "rest position");
  if (!(material.mass_density > 0.0) || !std::isfinite(material.mass_density)) {
    throw make_error("mass density mu = ", material.mass_density, " is not positive and finite");
  }
  if (!(material.damping_density >= 0.0) || !std::isfinite(material.damping_density)) {
    throw make_error("damping density gamma = ", material.damping_density,
                     " is not non-negative and finite");
  }
  check_weights(material.eta, "eta", -1);
  check_weights(material.xi, "xi", -1);
  if (!(settings.delta > 0.0) || !std::isfinite(settings.delta)) {
    throw make_error("normal threshold delta = ", settings.delta, " is not positive and finite");
  }
  operators_ = grid_difference_operators(grid);
  initial_ = rest;
  const int n = grid.node_count();
  eta_ = packed(material.eta).replicate(n, 1);
  xi_ = packed(material.xi).replicate(n, 1);
  set_rest(rest);
}

void TerzopoulosSurface::set_rest(const NodePositions& rest) {
  rest_ = rest;
  const Geometry g = geometry(rest_);
  rest_metric_ = g.metric;
  rest_curvature_ = g.curvature;
}

void TerzopoulosSurface::set_plastic_flow(const std::optional<PlasticFlow>& flow) {
  if (flow) {
    check_plastic_flow(*flow);
  }
  plastic_flow_ = flow;
}

int TerzopoulosSurface::flow_rest_shape(ConstVectorRef q, double dt) {
  if (!plastic_flow_) {
    return 0;
  }
  if (q.size() != coordinate_count()) {
    throw make_error("Terzopoulos surface coordinates have ", q.size(), " entries, not ",
                     coordinate_count());
  }
  Eigen::VectorXd rest = flowing_rest_coordinates();
  const int yielded = flow_rest_positions(*plastic_flow_, dt, 3, q, rest);
  if (yielded > 0) {
    set_rest(Eigen::Map<const RowNodes>(rest.data(), grid_.node_count(), 3));
  }
  return yielded;
}

Eigen::VectorXd TerzopoulosSurface::flowing_rest_coordinates() const {
  if (!plastic_flow_) {
    return {};
  }
  Eigen::VectorXd rest(coordinate_count());
  Eigen::Map<RowNodes>(rest.data(), grid_.node_count(), 3) = rest_;
  return rest;
}

void TerzopoulosSurface::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  if (!plastic_flow_) {
    Model::restore_flowing_rest_coordinates(rest);
  }
  check_rest_coordinates(rest, coordinate_count());
  set_rest(Eigen::Map<const RowNodes>(rest.data(), grid_.node_count(), 3));
}

void TerzopoulosSurface::check_node(int node) const {
  if (node < 0 || node >= grid_.node_count()) {
    throw make_error("node ", node, " is outside 0..", grid_.node_count() - 1);
  }
}

void TerzopoulosSurface::set_node_elasticity(int node, const Eigen::Matrix2d& eta,
                                             const Eigen::Matrix2d& xi) {
  check_node(node);
  check_weights(eta, "eta", node);
  check_weights(xi, "xi", node);
  eta_.row(node) = packed(eta);
  xi_.row(node) = packed(xi);
}

void TerzopoulosSurface::set_initial_positions(const NodePositions& positions) {
  check_grid_positions(grid_, positions, "initial position");
  initial_ = positions;
}

void TerzopoulosSurface::fix_border() {
  for (const int node : grid_.border_nodes()) {
    fix_point(node);
  }
}

NodePositions TerzopoulosSurface::positions(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("Terzopoulos surface coordinates have ", q.size(), " entries, not ",
                     coordinate_count());
  }
  return Eigen::Map<const RowNodes>(q.data(), grid_.node_count(), 3);
}

SurfaceTensors TerzopoulosSurface::tensors(ConstVectorRef q) const {
  const Geometry g = geometry(positions(q));
  return {g.metric, g.curvature};
}

TerzopoulosSurface::ChristoffelCoefficients TerzopoulosSurface::christoffel_coefficients(
    const Geometry& g) const {
  // Coefficients of the state they are computed at (the "previous state k-1" of Wu & de Melo,
  // section 4): metric of the central tangents, its inverse (eq 13), Christoffel symbols
  // (eq 15) and Weingarten coefficients d_ki (eq 8, n_i = sum_k d_ki r_k).
  const int n = grid_.node_count();
  const Eigen::VectorXd tg11 = dots(g.tangent[0], g.tangent[0]);
  const Eigen::VectorXd tg12 = dots(g.tangent[0], g.tangent[1]);
  const Eigen::VectorXd tg22 = dots(g.tangent[1], g.tangent[1]);
  const Eigen::VectorXd det = tg11.cwiseProduct(tg22) - tg12.cwiseProduct(tg12);
  // christoffel[c][l]: Gamma^l_ij for the packed pair c.
  std::array<std::array<Eigen::VectorXd, 2>, 3> christoffel;
  for (auto& row : christoffel) {
    for (auto& v : row) {
      v.setZero(n);
    }
  }
  ChristoffelCoefficients result;
  for (auto& row : result.weingarten) {
    for (auto& v : row) {
      v.setZero(n);
    }
  }
  auto& weingarten = result.weingarten;
  for (int node = 0; node < n; ++node) {
    const double g_det = det[node];
    if (!(g_det > 1e-300)) {
      continue;  // degenerate tangents: no coefficients
    }
    const double inv11 = tg22[node] / g_det;
    const double inv12 = -tg12[node] / g_det;
    const double inv22 = tg11[node] / g_det;
    for (int c = 0; c < 3; ++c) {
      const Eigen::RowVector3d rij = g.second[static_cast<size_t>(c)].row(node);
      const double p1 = rij.dot(g.tangent[0].row(node));
      const double p2 = rij.dot(g.tangent[1].row(node));
      christoffel[static_cast<size_t>(c)][0][node] = inv11 * p1 + inv12 * p2;
      christoffel[static_cast<size_t>(c)][1][node] = inv12 * p1 + inv22 * p2;
    }
    const double b11 = g.curvature(node, 0);
    const double b12 = g.curvature(node, 1);
    const double b22 = g.curvature(node, 2);
    weingarten[0][0][node] = (b12 * tg12[node] - b11 * tg22[node]) / g_det;  // d_11
    weingarten[1][0][node] = (b11 * tg12[node] - b12 * tg11[node]) / g_det;  // d_21
    weingarten[1][1][node] = (b12 * tg12[node] - b22 * tg11[node]) / g_det;  // d_22
    weingarten[0][1][node] = (b22 * tg12[node] - b12 * tg22[node]) / g_det;  // d_12
  }
  const std::array<const SparseMatrix*, 3> second{&operators_.d11, &operators_.d12,
                                                  &operators_.d22};
  for (int c = 0; c < 3; ++c) {
    const SparseMatrix& dij = *second[static_cast<size_t>(c)];
    // Eqs 24-26: n = s [D+_ij r - Gamma^1_ij r_1 - Gamma^2_ij r_2], s = 1/B if |B| > delta, +1
    // if 0 <= B <= delta, -1 if -delta < B < 0. The Gamma terms are dropped where D+_ij r is not
    // computable (a zero row of D+_ij), and r_1, r_2 are the central tangents Gamma is computed
    // with, so that at the coefficients' own state n is exactly the unit normal where |B| > delta.
    // Without normalization (section 4's first attempt, figure 6) |B_ij| = 1: only the sign.
    const bool normalized = settings_.normal != NormalApproximation::kChristoffelUnnormalized;
    Eigen::VectorXd s(n);
    Eigen::VectorXd computable = Eigen::VectorXd::Zero(n);
    for (int node = 0; node < n; ++node) {
      const double bk = g.curvature(node, c);
      s[node] = normalized && std::abs(bk) > settings_.delta ? 1.0 / bk : (bk >= 0.0 ? 1.0 : -1.0);
    }
    for (Eigen::Index col = 0; col < dij.outerSize(); ++col) {
      for (SparseMatrix::InnerIterator it(dij, col); it; ++it) {
        computable[it.row()] = 1.0;
      }
    }
    const Eigen::VectorXd gamma1 = christoffel[static_cast<size_t>(c)][0].cwiseProduct(computable);
    const Eigen::VectorXd gamma2 = christoffel[static_cast<size_t>(c)][1].cwiseProduct(computable);
    result.normal[static_cast<size_t>(c)] =
        s.asDiagonal() * SparseMatrix(dij - gamma1.asDiagonal() * operators_.t1 -
                                      gamma2.asDiagonal() * operators_.t2);
  }
  return result;
}

std::array<NodePositions, 3> TerzopoulosSurface::approximate_normals(ConstVectorRef previous,
                                                                     ConstVectorRef q) const {
  const ChristoffelCoefficients coefficients =
      christoffel_coefficients(geometry(positions(previous)));
  const NodePositions r = positions(q);
  std::array<NodePositions, 3> normals;
  for (size_t c = 0; c < 3; ++c) {
    normals[c] = coefficients.normal[c] * r;
  }
  return normals;
}

SparseMatrix TerzopoulosSurface::linearized_stiffness(ConstVectorRef q) const {
  const NodePositions r = positions(q);
  const Geometry g = geometry(r);
  const int n = grid_.node_count();
  const std::array<const SparseMatrix*, 2> first{&operators_.d1, &operators_.d2};
  const std::array<const SparseMatrix*, 3> second{&operators_.d11, &operators_.d12,
                                                  &operators_.d22};
  // Wu & de Melo, eq. 20: alpha_ij = eta_ij (G_ij - G0_ij), beta_ij = xi_ij (B_ij - B0_ij).
  const Eigen::MatrixX3d alpha = eta_.cwiseProduct(g.metric - rest_metric_);
  const Eigen::MatrixX3d beta = xi_.cwiseProduct(g.curvature - rest_curvature_);

  // Stretching: -sum_ij D-_i (alpha_ij D+_j r) = sum_ij (D+_i)^T alpha_ij D+_j r.
  SparseMatrix k(n, n);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const Eigen::VectorXd a = alpha.col(packed_column(i, j));
      if (a.cwiseAbs().maxCoeff() == 0.0) {
        continue;
      }
      k += SparseMatrix(first[static_cast<size_t>(i)]->transpose()) * a.asDiagonal() *
           (*first[static_cast<size_t>(j)]);
    }
  }

  const bool bending = beta.cwiseAbs().maxCoeff() > 0.0;
  if (bending && settings_.normal == NormalApproximation::kClassic) {
    // Wu & de Melo, eq. 21: d^2/da_i da_j (beta_ij r_ij) = (D+_ij)^T beta_ij D+_ij r.
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const int c = packed_column(i, j);
        const SparseMatrix& dij = *second[static_cast<size_t>(c)];
        k += SparseMatrix(dij.transpose()) * beta.col(c).asDiagonal() * dij;
      }
    }
  } else if (bending) {
    const ChristoffelCoefficients coefficients = christoffel_coefficients(g);
    const auto& weingarten = coefficients.weingarten;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const int c = packed_column(i, j);
        const Eigen::VectorXd b = beta.col(c);
        if (b.cwiseAbs().maxCoeff() == 0.0) {
          continue;
        }
        const SparseMatrix& dij = *second[static_cast<size_t>(c)];
        const SparseMatrix& di = *first[static_cast<size_t>(i)];
        const SparseMatrix& dj = *first[static_cast<size_t>(j)];
        // D-_ij(beta_ij) n, with D-_ij = (D+_ij)^T and n from eqs 24-26.
        const Eigen::VectorXd d_beta = dij.transpose() * b;
        k += d_beta.asDiagonal() * coefficients.normal[static_cast<size_t>(c)];
        // sum_k D-_j(beta_ij) d_ki D+_k r, with D-_j = -(D+_j)^T.
        const Eigen::VectorXd dj_beta = -(dj.transpose() * b);
        for (int kk = 0; kk < 2; ++kk) {
          const Eigen::VectorXd coefficient =
              dj_beta.cwiseProduct(weingarten[static_cast<size_t>(kk)][static_cast<size_t>(i)]);
          k += coefficient.asDiagonal() * (*first[static_cast<size_t>(kk)]);
        }
        // D-_i (beta_ij sum_k d_kj D+_k r).
        SparseMatrix inner = weingarten[0][static_cast<size_t>(j)].asDiagonal() * operators_.d1;
        inner += weingarten[1][static_cast<size_t>(j)].asDiagonal() * operators_.d2;
        k -= SparseMatrix(di.transpose()) * b.asDiagonal() * inner;
      }
    }
  }
  const double area = grid_.spacing() * grid_.spacing();
  k *= area;
  k.makeCompressed();
  return k;
}

Eigen::VectorXd TerzopoulosSurface::initial_coordinates() const {
  Eigen::VectorXd q(coordinate_count());
  Eigen::Map<RowNodes>(q.data(), grid_.node_count(), 3) = initial_;
  return q;
}

Eigen::Vector3d TerzopoulosSurface::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  return interpolate_nodes(q, grid_.bilinear_weights(u));
}

SparseMatrix TerzopoulosSurface::position_jacobian(ConstVectorRef /*q*/,
                                                   const Eigen::Vector2d& u) const {
  return node_interpolation_jacobian(grid_.bilinear_weights(u), coordinate_count());
}

void TerzopoulosSurface::assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const {
  const double area = grid_.spacing() * grid_.spacing();
  const int size = coordinate_count();
  // Rebuilt every time (cheap diagonals): `matrices` may have held another model's.
  matrices.mass = scaled_identity(size, material_.mass_density * area);
  matrices.damping = material_.damping_density > 0.0
                         ? scaled_identity(size, material_.damping_density * area)
                         : SparseMatrix(size, size);
  const SparseMatrix k = linearized_stiffness(q);
  if (settings_.normal == NormalApproximation::kClassic) {
    matrices.stiffness = kronecker_identity(k, 3);
  } else {
    matrices.stiffness = kronecker_identity(0.5 * (k + SparseMatrix(k.transpose())), 3);
  }
}

void TerzopoulosSurface::add_internal_force(ConstVectorRef q, VectorRef force) const {
  const SparseMatrix k = linearized_stiffness(q);
  const NodePositions r = positions(q);
  const NodePositions f = k * r;
  Eigen::Map<RowNodes>(force.data(), grid_.node_count(), 3) -= f;
}

double TerzopoulosSurface::potential_energy(ConstVectorRef q) const {
  const Geometry g = geometry(positions(q));
  // 12 terms count twice (i, j = 1, 2 and 2, 1).
  const Eigen::RowVector3d multiplicity(1.0, 2.0, 1.0);
  const Eigen::MatrixX3d dg = g.metric - rest_metric_;
  const Eigen::MatrixX3d db = g.curvature - rest_curvature_;
  double energy = 0.0;
  for (int k = 0; k < grid_.node_count(); ++k) {
    energy += (multiplicity.array() * (eta_.row(k).array() * dg.row(k).array().square() +
                                       xi_.row(k).array() * db.row(k).array().square()))
                  .sum();
  }
  return 0.25 * grid_.spacing() * grid_.spacing() * energy;
}

void TerzopoulosSurface::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                               VectorRef force) const {
  const NodePositions r = positions(q);
  const NodePositions t1 = operators_.t1 * r;
  const NodePositions t2 = operators_.t2 * r;
  const double area = grid_.spacing() * grid_.spacing();
  MaterialSample sample;
  sample.mass_density = material_.mass_density;
  for (int k = 0; k < grid_.node_count(); ++k) {
    sample.parameter = grid_.parameter(k);
    sample.position = r.row(k).transpose();
    sample.tangent_u = t1.row(k).transpose();
    sample.tangent_v = t2.row(k).transpose();
    force.segment<3>(3 * k) += area * density(sample);
  }
}

int TerzopoulosSurface::control_point_offset(int i) const {
  check_node(i);
  return 3 * i;
}

ParameterDomain TerzopoulosSurface::parameter_domain(ConstVectorRef /*q*/) const {
  return grid_parameter_domain(grid_);
}

TriangleMesh TerzopoulosSurface::tessellate(ConstVectorRef q,
                                            const ModelTessellationSettings& /*settings*/,
                                            std::string name) const {
  return grid_triangle_mesh(grid_, positions(q), std::move(name));
}

void TerzopoulosSurface::semi_implicit_matrices(ConstVectorRef q, bool scalar,
                                                ModelMatrices& matrices) const {
  const SparseMatrix k = linearized_stiffness(q);
  const double area = grid_.spacing() * grid_.spacing();
  const int nodes = grid_.node_count();
  SparseMatrix identity(nodes, nodes);
  identity.setIdentity();
  matrices.mass = material_.mass_density * area * identity;
  matrices.damping = material_.damping_density * area * identity;
  matrices.stiffness = k;
  if (!scalar) {
    matrices.mass = kronecker_identity(matrices.mass, 3);
    matrices.damping = kronecker_identity(matrices.damping, 3);
    matrices.stiffness = kronecker_identity(k, 3);
  }
}

}  // namespace dnurbs
