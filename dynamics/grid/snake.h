#pragma once
// Snakes (Terzopoulos 2003, eqs. 1.2-1.13): a chain of N nodes u_i = v(i h), open or closed, with
// tension w1 and rigidity w2, the finite-difference stiffness of eqs 1.8-1.11
//
//   a_i = (w1_{i-1} + w1_i)/h^2 + (w2_{i-1} + 4 w2_i + w2_{i+1})/h^4      (eq 1.9, diagonal)
//   b_i = -w1_i/h^2 - 2 (w2_i + w2_{i+1})/h^4                            (eq 1.10, (i, i+1))
//   c_i = w2_{i+1}/h^4                                                    (eq 1.11, (i, i+2))
//
// indices modulo N for a closed snake (the cyclic pentadiagonal matrix of eq 1.8). K is the
// Hessian of E = (1/2) sum_i w1_i |u_{i+1} - u_i|^2/h^2 + w2_i |u_{i+1} - 2u_i + u_{i-1}|^2/h^4
// (the discrete eq 1.2 with v_s forward and v_ss central differences). For an open snake the
// differences that reach past an end are left out, which is eq 1.8 without its wrap-around
// entries and with w1_{N-1} = w2_0 = w2_{N-1} = 0. M = mu I and D = gamma I (diagonal, eq 1.12).
//
// The coordinates are 3 per node (x, y, z) so that snakes share the System with surfaces; a
// planar snake keeps z = 0 under planar forces. Matrices are constant and S (x) I_3: the central
// integrator (dynamics/integrators/integrator.h) is the semi-implicit step of eq 1.13 with one
// LDL^T factorization reused for every step.

#include <functional>
#include <memory>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/surface/grid.h"
#include "dnurbs/surface/node_chain.h"

namespace dnurbs {

struct SnakeMaterial {
  double mass_density = 1.0;     ///< mu (> 0), mass per node
  double damping_density = 0.0;  ///< gamma (>= 0), damping per node
  /// w1_i and w2_i per node (N entries each, >= 0); an empty vector means the constant below.
  Eigen::VectorXd tension;
  Eigen::VectorXd rigidity;
  double constant_tension = 0.0;   ///< w1 where `tension` is empty
  double constant_rigidity = 0.0;  ///< w2 where `rigidity` is empty
};

/// A snake as a Model. q = [u_0, u_1, ...] (3 per node); material points s = u.x() in [0, 1]
/// interpolate neighboring nodes linearly.
class Snake : public Model {
 public:
  /// `initial` is #nodes by 3. Throws Error naming the value for a non-finite position, a
  /// negative or non-finite weight, a weight vector of the wrong size, mu <= 0 or gamma < 0.
  Snake(const NodeChain& chain, const NodePositions& initial, const SnakeMaterial& material);

  std::unique_ptr<Model> clone() const override { return std::make_unique<Snake>(*this); }

  const NodeChain& chain() const { return chain_; }
  /// The scalar matrices: stiffness is eq 1.8 (#nodes by #nodes).
  const ModelMatrices& scalar() const { return scalar_; }
  NodePositions positions(ConstVectorRef q) const;

  int coordinate_count() const override { return 3 * chain_.count(); }
  Eigen::VectorXd initial_coordinates() const override;
  int parametric_dimension() const override { return 1; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  bool matrices_are_constant() const override { return true; }
  const ModelMatrices* constant_matrices() const override { return &matrices_; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  int kronecker_block_size() const override { return 3; }
  const ModelMatrices* scalar_matrices() const override { return &scalar_; }
  /// Node-sampled: node i receives f(sample at node i) (the per-node convention of eq 1.6).
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  int control_point_offset(int i) const override;
  /// s in [0, 1], periodic for a closed chain.
  ParameterDomain parameter_domain(ConstVectorRef q) const override;

 private:
  NodeChain chain_;
  NodePositions initial_;
  ModelMatrices scalar_;
  ModelMatrices matrices_;
};

/// A scalar potential P(x, y) on the image plane.
using Potential = std::function<double(const Eigen::Vector2d&)>;

/// The external force of Terzopoulos 2003, eq. 1.5: -grad P at every node's (x, y) (z force 0), the
/// gradient by central differences of the given step. Acts on models with control points
/// (nodes): snakes, grid surfaces. Throws Error if the step is not positive and finite.
Force potential_force(Potential potential, double gradient_step = 1e-6);

/// The image potential of Terzopoulos 2003 (below eq 1.3): P = -c |grad(G_sigma * I)| of the
/// image given as a matrix (row y, column x; pixel units), the ImageEdgePotential of
/// vision/edge_potential.h (derivative-of-Gaussian gradient, cubic interpolation, points clamped
/// to the image) as a function. dynamics/core/image_force.h applies its exact gradient as a force
/// on any model. Throws Error for an image under 2 by 2 pixels, a non-finite pixel, sigma outside
/// [0, kMaxGaussianSigma] or c not finite.
Potential image_potential(const Eigen::MatrixXd& image, double sigma, double c = 1.0);

}  // namespace dnurbs
