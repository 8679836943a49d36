#pragma once
// The parameters T-snakes and T-surfaces share: the weights of their explicit deformation step
// (McInerney & Terzopoulos, T-snakes: Topology adaptive snakes, Medical Image Analysis 4(2)
// 2000; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, eqs. 1.2-1.5 with mu = 0) and the inflation switch F(I).

namespace dnurbs {

/// The weights of x_i <- x_i + (time_step / damping) (-tension alpha_i - rigidity beta_i + rho_i
/// + f_i), rho_i = inflation F(I(x_i)) n_i, f_i = -edge_weight grad P(x_i), and of the ACID (all in
/// pixel or voxel units). T-snakes and T-surfaces define alpha_i and beta_i (their headers).
struct TopologyAdaptiveParameters {
  double cell_size = 2.0;                ///< ACID grid cell side
  double tension = 0.05;                 ///< a
  double rigidity = 0.0;                 ///< b
  double damping = 1.0;                  ///< gamma
  double time_step = 0.2;                ///< Delta t
  double inflation = 1.0;                ///< q
  double threshold = 0.5;                ///< T of the switch F
  double inflation_band = 0.0;           ///< w of the switch F, 0 for the binary switch
  double edge_weight = 1.0;              ///< p
  int steps_per_reparameterization = 1;  ///< M

  /// Throws Error naming `model` and the parameter for a negative or non-finite weight, damping,
  /// time step or cell size <= 0, a non-finite threshold, M < 1, or an unstable explicit step:
  /// time_step / damping (tension_eigenvalue tension + rigidity_eigenvalue rigidity) >= 1, with the
  /// largest eigenvalues of the model's alpha and beta operators.
  void validate(const char* model, double tension_eigenvalue, double rigidity_eigenvalue) const;
};

/// The inflation switch F(I) (McInerney & Terzopoulos 2000): +1 where I >= threshold
/// and -1 elsewhere when band = 0; otherwise the continuous ramp clamp((I - threshold) / band,
/// -1, 1), which lets a node rest on the threshold contour instead of oscillating about it.
double inflation_switch(double intensity, double threshold, double band);

}  // namespace dnurbs
