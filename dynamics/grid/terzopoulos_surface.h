#pragma once
// The grid-based Terzopoulos elastic surface (Wu & de Melo, eqs 16-26): nodes r_ij of a regular
// (u, v) grid are the coordinates, mass mu h^2 and damping gamma h^2 per node (M, D diagonal),
// and the internal force comes from the metric tensor G and the curvature tensor B,
//
//   energy (eq 18)   E = integral sum_ij eta_ij (G_ij - G0_ij)^2 + xi_ij (B_ij - B0_ij)^2
//   force  (eq 19)   e = sum_ij -d/da_i (alpha_ij dr/da_j) + d^2/da_i da_j (beta_ij n)
//                    alpha_ij = eta_ij (G_ij - G0_ij),  beta_ij = xi_ij (B_ij - B0_ij)  (eq 20)
//
// discretized with the standard differences of Terzopoulos et al. (surface/grid_difference_
// operators.h): forward differences D+, their adjoints D- = -(D+)^T, so that the node force is
//
//   f_int = -h^2 K(r) r,   K(r) = sum_ij (D+_i)^T alpha_ij D+_j + (bending part),
//
// with alpha_ij, beta_ij and the normal coefficients frozen at the state K is built at. Two
// bending parts (selectable):
//   classic      n ~ r_ij (eq 21):  sum_ij (D+_ij)^T beta_ij D+_ij                (symmetric)
//   christoffel  eq 22 discretized as in Wu & de Melo, section 4,
//                  D-_ij(beta_ij) n + sum_k D-_j(beta_ij) d_ki D+_k r
//                                   + D-_i(beta_ij sum_k d_kj D+_k r)
//                with n = s_ij [D+_ij r - Gamma^1_ij r_1 - Gamma^2_ij r_2] (eqs 23-26), s = 1/B
//                if |B| > delta, +1 if 0 <= B <= delta, -1 if -delta < B < 0; Gamma (eq 15),
//                d (Weingarten, eq 8) and B (eq 6) from the state K is built at. Where D+_ij r
//                is not computable the Gamma terms are dropped too (Wu & de Melo, section 4). The
//                r_1, r_2 in n are the central tangents Gamma is computed with (the seed writes
//                D+_k), so that at the coefficients' own state n is exactly the unit normal
//                where |B| > delta. K is not symmetric.
//   christoffel_unnormalized
//                the first attempt of Wu & de Melo, section 4 (their figure 6): the same
//                operator with |B_ij| = 1 at every node, s = +1 if B >= 0, -1 if B < 0 (eqs
//                25-26 everywhere; delta is not used), so that at the coefficients' own state n
//                is |B_ij| times the unit normal. The seed reports a tangential, "rotating"
//                motion with it after a large reaction force (figure 6) and normalizes (eqs
//                24-26, figure 8) to avoid it. The normal used for the classic surface's
//                approximate_normals is the normalized one.
//
// Plastic behaviour (the inelastic surfaces of Terzopoulos & Fleischer, SIGGRAPH 1988, whose
// reference tensors G0, B0 yield): with set_plastic_flow the rest positions r0 flow towards the
// node positions by the rule of dynamics/core/plastic_flow.h after every committed step, and G0
// and B0 are those of the moved rest shape, so a push leaves a dent.
//
// Stepping: through the common integrators (the Model contract; K(q) symmetrised is the
// "stiffness", the exact force is -h^2 K(q) q evaluated at the step's state) or as in the seed
// with the matrix from the current tensors (dynamics/integrators/semi_implicit_step.h).

#include <array>
#include <memory>
#include <optional>

#include <string>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/model.h"
#include "dnurbs/dynamics/core/plastic_flow.h"
#include "dnurbs/surface/grid.h"
#include "dnurbs/surface/grid_difference_operators.h"

namespace dnurbs {

/// How the normal in d^2(beta_ij n)/da_i da_j is approximated.
enum class NormalApproximation {
  kClassic,      ///< second derivatives r_ij (Wu & de Melo, eq. 21)
  kChristoffel,  ///< Gauss formula with the previous state's Christoffel symbols (eqs 22-26)
  /// eq 23 with |B_ij| = 1: not normalized, n has length |B_ij| (Wu & de Melo, figure 6)
  kChristoffelUnnormalized,
};

/// The name of a normal approximation in scene files and Python: "classic", "christoffel" or
/// "christoffel_unnormalized".
const char* to_string(NormalApproximation normal);
/// The approximation named `name` (as to_string); throws Error naming it and the choices.
NormalApproximation parse_normal_approximation(const std::string& name);

/// Uniform material of a Terzopoulos surface (per-node weights: set_node_elasticity).
struct TerzopoulosMaterial {
  double mass_density = 1.0;     ///< mu (> 0), mass mu h^2 per node
  double damping_density = 0.0;  ///< gamma (>= 0), damping gamma h^2 per node
  Eigen::Matrix2d eta =
      Eigen::Matrix2d::Zero();  ///< resistance to metric variation (>= 0, symmetric)
  Eigen::Matrix2d xi = Eigen::Matrix2d::Zero();  ///< resistance to curving (>= 0, symmetric)
};

struct TerzopoulosSettings {
  NormalApproximation normal = NormalApproximation::kClassic;
  /// Threshold of eqs 24-26 (> 0); Wu & de Melo: 0.5 suits grids whose cells are almost planar.
  /// Checked always, used by kChristoffel only.
  double delta = 0.5;
};

/// Metric and curvature tensors at every node: #nodes by 3 with columns (11, 12, 22).
/// metric: G_ij = D+_i r . D+_j r (zero where a forward difference is not computable);
/// curvature: B_ij = n . D+_ij r with n the unit normal of the central tangents (eq 6).
struct SurfaceTensors {
  Eigen::MatrixX3d metric;
  Eigen::MatrixX3d curvature;
};

/// The Terzopoulos surface as a Model. Coordinates q = [r_0, r_1, ...] (3 per node, node order
/// of Grid: k = i + nu j). Material points are grid parameters u = (i h, j h); x(u) interpolates
/// the nodes bilinearly.
class TerzopoulosSurface : public Model {
 public:
  /// `rest` (#nodes by 3) is the rest shape r0 (G0, B0) and the initial shape. Throws Error
  /// naming the value for a grid under 3 by 3 nodes, a non-finite rest position, mu <= 0,
  /// gamma < 0, a negative, non-finite or non-symmetric eta or xi, or delta <= 0.
  TerzopoulosSurface(const Grid& grid, const NodePositions& rest,
                     const TerzopoulosMaterial& material = {},
                     const TerzopoulosSettings& settings = {});

  std::unique_ptr<Model> clone() const override {
    return std::make_unique<TerzopoulosSurface>(*this);
  }

  // Set-up ----------------------------------------------------------------------------------
  /// Per-node elasticity weights eta_ij and xi_ij (same checks as the material).
  void set_node_elasticity(int node, const Eigen::Matrix2d& eta, const Eigen::Matrix2d& xi);
  /// The initial shape (default: the rest shape), #nodes by 3, finite.
  void set_initial_positions(const NodePositions& positions);
  /// Fixes every border node (a fixed node never moves; single nodes: Model::fix_point).
  void fix_border() override;

  const Grid& grid() const { return grid_; }
  const TerzopoulosSettings& settings() const { return settings_; }
  const TerzopoulosMaterial& material() const { return material_; }
  /// The rest shape r0 (#nodes by 3): the constructor's, moved by plastic flow.
  const NodePositions& rest_positions() const { return rest_; }
  /// Makes the rest shape yield by `flow` (checked) after every committed step (header
  /// comment), or stop yielding (nullopt; the rest stays where it is).
  void set_plastic_flow(const std::optional<PlasticFlow>& flow);
  const std::optional<PlasticFlow>& plastic_flow() const { return plastic_flow_; }
  /// The node positions of q (#nodes by 3).
  NodePositions positions(ConstVectorRef q) const;
  SurfaceTensors tensors(ConstVectorRef q) const;

  /// K(q) of the header comment (#nodes by #nodes, scaled by the node area h^2): the force at
  /// coordinates r with coefficients frozen at q is -(K(q) (x) I_3) r. Not symmetric for the
  /// christoffel approximation.
  SparseMatrix linearized_stiffness(ConstVectorRef q) const;

  /// The normal estimates of Wu & de Melo, eqs. 24-26 at coordinates q with the coefficients (B,
  /// Christoffel symbols) of the state `previous`, for the pairs 11, 12, 22 (each #nodes by 3).
  /// Where |B_ij| > delta and q = previous this is the unit normal (eq 23); below delta it is
  /// +-B_ij n (eqs 25-26). With kChristoffelUnnormalized it is |B_ij| n at every node.
  std::array<NodePositions, 3> approximate_normals(ConstVectorRef previous, ConstVectorRef q) const;

  // Model -----------------------------------------------------------------------------------
  int coordinate_count() const override { return 3 * grid_.node_count(); }
  Eigen::VectorXd initial_coordinates() const override;
  int parametric_dimension() const override { return 2; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  SparseMatrix position_jacobian(ConstVectorRef q, const Eigen::Vector2d& u) const override;
  bool matrices_are_constant() const override { return false; }
  /// M = mu h^2 I, D = gamma h^2 I, K = the symmetric part of linearized_stiffness(q) (x) I_3.
  void assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const override;
  /// f_int = -(linearized_stiffness(q) (x) I_3) q.
  void add_internal_force(ConstVectorRef q, VectorRef force) const override;
  /// E = (h^2 / 4) sum_nodes sum_ij eta_ij (G_ij - G0_ij)^2 + xi_ij (B_ij - B0_ij)^2 (eq 18,
  /// i, j over 1..2, so the 12 terms count twice). f_int = -dE/dq exactly when xi = 0; the
  /// bending force is Terzopoulos' approximation and not the gradient of this term.
  double potential_energy(ConstVectorRef q) const override;
  /// sum over nodes of h^2 f(sample at the node) (the node-area rule that makes gravity mu g
  /// consistent with M).
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override;
  /// Node i's coordinates start at 3 i (forces.h control_point_force acts on nodes).
  int control_point_offset(int i) const override;
  /// The grid's [0, (nu - 1) h] x [0, (nv - 1) h].
  ParameterDomain parameter_domain(ConstVectorRef q) const override;
  /// The node grid at q (its shape is that mesh); the segments are ignored.
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& settings,
                          std::string name) const override;
  /// Node blocks of 3: the semi-implicit step solves one node matrix for x, y and z.
  int semi_implicit_block_size() const override { return 3; }
  /// The semi-implicit matrices of Wu & de Melo (the grid Terzopoulos surface) from the current
  /// tensors: M = mu h^2 I, D = gamma h^2 I and K = linearized_stiffness(q) (nodes by nodes when
  /// `scalar`, else (x) I_3).
  void semi_implicit_matrices(ConstVectorRef q, bool scalar,
                              ModelMatrices& matrices) const override;
  /// With plastic flow: the rule on every node, then G0 and B0 of the moved rest shape; returns
  /// the nodes that yielded.
  int flow_rest_shape(ConstVectorRef q, double dt) override;
  /// The rest positions (3 per node, the order of q) with plastic flow, empty without.
  Eigen::VectorXd flowing_rest_coordinates() const override;
  void restore_flowing_rest_coordinates(ConstVectorRef rest) override;

 private:
  struct Geometry;
  /// The normal operators of eqs 24-26 (#nodes by #nodes, for the pairs 11, 12, 22) and the
  /// Weingarten coefficients weingarten[k][i] = d_ki (eq 8) of one state.
  struct ChristoffelCoefficients {
    std::array<SparseMatrix, 3> normal;
    std::array<std::array<Eigen::VectorXd, 2>, 2> weingarten;
  };
  Geometry geometry(const Eigen::Ref<const NodePositions>& r) const;
  ChristoffelCoefficients christoffel_coefficients(const Geometry& g) const;
  void check_node(int node) const;
  /// r0 = rest, with G0 and B0 of it.
  void set_rest(const NodePositions& rest);

  Grid grid_;
  TerzopoulosMaterial material_;
  TerzopoulosSettings settings_;
  GridDifferenceOperators operators_;
  NodePositions rest_;
  NodePositions initial_;
  Eigen::MatrixX3d eta_;  ///< per node (11, 12, 22)
  Eigen::MatrixX3d xi_;
  Eigen::MatrixX3d rest_metric_;
  Eigen::MatrixX3d rest_curvature_;
  std::optional<PlasticFlow> plastic_flow_;
};

}  // namespace dnurbs
