#include "dnurbs/vision/t_snake.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

FreudenthalGrid grid_over_image(const Image& image, const TSnakeParameters& parameters) {
  // Alpha and beta are the second and fourth differences: largest eigenvalues 4 and 16.
  parameters.validate("T-snake", 4.0, 16.0);
  const double cell_size = parameters.cell_size;
  const int cells_x = static_cast<int>(std::floor((image.width() - 1) / cell_size));
  const int cells_y = static_cast<int>(std::floor((image.height() - 1) / cell_size));
  return {Eigen::Vector2d::Zero(), cell_size, cells_x, cells_y};
}

}  // namespace

TSnake::TSnake(const Image& image, ImageEdgePotential potential, const TSnakeParameters& parameters)
    : image_(image),
      potential_(std::move(potential)),
      parameters_(parameters),
      grid_(grid_over_image(image, parameters)) {
  const Image& samples = potential_.samples();
  if (image.width() != samples.width() || image.height() != samples.height()) {
    throw make_error("T-snake image is ", image.width(), " by ", image.height(),
                     ", its edge potential ", samples.width(), " by ", samples.height());
  }
  if (!image.values.allFinite()) {
    throw make_error("T-snake image has a pixel that is not finite");
  }
  inside_.assign(static_cast<std::size_t>(grid_.vertex_count()), 0);
}

double TSnake::intensity(const Eigen::Vector2d& point) const {
  const double x = std::clamp(point.x(), 0.0, image_.width() - 1.0);
  const double y = std::clamp(point.y(), 0.0, image_.height() - 1.0);
  const int i = std::min(static_cast<int>(x), image_.width() - 2);
  const int j = std::min(static_cast<int>(y), image_.height() - 2);
  const double s = x - i;
  const double t = y - j;
  return (1.0 - t) * ((1.0 - s) * image_(i, j) + s * image_(i + 1, j)) +
         t * ((1.0 - s) * image_(i, j + 1) + s * image_(i + 1, j + 1));
}

Eigen::MatrixX2d TSnake::outward_normals(const Contour& contour) {
  const Eigen::Index n = contour.rows();
  Eigen::MatrixX2d normals(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    // The central tangent turned clockwise: the right-hand side, outside for inside-on-the-left.
    const Eigen::RowVector2d tangent = contour.row((i + 1) % n) - contour.row((i + n - 1) % n);
    const double length = tangent.norm();
    normals.row(i) = Eigen::RowVector2d(tangent.y(), -tangent.x()) / std::max(length, 1e-300);
  }
  return normals;
}

Eigen::MatrixX2d TSnake::node_forces(const Contour& contour) const {
  const Eigen::Index n = contour.rows();
  const auto wrap = [n](Eigen::Index i) { return (i % n + n) % n; };
  // Tension and rigidity differences alpha_i, beta_i of the discrete snake (Terzopoulos, eqs.
  // 1.8-1.11 with unit spacing; McInerney & Terzopoulos 2000).
  Eigen::MatrixX2d alpha(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    alpha.row(i) = 2.0 * contour.row(i) - contour.row(wrap(i - 1)) - contour.row(wrap(i + 1));
  }
  const Eigen::MatrixX2d normals = outward_normals(contour);
  Eigen::MatrixX2d forces(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector2d beta =
        2.0 * alpha.row(i) - alpha.row(wrap(i - 1)) - alpha.row(wrap(i + 1));
    const Eigen::Vector2d x = contour.row(i).transpose();
    // Inflation rho_i = q F(I(x_i)) n_i and edge force f_i = -p grad P(x_i).
    const double switch_value =
        inflation_switch(intensity(x), parameters_.threshold, parameters_.inflation_band);
    const Eigen::RowVector2d rho = parameters_.inflation * switch_value * normals.row(i);
    const Eigen::RowVector2d edge = -parameters_.edge_weight * potential_.gradient(x).transpose();
    forces.row(i) = -parameters_.tension * alpha.row(i) - parameters_.rigidity * beta + rho + edge;
  }
  return forces;
}

bool TSnake::reparameterize() {
  const GridCrossings crossings = grid_crossings(grid_, contours_);
  std::vector<char> inside = inside_vertices(grid_, crossings);
  contours_ = boundary_contours(grid_, inside, crossings);
  const bool changed = inside != inside_;
  inside_ = std::move(inside);
  return changed;
}

void TSnake::add_contour(const Contour& contour) {
  if (contour.rows() < 3) {
    throw make_error("T-snake contour has ", contour.rows(), " nodes, needs at least 3");
  }
  if (!contour.allFinite()) {
    throw make_error("T-snake contour has a node that is not finite");
  }
  contours_.push_back(contour);
  reparameterize();
}

void TSnake::add_circle(const Eigen::Vector2d& center, double radius) {
  if (!center.allFinite() || !(std::isfinite(radius) && radius > 0.0)) {
    throw make_error("T-snake circle at (", center.x(), ", ", center.y(), ") of radius ", radius,
                     " is not finite with radius > 0");
  }
  constexpr int kNodes = 64;
  Contour circle(kNodes, 2);
  for (int k = 0; k < kNodes; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kNodes;
    circle.row(k) =
        (center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle))).transpose();
  }
  add_contour(circle);
}

void TSnake::remove_contour(int index) {
  if (index < 0 || index >= static_cast<int>(contours_.size())) {
    throw make_error("T-snake contour index ", index, " is not in [0, ", contours_.size(), ")");
  }
  contours_.erase(contours_.begin() + index);
  reparameterize();
}

bool TSnake::step() {
  const double scale = parameters_.time_step / parameters_.damping;
  const Eigen::RowVector2d low = grid_.origin().transpose();
  const Eigen::RowVector2d high =
      low + grid_.cell_size() * Eigen::RowVector2d(grid_.cells_x(), grid_.cells_y());
  for (Contour& contour : contours_) {
    contour += scale * node_forces(contour);
    // Nodes stay in the grid's box, whose border vertices are always outside.
    for (Eigen::Index i = 0; i < contour.rows(); ++i) {
      contour.row(i) = contour.row(i).cwiseMax(low).cwiseMin(high);
    }
  }
  ++steps_;
  if (steps_ % parameters_.steps_per_reparameterization != 0) {
    return false;
  }
  return reparameterize();
}

int TSnake::run(int max_steps, int stable_steps) {
  int stable = 0;
  int taken = 0;
  while (taken < max_steps && stable < stable_steps && !contours_.empty()) {
    stable = step() ? 0 : stable + 1;
    ++taken;
  }
  return taken;
}

double TSnake::enclosed_area() const {
  double area = 0.0;
  for (const Contour& contour : contours_) {
    area += signed_area(contour);
  }
  return area;
}

}  // namespace dnurbs
