#pragma once
// Topology-adaptive snakes (T-snakes) (McInerney & Terzopoulos, T-snakes: Topology adaptive
// snakes, Medical Image Analysis 4(2) 2000; Topologically adaptable snakes, ICCV 1995;
// Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations,
// section 3.1): closed snakes of nodes and elements driven by tension, rigidity, an inflation
// force switched by the image intensity and the edge force -grad P, reparameterized on a
// Coxeter-Freudenthal ACID after every M deformation steps so that they merge, split, appear
// and vanish as the image demands.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/vision/affine_cell_decomposition.h"
#include "dnurbs/vision/contour.h"
#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/freudenthal_grid.h"
#include "dnurbs/vision/image.h"
#include "dnurbs/vision/topology_adaptive_parameters.h"

namespace dnurbs {

/// The parameters of T-snakes (pixel units; TopologyAdaptiveParameters lists them).
///
/// The explicit deformation step of every node (McInerney & Terzopoulos 2000, the
/// discrete snake of Terzopoulos, eqs. 1.2-1.5 with mu = 0) is
///   x_i <- x_i + (time_step / damping) (-tension alpha_i - rigidity beta_i + rho_i + f_i)
/// with alpha_i = 2 x_i - x_{i-1} - x_{i+1}, beta_i = 2 alpha_i - alpha_{i-1} - alpha_{i+1},
/// the inflation rho_i = inflation F(I(x_i)) n_i along the outward unit normal n_i, and the edge
/// force f_i = -edge_weight grad P(x_i); F is inflation_switch and I the image bilinearly
/// interpolated. The defaults are TopologyAdaptiveParameters'.
struct TSnakeParameters : TopologyAdaptiveParameters {};

/// A set of T-snakes on one image.
///
/// The ACID grid covers the image: cells of side cell_size from (0, 0), floor((width - 1) /
/// cell_size) by floor((height - 1) / cell_size) cells. The snakes are the contours of the region
/// of inside grid vertices: outer boundaries counter-clockwise, holes clockwise in the (x, y)
/// frame (x along image columns, y along rows).
class TSnake {
 public:
  /// Throws Error as TopologyAdaptiveParameters::validate (the largest eigenvalues of alpha and
  /// beta are 4 and 16), for an image whose size differs from the potential's, a pixel that is
  /// not finite, or a grid with fewer than 2 cells per side.
  TSnake(const Image& image, ImageEdgePotential potential, const TSnakeParameters& parameters);

  /// Creates a snake from a closed polygon (#N by 2, N >= 3): the region it winds around
  /// positively joins the inside region (union, so a snake overlapping another merges with it).
  /// Throws Error for fewer than 3 nodes or a node that is not finite.
  void add_contour(const Contour& contour);
  /// Creates a circular snake (a 64-gon) of `radius` about `center`.
  void add_circle(const Eigen::Vector2d& center, double radius);
  /// Removes contour `index` and rebuilds the region from the others: removing an outer boundary
  /// destroys that snake (with its holes), removing a hole fills it. Throws Error for a bad index.
  void remove_contour(int index);

  /// One deformation step of every node, followed by the two-phase reparameterization when the
  /// step count reaches a multiple of M. Returns true if the set of inside grid vertices changed.
  bool step();
  /// Steps until the inside grid vertices have not changed for `stable_steps` consecutive steps
  /// or `max_steps` steps are taken; returns the number of steps taken.
  int run(int max_steps, int stable_steps = 40);

  /// The bracketed force sum of the deformation step for one contour (#N by 2): -a alpha_i -
  /// b beta_i + rho_i + f_i.
  Eigen::MatrixX2d node_forces(const Contour& contour) const;
  /// The outward unit normals of a contour oriented with its inside on the left (#N by 2).
  static Eigen::MatrixX2d outward_normals(const Contour& contour);
  /// The image intensity at a point, bilinear between pixels (clamped to the image).
  double intensity(const Eigen::Vector2d& point) const;

  const std::vector<Contour>& contours() const { return contours_; }
  /// vertex_count flags of the grid, 1 for inside.
  const std::vector<char>& inside() const { return inside_; }
  const FreudenthalGrid& grid() const { return grid_; }
  int steps_taken() const { return steps_; }
  /// The area of the inside region: the sum of the contours' signed areas.
  double enclosed_area() const;

 private:
  /// Phases I and II on the current (deformed) contours; returns true if inside_ changed.
  bool reparameterize();

  Image image_;
  ImageEdgePotential potential_;
  TSnakeParameters parameters_;
  FreudenthalGrid grid_;
  std::vector<Contour> contours_;
  std::vector<char> inside_;
  int steps_ = 0;
};

}  // namespace dnurbs
