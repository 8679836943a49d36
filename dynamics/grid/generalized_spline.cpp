#include "dnurbs/dynamics/grid/generalized_spline.h"

#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/core/kronecker.h"
#include "dnurbs/dynamics/core/node_interpolation.h"

namespace dnurbs {

namespace {

using RowNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// One direction of the domain: its node count and whether it closes on itself. A chain has a
// second direction of one node (the absent v), where only order 0 occurs.
struct Direction {
  int count = 1;
  bool closed = false;
};

// The difference of order a along one direction (the header's "Stencils", "Anchors" and
// "Quadrature" items): anchors, node offsets, coefficients, centres and end factors.
struct Stencil1d {
  int order = 0;
  int first = 0;  // first and last anchor
  int last = 0;
  std::vector<int> offsets;          // node = anchor + offset
  std::vector<double> coefficients;  // (-1)^(a-k) C(a, k) / h^a

  Stencil1d(const Direction& direction, int a, double h) : order(a) {
    first = direction.closed ? 0 : a / 2;
    last = direction.closed ? direction.count - 1 : direction.count - 1 - (a - a / 2);
    double binomial = 1.0;  // C(a, k)
    for (int k = 0; k <= a; ++k) {
      offsets.push_back(k - a / 2);
      coefficients.push_back(((a - k) % 2 == 0 ? binomial : -binomial) / std::pow(h, a));
      binomial = binomial * (a - k) / (k + 1);
    }
  }

  // c of the anchor: (a + 1)/2 at the ends of an open direction, a for a single anchor.
  double end_factor(const Direction& direction, int anchor) const {
    if (direction.closed || direction.count == 1) {
      return 1.0;
    }
    if (first == last) {
      return order;
    }
    return anchor == first || anchor == last ? 0.5 * (order + 1) : 1.0;
  }

  // The centre of the stencil anchored at `anchor`, in units of h (wrapped for closed).
  double centre(const Direction& direction, int anchor) const {
    double x = anchor + (order % 2 == 1 ? 0.5 : 0.0);
    if (direction.closed && x >= direction.count) {
      x -= direction.count;
    }
    return x;
  }
};

int node_index(const Direction& direction, int i) {
  return direction.closed ? ((i % direction.count) + direction.count) % direction.count : i;
}

double factorial(int m) {
  double result = 1.0;
  for (int k = 2; k <= m; ++k) {
    result *= k;
  }
  return result;
}

std::string term_name(const SplineTerm& term) {
  return "generalized spline weight w_(" + std::to_string(term.ju) + "," + std::to_string(term.jv) +
         ")";
}

// The terms of the material after the checks of GeneralizedSpline's constructor.
std::vector<SplineTerm> checked_terms(const GeneralizedSplineMaterial& material, int dimension,
                                      const std::array<Direction, 2>& directions, int nodes) {
  const int n = material.order;
  if (n < 1) {
    throw make_error("generalized spline order n = ", n, " is below 1");
  }
  for (int d = 0; d < dimension; ++d) {
    if (directions[static_cast<size_t>(d)].count < n + 1) {
      throw make_error("generalized spline of order n = ", n, " needs at least ", n + 1,
                       " nodes along ", d == 0 ? "u" : "v", ", not ",
                       directions[static_cast<size_t>(d)].count);
    }
  }
  std::vector<SplineTerm> terms = material.terms;
  if (terms.empty()) {
    for (int m = 1; m <= n; ++m) {
      for (int jv = 0; jv <= (dimension == 2 ? m : 0); ++jv) {
        SplineTerm term;
        term.ju = m - jv;
        term.jv = jv;
        terms.push_back(term);
      }
    }
  }
  std::set<std::pair<int, int>> seen;
  for (const SplineTerm& term : terms) {
    const std::string name = term_name(term);
    if (term.ju < 0 || term.jv < 0 || term.ju + term.jv < 1 || term.ju + term.jv > n) {
      throw make_error(name, " has |j| = ", term.ju + term.jv, " or a negative order, outside 1..",
                       n);
    }
    if (dimension == 1 && term.jv != 0) {
      throw make_error(name, " differentiates along v on a chain (p = 1)");
    }
    if (!seen.insert({term.ju, term.jv}).second) {
      throw make_error(name, " is listed twice");
    }
    if (term.node_weights.size() != 0) {
      if (term.node_weights.size() != nodes) {
        throw make_error(name, " has ", term.node_weights.size(), " node weights for ", nodes,
                         " nodes");
      }
      for (int k = 0; k < nodes; ++k) {
        if (!(term.node_weights[k] >= 0.0) || !std::isfinite(term.node_weights[k])) {
          throw make_error(name, " at node ", k, " is ", term.node_weights[k],
                           ", not a non-negative finite number");
        }
      }
    }
  }
  return terms;
}

// S_K = sum_j (m!/j!) h^p D_j^T W_j D_j = B^T B over the directions (u fastest in the node
// index), B the rows sqrt((m!/j!) h^p c_i w_j,i) D_j(i, :) of every term stacked.
struct SplineMatrices {
  SparseMatrix stiffness;
  SparseMatrix energy_factor;
};

SplineMatrices spline_matrices(const std::array<Direction, 2>& directions, int dimension, double h,
                               const GeneralizedSplineMaterial& material) {
  const int nu = directions[0].count;
  const int nodes = nu * directions[1].count;
  const std::vector<SplineTerm> terms = checked_terms(material, dimension, directions, nodes);
  const double measure = std::pow(h, dimension);
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Triplet<double>> factor_triplets;
  int rows = 0;
  std::vector<std::pair<int, double>> entries;
  for (const SplineTerm& term : terms) {
    const int m = term.ju + term.jv;
    // Terzopoulos 2003, eq 1.17: the multinomial m!/(j_1! j_2!) of the term
    const double multinomial = factorial(m) / (factorial(term.ju) * factorial(term.jv));
    const Stencil1d su(directions[0], term.ju, h);
    const Stencil1d sv(directions[1], term.jv, h);
    const std::string name = term_name(term);
    for (int av = sv.first; av <= sv.last; ++av) {
      for (int au = su.first; au <= su.last; ++au) {
        const int anchor = au + nu * av;
        const double w =
            term.node_weights.size() != 0
                ? term.node_weights[anchor]
                : term.weight.checked(
                      Eigen::Vector2d(su.centre(directions[0], au) * h,
                                      dimension == 2 ? sv.centre(directions[1], av) * h : 0.0),
                      name, true);
        const double factor = multinomial * measure * w * su.end_factor(directions[0], au) *
                              sv.end_factor(directions[1], av);
        if (factor == 0.0) {
          continue;
        }
        // Row `anchor` of D_j: the tensor product of the two 1-D differences
        entries.clear();
        for (size_t kv = 0; kv < sv.offsets.size(); ++kv) {
          const int node_v = node_index(directions[1], av + sv.offsets[kv]);
          for (size_t ku = 0; ku < su.offsets.size(); ++ku) {
            const int node_u = node_index(directions[0], au + su.offsets[ku]);
            entries.emplace_back(node_u + nu * node_v, su.coefficients[ku] * sv.coefficients[kv]);
          }
        }
        // factor D_j(anchor, :)^T D_j(anchor, :), each product formed alike for (a, b) and (b, a)
        const double root = std::sqrt(factor);
        for (const auto& [a, ca] : entries) {
          factor_triplets.emplace_back(rows, a, root * ca);
          for (const auto& [b, cb] : entries) {
            triplets.emplace_back(a, b, factor * (ca * cb));
          }
        }
        ++rows;
      }
    }
  }
  SplineMatrices result;
  result.stiffness.resize(nodes, nodes);
  result.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  result.stiffness.makeCompressed();
  result.energy_factor.resize(rows, nodes);
  result.energy_factor.setFromTriplets(factor_triplets.begin(), factor_triplets.end());
  return result;
}

std::array<Direction, 2> chain_directions(const NodeChain& chain) {
  return {Direction{chain.count(), chain.closed()}, Direction{1, false}};
}

std::array<Direction, 2> grid_directions(const Grid& grid) {
  return {Direction{grid.nu(), false}, Direction{grid.nv(), false}};
}

void check_densities(const GeneralizedSplineMaterial& material) {
  if (!(material.mass_density >= 0.0) || !std::isfinite(material.mass_density)) {
    throw make_error("generalized spline mass density mu = ", material.mass_density,
                     " is not non-negative and finite");
  }
  if (!(material.damping_density >= 0.0) || !std::isfinite(material.damping_density)) {
    throw make_error("generalized spline damping density gamma = ", material.damping_density,
                     " is not non-negative and finite");
  }
  if (material.mass_density == 0.0 && material.damping_density == 0.0) {
    throw make_error("generalized spline with mass density mu = 0 needs a damping density gamma > ",
                     "0 (the massless flow gamma u_t = -K u + f); gamma = 0");
  }
}

SparseMatrix diagonal(const Eigen::VectorXd& values) {
  SparseMatrix result(values.size(), values.size());
  if (values.isZero(0.0)) {
    return result;  // no entries: an absent mass or damping
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    triplets.emplace_back(i, i, values[i]);
  }
  result.setFromTriplets(triplets.begin(), triplets.end());
  return result;
}

}  // namespace

GeneralizedSplineMaterial membrane_material(int dimension, const MaterialFunction& tension) {
  if (dimension != 1 && dimension != 2) {
    throw make_error("membrane dimension p = ", dimension, " is not 1 or 2");
  }
  GeneralizedSplineMaterial material;
  material.order = 1;
  material.terms.push_back(SplineTerm{1, 0, tension, {}});
  if (dimension == 2) {
    material.terms.push_back(SplineTerm{0, 1, tension, {}});
  }
  return material;
}

GeneralizedSplineMaterial thin_plate_material(const MaterialFunction& w10,
                                              const MaterialFunction& w01,
                                              const MaterialFunction& w20,
                                              const MaterialFunction& w11,
                                              const MaterialFunction& w02) {
  // Terzopoulos 2003, eq 1.20: w10 |v_u|^2 + w01 |v_v|^2 + w20 |v_uu|^2 + 2 w11 |v_uv|^2 +
  // w02 |v_vv|^2, the factor 2 being eq 1.17's multinomial 2!/(1! 1!)
  GeneralizedSplineMaterial material;
  material.order = 2;
  material.terms = {SplineTerm{1, 0, w10, {}}, SplineTerm{0, 1, w01, {}}, SplineTerm{2, 0, w20, {}},
                    SplineTerm{1, 1, w11, {}}, SplineTerm{0, 2, w02, {}}};
  return material;
}

SparseMatrix generalized_spline_stiffness(const NodeChain& chain,
                                          const GeneralizedSplineMaterial& material) {
  return spline_matrices(chain_directions(chain), 1, chain.spacing(), material).stiffness;
}

SparseMatrix generalized_spline_stiffness(const Grid& grid,
                                          const GeneralizedSplineMaterial& material) {
  return spline_matrices(grid_directions(grid), 2, grid.spacing(), material).stiffness;
}

GeneralizedSpline::GeneralizedSpline(const NodeChain& chain, const NodePositions& initial,
                                     const GeneralizedSplineMaterial& material)
    : chain_(chain) {
  check_densities(material);
  const int n = chain.count();
  if (initial.rows() != n) {
    throw make_error("generalized spline initial positions have ", initial.rows(), " rows for ", n,
                     " nodes");
  }
  for (int i = 0; i < n; ++i) {
    if (!initial.row(i).allFinite()) {
      throw make_error("generalized spline initial position of node ", i, " is not finite");
    }
  }
  node_measure_ = Eigen::VectorXd::Constant(n, chain.spacing());
  if (!chain.closed()) {
    node_measure_[0] *= 0.5;  // the trapezoid rule's half cells at the ends
    node_measure_[n - 1] *= 0.5;
  }
  const SplineMatrices matrices =
      spline_matrices(chain_directions(chain), 1, chain.spacing(), material);
  build(initial, material, matrices.stiffness, matrices.energy_factor);
}

GeneralizedSpline::GeneralizedSpline(const Grid& grid, const NodePositions& initial,
                                     const GeneralizedSplineMaterial& material)
    : grid_(grid) {
  check_densities(material);
  check_grid_positions(grid, initial, "generalized spline initial positions");
  const double h = grid.spacing();
  node_measure_.resize(grid.node_count());
  for (int k = 0; k < grid.node_count(); ++k) {
    const auto [i, j] = grid.node(k);
    node_measure_[k] = h * h * (i == 0 || i == grid.nu() - 1 ? 0.5 : 1.0) *
                       (j == 0 || j == grid.nv() - 1 ? 0.5 : 1.0);
  }
  const SplineMatrices matrices = spline_matrices(grid_directions(grid), 2, h, material);
  build(initial, material, matrices.stiffness, matrices.energy_factor);
}

void GeneralizedSpline::build(const NodePositions& initial,
                              const GeneralizedSplineMaterial& material,
                              const SparseMatrix& stiffness, const SparseMatrix& energy_factor) {
  initial_ = initial;
  mass_density_ = material.mass_density;
  scalar_.stiffness = stiffness;
  energy_factor_ = energy_factor;
  scalar_.mass = diagonal(material.mass_density * node_measure_);
  scalar_.damping = diagonal(material.damping_density * node_measure_);
  matrices_.mass = kronecker_identity(scalar_.mass, 3);
  matrices_.damping = kronecker_identity(scalar_.damping, 3);
  matrices_.stiffness = kronecker_identity(scalar_.stiffness, 3);
}

NodePositions GeneralizedSpline::positions(ConstVectorRef q) const {
  if (q.size() != coordinate_count()) {
    throw make_error("generalized spline coordinates have ", q.size(), " entries, not ",
                     coordinate_count());
  }
  return Eigen::Map<const RowNodes>(q.data(), node_measure_.size(), 3);
}

Eigen::VectorXd GeneralizedSpline::initial_coordinates() const {
  Eigen::VectorXd q(coordinate_count());
  Eigen::Map<RowNodes>(q.data(), node_measure_.size(), 3) = initial_;
  return q;
}

namespace {

// The nodes and interpolation weights of the material point u.
std::vector<std::pair<int, double>> interpolation(const std::optional<NodeChain>& chain,
                                                  const std::optional<Grid>& grid,
                                                  const Eigen::Vector2d& u) {
  if (chain) {
    const auto weights = chain->linear_weights(u.x());
    return {weights.begin(), weights.end()};
  }
  const auto weights = grid->bilinear_weights(u);
  return {weights.begin(), weights.end()};
}

}  // namespace

Eigen::Vector3d GeneralizedSpline::position(ConstVectorRef q, const Eigen::Vector2d& u) const {
  return interpolate_nodes(q, interpolation(chain_, grid_, u));
}

SparseMatrix GeneralizedSpline::position_jacobian(ConstVectorRef /*q*/,
                                                  const Eigen::Vector2d& u) const {
  return node_interpolation_jacobian(interpolation(chain_, grid_, u), coordinate_count());
}

double GeneralizedSpline::potential_energy(ConstVectorRef q) const {
  // E = 1/2 |B X|^2 (X the #nodes by 3 positions): the differences are squared after they are
  // formed, not cancelled inside q^T K q
  return 0.5 * (energy_factor_ * positions(q)).squaredNorm();
}

void GeneralizedSpline::assemble_matrices(ConstVectorRef /*q*/, ModelMatrices& matrices) const {
  matrices = matrices_;
}

void GeneralizedSpline::add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                                              VectorRef force) const {
  MaterialSample sample;
  sample.mass_density = mass_density_;
  // The tangent along a direction: central differences, one-sided at an open end
  const auto tangent = [&](int previous, int next, int steps, double h) -> Eigen::Vector3d {
    return (q.segment<3>(3 * next) - q.segment<3>(3 * previous)) / (steps * h);
  };
  for (int k = 0; k < static_cast<int>(node_measure_.size()); ++k) {
    sample.position = q.segment<3>(3 * k);
    if (chain_) {
      const int next = chain_->neighbor(k, 1) >= 0 ? chain_->neighbor(k, 1) : k;
      const int previous = chain_->neighbor(k, -1) >= 0 ? chain_->neighbor(k, -1) : k;
      sample.parameter = Eigen::Vector2d(chain_->parameter(k), 0.0);
      sample.tangent_u =
          tangent(previous, next, next == k || previous == k ? 1 : 2, chain_->spacing());
    } else {
      const auto [i, j] = grid_->node(k);
      const int i0 = std::max(i - 1, 0);
      const int i1 = std::min(i + 1, grid_->nu() - 1);
      const int j0 = std::max(j - 1, 0);
      const int j1 = std::min(j + 1, grid_->nv() - 1);
      sample.parameter = grid_->parameter(k);
      sample.tangent_u =
          tangent(grid_->index(i0, j), grid_->index(i1, j), i1 - i0, grid_->spacing());
      sample.tangent_v =
          tangent(grid_->index(i, j0), grid_->index(i, j1), j1 - j0, grid_->spacing());
    }
    force.segment<3>(3 * k) += node_measure_[k] * density(sample);
  }
}

int GeneralizedSpline::control_point_offset(int i) const {
  if (i < 0 || i >= node_measure_.size()) {
    throw make_error("generalized spline node ", i, " is outside 0..", node_measure_.size() - 1);
  }
  return 3 * i;
}

ParameterDomain GeneralizedSpline::parameter_domain(ConstVectorRef /*q*/) const {
  if (grid_) {
    return grid_parameter_domain(*grid_);
  }
  ParameterDomain domain;
  domain.periodic_u = chain_->closed();
  return domain;
}

void GeneralizedSpline::fix_border() {
  if (!grid_) {
    throw make_error("a generalized spline on a chain has no border; fix its end nodes by index");
  }
  for (const int k : grid_->border_nodes()) {
    fix_point(k);
  }
}

TriangleMesh GeneralizedSpline::tessellate(ConstVectorRef q,
                                           const ModelTessellationSettings& settings,
                                           std::string name) const {
  if (grid_) {
    return grid_triangle_mesh(*grid_, positions(q), std::move(name));
  }
  return Model::tessellate(q, settings, std::move(name));
}

}  // namespace dnurbs
