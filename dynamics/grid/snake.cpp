#include "dnurbs/dynamics/grid/snake.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/dynamics/core/node_interpolation.h"
#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/image.h"

namespace dnurbs {

namespace {

using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

Eigen::VectorXd weights(const Eigen::VectorXd& given, double constant, int count,
                        const char* name) {
  Eigen::VectorXd w = given.size() == 0 ? Eigen::VectorXd::Constant(count, constant) : given;
  if (w.size() != count) {
    throw make_error(name, " has ", w.size(), " entries for a snake of ", count, " nodes");
  }
  for (int i = 0; i < count; ++i) {
    if (!(w[i] >= 0.0) || !std::isfinite(w[i])) {
      throw make_error(name, " at node ", i, " is ", w[i], ", not a non-negative finite number");
    }
  }
  return w;
}

}  // namespace

Snake::Snake(const NodeChain& chain, const NodePositions& initial, const SnakeMaterial& material)
    : chain_(chain), initial_(initial) {
  const int n = chain.count();
  if (initial.rows() != n) {
    throw make_error("snake initial positions have ", initial.rows(), " rows for ", n, " nodes");
  }
  for (int i = 0; i < n; ++i) {
    if (!initial.row(i).allFinite()) {
      throw make_error("snake initial position of node ", i, " is not finite");
    }
  }
  if (!(material.mass_density > 0.0) || !std::isfinite(material.mass_density)) {
    throw make_error("snake mass density mu = ", material.mass_density,
                     " is not positive and finite");
  }
  if (!(material.damping_density >= 0.0) || !std::isfinite(material.damping_density)) {
    throw make_error("snake damping density gamma = ", material.damping_density,
                     " is not non-negative and finite");
  }
  Eigen::VectorXd w1 = weights(material.tension, material.constant_tension, n, "tension w1");
  Eigen::VectorXd w2 = weights(material.rigidity, material.constant_rigidity, n, "rigidity w2");
  if (!chain.closed()) {
    // An open chain has no difference past its ends: no u_N - u_{N-1} and no second
    // difference at the end nodes.
    w1[n - 1] = 0.0;
    w2[0] = 0.0;
    w2[n - 1] = 0.0;
  }
  const double h = chain.spacing();
  const double h2 = h * h;
  const double h4 = h2 * h2;
  const auto at = [&](const Eigen::VectorXd& w, int i) { return w[((i % n) + n) % n]; };
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < n; ++i) {
    // Terzopoulos 2003, eqs. 1.9-1.11, indices modulo N.
    const double a =
        (at(w1, i - 1) + at(w1, i)) / h2 + (at(w2, i - 1) + 4.0 * at(w2, i) + at(w2, i + 1)) / h4;
    const double b = -at(w1, i) / h2 - 2.0 * (at(w2, i) + at(w2, i + 1)) / h4;
    const double c = at(w2, i + 1) / h4;
    triplets.emplace_back(i, i, a);
    const int i1 = chain.neighbor(i, 1);
    const int i2 = chain.neighbor(i, 2);
    if (i1 >= 0 && b != 0.0) {
      triplets.emplace_back(i, i1, b);
      triplets.emplace_back(i1, i, b);
    }
    if (i2 >= 0 && c != 0.0) {
      triplets.emplace_back(i, i2, c);
      triplets.emplace_back(i2, i, c);
    }
  }
  scalar_.stiffness.resize(n, n);
  scalar_.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  scalar_.stiffness.makeCompressed();
  SparseMatrix identity(n, n);
  identity.setIdentity();
  scalar_.mass = material.mass_density * identity;
  scalar_.damping = material.damping_density > 0.0
                        ? SparseMatrix(material.damping_density * identity)
                        : SparseMatrix(n, n);
  matrices_.mass = kronecker_identity(scalar_.mass, 3);
  matrices_.damping = kronecker_identity(scalar_.damping, 3);
  matrices_.stiffness = kronecker_identity(scalar_.stiffness, 3);
}

NodePositions Snake::positions(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("snake coordinates have ", q.size(), " entries, not ", coordinate_count());
  }
  return Eigen::Map<const RowNodes>(q.data(), chain_.count(), 3);
}

Eigen::VectorXd Snake::initial_coordinates() const {
  Eigen::VectorXd q(coordinate_count());
  Eigen::Map<RowNodes>(q.data(), chain_.count(), 3) = initial_;
  return q;
}

Eigen::Vector3d Snake::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  return interpolate_nodes(q, chain_.linear_weights(u.x()));
}

SparseMatrix Snake::position_jacobian(ConstVectorRef /*q*/, const Eigen::Vector2d& u) const {
  return node_interpolation_jacobian(chain_.linear_weights(u.x()), coordinate_count());
}

void Snake::assemble_matrices(ConstVectorRef /*q*/, ModelMatrices& matrices) const {
  matrices = matrices_;
}

void Snake::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                  VectorRef force) const {
  MaterialSample sample;
  sample.mass_density = scalar_.mass.coeff(0, 0);
  const int n = chain_.count();
  for (int i = 0; i < n; ++i) {
    sample.parameter = Eigen::Vector2d(chain_.parameter(i), 0.0);
    sample.position = q.segment<3>(3 * i);
    const int next = chain_.neighbor(i, 1) >= 0 ? chain_.neighbor(i, 1) : i;
    const int previous = chain_.neighbor(i, -1) >= 0 ? chain_.neighbor(i, -1) : i;
    sample.tangent_u = (q.segment<3>(3 * next) - q.segment<3>(3 * previous)) /
                       ((next - previous == 0 ? 1 : 2) * chain_.spacing());
    force.segment<3>(3 * i) += density(sample);
  }
}

int Snake::control_point_offset(int i) const {
  if (i < 0 || i >= chain_.count()) {
    throw make_error("snake node ", i, " is outside 0..", chain_.count() - 1);
  }
  return 3 * i;
}

ParameterDomain Snake::parameter_domain(ConstVectorRef /*q*/) const {
  ParameterDomain domain;
  domain.periodic_u = chain_.closed();
  return domain;
}

Force potential_force(Potential potential, double gradient_step) {
  if (!potential) {
    throw make_error("potential force has no potential function");
  }
  if (!(gradient_step > 0.0) || !std::isfinite(gradient_step)) {
    throw make_error("potential gradient step ", gradient_step, " is not positive and finite");
  }
  return [potential = std::move(potential), gradient_step](const Model& model, double /*t*/,
                                                           ConstVectorRef q, ConstVectorRef /*qd*/,
                                                           VectorRef generalized) {
    const int nodes = model.coordinate_count() / 3;
    for (int i = 0; i < nodes; ++i) {
      const int offset = model.control_point_offset(i);
      const Eigen::Vector2d x = q.segment<2>(offset);
      const Eigen::Vector2d ex(gradient_step, 0.0);
      const Eigen::Vector2d ey(0.0, gradient_step);
      // Terzopoulos 2003, eq. 1.5: the external force -grad P(v).
      generalized[offset] -= (potential(x + ex) - potential(x - ex)) / (2.0 * gradient_step);
      generalized[offset + 1] -= (potential(x + ey) - potential(x - ey)) / (2.0 * gradient_step);
    }
  };
}

Potential image_potential(const Eigen::MatrixXd& image, double sigma, double c) {
  if (image.rows() < 2 || image.cols() < 2) {
    throw make_error("image of ", image.rows(), " by ", image.cols(),
                     " pixels is smaller than 2 by 2");
  }
  // Rows are y and columns x here, Image is width by height: the transpose.
  Image data(static_cast<int>(image.cols()), static_cast<int>(image.rows()));
  data.values = image.transpose().array();
  auto potential = std::make_shared<const ImageEdgePotential>(data, sigma, c);
  return [potential](const Eigen::Vector2d& x) { return potential->value(x); };
}

}  // namespace dnurbs
