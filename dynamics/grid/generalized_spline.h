#pragma once
// Controlled-continuity generalized splines of order n (Terzopoulos 2003, section 2.5): in a
// p-dimensional parametric domain
//
//   S_n(v) = 1/2 int sum_{m=1..n} sum_{|j|=m} (m!/(j_1! ... j_p!)) w_j(x) |d^m v / dx^j|^2 dx
//   (eq 1.17)
//
// with the Euler-Lagrange equation sum_m (-1)^m Delta_w^m v + grad P(v) = 0 (eq 1.18),
// Delta_w^m = sum_{|j|=m} (m!/j!) d^j (w_j d^j) (eq 1.19). n = 1 is the membrane, n = 2 with p = 2
// the thin plate under tension (eq 1.20), p = 1 with n = 2 the snake of eq 1.2.
//
// Discretization, on a NodeChain (p = 1, open or closed, spacing h) or a Grid (p = 2, open, spacing
// h), q = 3 coordinates (x, y, z) per node:
//
// * Stencils. Along one direction, the difference of order a anchored at node i uses the nodes
//   i - floor(a/2) + k, k = 0..a, with the coefficients (-1)^(a-k) C(a, k) / h^a (a = 1: the
//   forward difference u_{i+1} - u_i; a = 2: the central u_{i+1} - 2 u_i + u_{i-1}; a = 3:
//   u_{i+2} - 3 u_{i+1} + 3 u_i - u_{i-1}). Its centre is at (i + 1/2) h for odd a and at i h for
//   even a, where it approximates d^a v / dx^a to O(h^2). On a grid D_j is the product of the
//   difference of order j_1 along u and of order j_2 along v, anchored at node (i, k).
// * Anchors. Closed chains: every node, indices modulo N. Open chains and grids: the nodes whose
//   stencil lies inside, i = floor(a/2) .. N-1-ceil(a/2) along each direction (no differences reach
//   past an end).
// * Weights. w_j is sampled once per anchor: SplineTerm::node_weights[k] is the weight of the
//   stencil anchored at node k (entries of nodes that anchor no stencil are checked, then unused),
//   or else SplineTerm::weight is evaluated at the stencil's centre (s for chains, (u, v) for
//   grids; the centres of closed chains are wrapped into [0, 1)). Sampling at the centres keeps the
//   Euler-Lagrange operator second order for varying weights; a weight sampled at the anchor node
//   instead makes odd orders first order.
// * Quadrature. Each anchor carries the measure c_i h^p (c a product over the directions): c = 1
//   inside, and at the first and last anchor along an open direction of order a, c = (a + 1)/2
//   (a single anchor: c = a). Along an open direction the centres, each standing for a cell of
//   width h, leave a strip of (a - 1) h / 2 uncovered at each end (a = 0 covers h/2 too much: the
//   trapezoid rule); the end factor gives that strip to the end anchor, so the sum approximates the
//   integral to O(h^2) for smooth v, open or closed.
//
// The discrete energy is exactly
//
//   E(q) = 1/2 sum_{m=1..n} sum_{|j|=m} (m!/j!) sum_{anchors i} c_i h^p w_j,i |(D_j u)_i|^2
//        = 1/2 q^T K q,     K = sum_j (m!/j!) h^p D_j^T W_j D_j (x) I_3,
//
// W_j = diag(c_i w_j,i), D_j of #anchors by #nodes. (K u)_i / (node measure) approximates
// sum_m (-1)^m Delta_w^m v at interior nodes to O(h^2) (its D_j^T is the adjoint stencil, centred
// on the node). M = mu diag(node measure) (x) I_3 and D = gamma diag(node measure) (x) I_3, with
// the node measure h^p times the trapezoid factor 1/2 per open end the node lies on: lumped,
// diagonal. Distributed forces give node i (node measure) f(x_i).
//
// The snake (dynamics/grid/snake.h, eqs 1.8-1.11) is p = 1, n = 2 with w1 = w_(1), w2 = w_(2) per
// node and M = mu I: for a closed chain K_snake = K / h and M_snake = M / h (the stencils and
// anchors are the snake's; h is the quadrature measure, which the snake leaves out of both; the
// entries agree to rounding, their sums being formed in another order). For an open chain the two
// end anchors of the second difference (nodes 1 and N-2) carry c = 3/2 here and 1 in the snake: a
// snake whose w2 at those nodes is multiplied by 3/2 has K / h again, and without that only the
// rows 4..N-5 agree. A weight function sampled at the centres is the snake's w1_i = w((i + 1/2) h),
// w2_i = w(i h).
//
// The massless limit (section 2.6): mu = 0 with gamma > 0 is the first-order flow
// gamma u_t = -K u + f; the implicit-euler integrator steps it as backward Euler
// (dynamics/integrators/integrator.h), the second-order schemes refuse it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/material_function.h"
#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/surface/grid.h"
#include "dnurbs/surface/node_chain.h"

namespace dnurbs {

/// One term j of eq 1.17: the derivative d^(j_u + j_v) / du^j_u dv^j_v with its weight w_j. Chains
/// use j_u only (j_v = 0).
struct SplineTerm {
  int ju = 1;  ///< j_1, the order along u (s for chains)
  int jv = 0;  ///< j_2, the order along v (0 for chains)
  /// w_j at each stencil's centre (>= 0, finite), constant 1 by default.
  MaterialFunction weight = 1.0;
  /// If non-empty: #nodes weights (>= 0, finite), entry k for the stencil anchored at node k;
  /// it overrides `weight`.
  Eigen::VectorXd node_weights;
};

struct GeneralizedSplineMaterial {
  int order = 1;                 ///< n >= 1: the highest derivative order of eq 1.17
  double mass_density = 1.0;     ///< mu >= 0; 0 is the massless first-order flow (section 2.6)
  double damping_density = 0.0;  ///< gamma >= 0, > 0 when mu = 0
  /// The terms j with 1 <= |j| <= n, each at most once; a j not listed has w_j = 0. Empty: every
  /// j with 1 <= |j| <= n at weight 1.
  std::vector<SplineTerm> terms;
};

/// The membrane (n = 1, eq 1.17): w_j = tension for every |j| = 1 in `dimension` (1 or 2)
/// directions. Throws Error naming the dimension otherwise.
GeneralizedSplineMaterial membrane_material(int dimension, const MaterialFunction& tension);

/// The thin plate under tension (n = 2, p = 2, eq 1.20): w10, w01 (tension), w20, w11, w02
/// (rigidity; the energy weighs |v_uv|^2 by 2 w11, the multinomial m!/j! of eq 1.17).
GeneralizedSplineMaterial thin_plate_material(const MaterialFunction& w10,
                                              const MaterialFunction& w01,
                                              const MaterialFunction& w20,
                                              const MaterialFunction& w11,
                                              const MaterialFunction& w02);

/// The scalar stiffness S_K (#nodes by #nodes) of eq 1.17 as stated in this header's comment
/// (K = S_K (x) I_3), on a chain (p = 1) or a grid (p = 2). Throws Error for the material errors
/// listed at GeneralizedSpline's constructor.
SparseMatrix generalized_spline_stiffness(const NodeChain& chain,
                                          const GeneralizedSplineMaterial& material);
SparseMatrix generalized_spline_stiffness(const Grid& grid,
                                          const GeneralizedSplineMaterial& material);

/// A generalized spline as a Model. q = [u_0, u_1, ...] (3 per node, node order of the chain or
/// grid); material points interpolate the nodes linearly (chains, s in [0, 1]) or bilinearly
/// (grids, the grid's parameter rectangle). Matrices are constant and S (x) I_3.
class GeneralizedSpline : public Model {
 public:
  /// `initial` is #nodes by 3. Throws Error naming the value for: order n < 1; a term with
  /// |j| outside 1..n, a negative order, j_v != 0 on a chain, or a j listed twice; a negative or
  /// non-finite weight (naming the term and the node or centre); node_weights of a size other
  /// than #nodes; fewer than n + 1 nodes along a direction; a non-finite or mis-sized initial
  /// position; mu or gamma negative or not finite; mu = 0 with gamma = 0.
  GeneralizedSpline(const NodeChain& chain, const NodePositions& initial,
                    const GeneralizedSplineMaterial& material);
  GeneralizedSpline(const Grid& grid, const NodePositions& initial,
                    const GeneralizedSplineMaterial& material);

  std::unique_ptr<Model> clone() const override {
    return std::make_unique<GeneralizedSpline>(*this);
  }

  /// The chain (p = 1) or the grid (p = 2); the other is empty.
  const std::optional<NodeChain>& chain() const { return chain_; }
  const std::optional<Grid>& grid() const { return grid_; }
  /// The measure of each node (#nodes): h^p times 1/2 per open end it lies on.
  const Eigen::VectorXd& node_measure() const { return node_measure_; }
  /// The scalar matrices (#nodes by #nodes); mass has no entries when mu = 0.
  const ModelMatrices& scalar() const { return scalar_; }
  NodePositions positions(ConstVectorRef q) const;

  int coordinate_count() const override { return 3 * static_cast<int>(node_measure_.size()); }
  Eigen::VectorXd initial_coordinates() const override;
  int parametric_dimension() const override { return chain_ ? 1 : 2; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  bool matrices_are_constant() const override { return true; }
  const ModelMatrices* constant_matrices() const override { return &matrices_; }
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  /// The discrete S_n of the header comment, 1/2 |B X|^2 with X the #nodes by 3 positions and B
  /// the rows sqrt((m!/j!) h^p c_i w_j,i) D_j(i, :) of every term (S_K = B^T B): 1/2 q^T K q
  /// without its cancellation (rounding eps E instead of eps |q|^2 |K|, which grows as h^-2n).
  double potential_energy(ConstVectorRef q) const override;
  int kronecker_block_size() const override { return 3; }
  const ModelMatrices* scalar_matrices() const override { return &scalar_; }
  /// Node i receives node_measure()[i] f(sample at node i) (tangents by central differences,
  /// one-sided at open ends).
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  int control_point_offset(int i) const override;
  /// Chains: s in [0, 1], periodic when closed; grids: the grid's parameter rectangle.
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// Grids: fixes every border node. Chains: throws Error (use fix_point on the ends).
  void fix_border() override;
  /// Grids: the node mesh (grid_triangle_mesh); chains: the default tessellation.
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                          std::string name) const override;

 private:
  void build(const NodePositions& initial, const GeneralizedSplineMaterial& material,
             const SparseMatrix& stiffness, const SparseMatrix& energy_factor);

  std::optional<NodeChain> chain_;
  std::optional<Grid> grid_;
  NodePositions initial_;
  Eigen::VectorXd node_measure_;
  double mass_density_ = 1.0;
  ModelMatrices scalar_;
  ModelMatrices matrices_;
  SparseMatrix energy_factor_;  ///< B (#difference rows by #nodes), S_K = B^T B
};

}  // namespace dnurbs
