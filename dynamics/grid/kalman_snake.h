#pragma once
// Kalman snakes (Terzopoulos & Szeliski, "Tracking with Kalman snakes", Active Vision, MIT Press
// 1992; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations,
// 2003, section 2.4): a closed snake whose internal energy is a Gibbs prior and whose equations of
// motion (eq 1.12, mu u'' + gamma u' + K (u - u_rest) = f) are the system model of a Kalman
// filter; linear measurements with Gaussian noise are the sensor model (eq 1.16). The filter
// tracks a contour through a sequence of images.
//
// System model: the semi-implicit step of eq 1.13 with the velocity stored as the backward
// difference v = (u(t) - u(t - dt)) / dt,
//   B u(t + dt) = c1 u(t) + c2 v(t) + K u_rest + mu a,   v(t + dt) = (u(t + dt) - u(t)) / dt,
//   B = c1 I + K,  c1 = mu/dt^2 + gamma/(2 dt),  c2 = mu/dt - gamma/2,
// that is x_{k+1} = A x_k + b + G a_k with the process noise a_k (an acceleration, white,
// constant over a step, N(0, acceleration_variance) in every coordinate):
//   A = [c1 B^-1, c2 B^-1; (c1 B^-1 - I)/dt, c2 B^-1/dt],  b = [B^-1 K u_rest; B^-1 K u_rest/dt],
//   G = [mu B^-1; mu B^-1/dt],  Q = acceleration_variance G G^T.
// K is the closed snake's stiffness of eqs 1.8-1.11 with constant w1, w2 (h = 1/N), the
// Snake's (dynamics/grid/snake.h): its rows sum to zero, so a translation of the whole contour
// is in K's null space. The prior constrains the shape relative to u_rest, not where it is: the
// rest shape may sit anywhere in the image, and a contour translating at constant velocity is an
// exact solution of the undamped model.
//
// Structure: the stiffness of the 2-D snake is S (x) I_2 (S the N by N scalar matrix), so with
// the same noise in x and y the x and y filters share A, Q and, for full-position measurements
// (H = [I, 0] per axis), the gain and covariance: the covariance is I_2 (x) P_s with P_s of size
// 2N and predict/update cost one 2N filter. A measurement along a normal n_i (H row n_i^T on node
// i's position) couples the axes; from the first one on the filter keeps the full dense 4N by 4N
// covariance (predicted block by block, since A is block diagonal over the axes). A is dense
// (B^-1 couples every node), H sparse (two non-zeros per normal measurement): H P and H P H^T
// are sparse-by-dense products.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "dnurbs/vision/contour.h"
#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/image.h"

namespace dnurbs {

/// The system model and prior of a Kalman snake (pixel and frame units).
struct KalmanSnakeParameters {
  double mass = 1.0;                       ///< mu (> 0) per node
  double damping = 0.0;                    ///< gamma (>= 0) per node
  double tension = 0.0;                    ///< w1 (>= 0), constant along the snake
  double rigidity = 0.0;                   ///< w2 (>= 0), constant along the snake
  double time_step = 1.0;                  ///< dt (> 0) between frames
  double acceleration_variance = 1.0;      ///< variance of a_k per coordinate (> 0)
  double initial_position_variance = 1.0;  ///< prior variance of every position coordinate (> 0)
  double initial_velocity_variance = 1.0;  ///< prior variance of every velocity coordinate (> 0)
};

/// One scalar measurement of node `node`'s position along the unit vector `normal`:
/// z = normal^T u_node + noise of variance `variance`.
struct NormalMeasurement {
  int node = 0;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double position = 0.0;  ///< z (pixels)
  double variance = 1.0;  ///< r (> 0, pixels^2)
};

/// How measurements are found in an image: along each predicted node's normal, within
/// [-half_window, half_window] pixels sampled every sample_step, the strongest edge of
/// P = -|grad(G_sigma * I)| (edge_potential.h, c = 1), refined by a parabola through the
/// strongest sample and its neighbours. A node whose strongest sample is at the window's end,
/// below min_edge_strength or outside the image finds no edge and is not measured.
struct EdgeSearchParameters {
  int width = 0;                    ///< the frames' width (pixels); every frame must have it
  int height = 0;                   ///< the frames' height (pixels)
  double sigma = 1.5;               ///< of the Gaussian G_sigma (pixels)
  double half_window = 6.0;         ///< (> 0, pixels)
  double sample_step = 0.25;        ///< (> 0, <= half_window, pixels)
  double min_edge_strength = 0.02;  ///< smallest |grad(G_sigma * I)| taken as an edge (>= 0)
  double variance = 0.25;           ///< r of every edge measurement (> 0, pixels^2)
};

/// A closed snake of N >= 3 nodes in the image plane tracked by a Kalman filter.
///
/// State x (4N): axis-major, [u_x (N), v_x (N), u_y (N), v_y (N)] with u the node positions and v
/// their velocities. Contours are #N by 2 (Contour, contour.h).
class KalmanSnake {
 public:
  /// `rest_shape`, `initial_positions`, `initial_velocities`: #N by 2. The prior covariance is
  /// diagonal (initial_position_variance, initial_velocity_variance). Throws Error naming the
  /// value for N < 3, mismatched sizes, a non-finite position or velocity, or a parameter out of
  /// its range.
  KalmanSnake(const Contour& rest_shape, const Contour& initial_positions,
              const Eigen::MatrixX2d& initial_velocities, const KalmanSnakeParameters& parameters);

  /// The prediction x <- A x + b, P <- A P A^T + Q.
  void predict();
  /// The update with every node's position measured (#N by 2), each coordinate with noise of
  /// `variance` (R = variance I): H = [I, 0] per axis, the shared per-axis filter while the
  /// covariance is separable. Throws Error for a wrong size, a non-finite entry or variance <= 0.
  void update(const Contour& measured_positions, double variance);
  /// The update with scalar measurements along normals (R diagonal); couples the axes. Throws
  /// Error for a node out of range, a normal that is not finite or not of unit length (1e-9),
  /// a non-finite position or variance <= 0.
  void update(const std::vector<NormalMeasurement>& measurements);
  /// One frame: predict, search the frame for edges (edge_measurements) about the predicted
  /// nodes and update with them. Returns the number of nodes that found an edge. Throws Error
  /// for a frame whose size is not search.width by search.height, or bad search parameters.
  int track(const Image& frame, const EdgeSearchParameters& search);

  int node_count() const { return static_cast<int>(rest_shape_.rows()); }
  /// The filtered (or predicted, after predict()) node positions, #N by 2.
  Contour positions() const;
  /// The node velocities, #N by 2.
  Eigen::MatrixX2d velocities() const;
  /// The 4N by 4N covariance of the state, in the state's order.
  Eigen::MatrixXd covariance() const;
  /// The 2 by 2 covariance of node i's position (x, y): the uncertainty of the fitted shape.
  Eigen::Matrix2d node_covariance(int i) const;
  /// True while the covariance is I_2 (x) P_s (no normal measurement yet).
  bool axes_separable() const { return separable_; }

  /// The scalar stiffness S (N by N) of eqs 1.8-1.11; K = S (x) I_2.
  const Eigen::SparseMatrix<double>& stiffness() const { return stiffness_; }
  /// The per-axis transition A_s (2N by 2N); A = I_2 (x) A_s in the state's order.
  const Eigen::MatrixXd& transition() const { return transition_; }
  /// The per-axis process noise covariance Q_s (2N by 2N); Q = I_2 (x) Q_s.
  const Eigen::MatrixXd& process_noise() const { return process_noise_; }

 private:
  void update_separable(const Contour& measured_positions, double variance);
  void make_coupled();

  Contour rest_shape_;
  KalmanSnakeParameters parameters_;
  Eigen::SparseMatrix<double> stiffness_;  ///< S, N by N, constant
  Eigen::MatrixXd transition_;             ///< A_s, 2N by 2N, constant
  Eigen::MatrixX2d offset_;                ///< b per axis, 2N by 2 (column a is axis a), constant
  Eigen::MatrixXd process_noise_;          ///< Q_s, 2N by 2N, constant
  Eigen::MatrixX2d state_;                 ///< column a: [u_a; v_a] (2N)
  bool separable_ = true;
  Eigen::MatrixXd covariance_;  ///< P_s (2N) while separable_, else the full P (4N)
};

/// The unit normals of a closed contour (#N by 2): the central tangent t = u_{i+1} - u_{i-1}
/// turned by +90 degrees, (-t_y, t_x) / |t| (to the left of the direction of travel: inward for
/// a counter-clockwise contour in the (x, y) frame). A row is zero where the tangent vanishes.
Eigen::MatrixX2d contour_normals(const Contour& contour);

/// The edge measurements of EdgeSearchParameters about `predicted` (#N by 2) in the edge
/// potential of a frame (computed with c = 1): at most one per node. Throws Error for a potential
/// whose size is not search.width by search.height or bad search parameters.
std::vector<NormalMeasurement> edge_measurements(const ImageEdgePotential& potential,
                                                 const Contour& predicted,
                                                 const EdgeSearchParameters& search);

}  // namespace dnurbs
