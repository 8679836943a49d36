#pragma once
// Data forces: physics-based fitting of a model to 3-D points (Terzopoulos & Metaxas, "Dynamic 3D
// models with local and global deformations: deformable superquadrics", IEEE PAMI 13(7) 1991,
// section 5; Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized
// Formulations, 2003, section 2.7). Every data point z_k is joined by a spring of stiffness k to
// the material point u_k of the model nearest to it at the current state,
//
//   f_k = k (z_k - x(u_k)),   generalized force  sum_k L(u_k)^T f_k,
//
// so the model is pulled over time toward the data; the points may move (tracking). The nearest
// material point is found on a grid of parameters, then refined by Gauss-Newton steps on
// |x(u) - z|^2 with difference tangents, clamped to the domain (wrapped where it is periodic).

#include <functional>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"

namespace dnurbs {

/// How data points find their material points.
struct DataForceSettings {
  double stiffness = 1.0;    ///< k >= 0, force per unit distance of each point's spring
  int search_segments = 24;  ///< parameter grid cells per direction for the coarse search (>= 2)
  /// Most Gauss-Newton steps after the coarse search (>= 0); they stop when no step decreases
  /// the distance.
  int refinement_steps = 30;

  /// Throws Error naming the value for a negative or non-finite stiffness or counts out of range.
  void validate() const;
};

/// The material point of `model` at state q nearest to `point` (the search of data_force).
struct NearestMaterialPoint {
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();  ///< u (curves: (u, 0))
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   ///< x(u)
};

/// The nearest material point for each row of `points` (#points by 3). The coarse search
/// evaluates x on a (search_segments + 1)^d grid of the model's parameter domain once for all
/// points. Throws Error for a non-finite point or bad settings.
std::vector<NearestMaterialPoint> nearest_material_points(const Model& model, ConstVectorRef q,
                                                          const Eigen::MatrixX3d& points,
                                                          const DataForceSettings& settings = {});

/// Data points over time: #points by 3 at time t (the same count at every time).
using PointsOfTime = std::function<Eigen::MatrixX3d(double)>;

/// The data force of points that move (tracking): sum_k L(u_k)^T k (z_k(t) - x(u_k)). Throws
/// Error for bad settings or a missing function; a non-finite point throws when evaluated.
Force moving_data_force(PointsOfTime points, const DataForceSettings& settings = {});
/// The same for fixed points (#points by 3, every entry finite).
Force data_force(const Eigen::MatrixX3d& points, const DataForceSettings& settings = {});

}  // namespace dnurbs
