#pragma once
// Forces drawn from images and volumes: the external force -grad P of the snake equations
// (Terzopoulos, Deformable Models: Classic, Topology-Adaptive and Generalized Formulations, 2003,
// eqs. 1.3-1.5) with P the Gaussian-smoothed edge potential P = -c |grad(G_sigma * I)| (below
// eq. 1.3) of a 2-D image, or of a 3-D volume for surfaces (section 2.5; the volume setting of
// section 3.2). The potentials are those of vision/edge_potential.h (cubic interpolation, exact
// gradient of the interpolant).
//
// An ImageFrame places the data in model space: the sample at pixel (voxel) index p sits at
//   x = origin + spacing .* p
// (x along image columns, y along rows, z along slices), so grad_x P = grad_p P ./ spacing.

#include <memory>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/volume_edge_potential.h"

namespace dnurbs {

/// Where an image or volume sits in model space (see the file comment). A 2-D image lies in the
/// plane z = origin.z(); its force has no z component and does not depend on z.
struct ImageFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   ///< model-space position of sample (0, 0, 0)
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();  ///< model-space size of a pixel (voxel)

  /// Throws Error naming the value if the origin is not finite or a spacing is not positive and
  /// finite.
  void validate() const;
};

/// The force density -grad_x P(x(u)) of a 2-D edge potential at every material point
/// (Terzopoulos 2003, eq. 1.5), through Model::add_distributed_force: snakes and grid surfaces
/// take it node by node (the per-node -grad P(u_i) of eq. 1.5's discretization), D-NURBS and the
/// other continuous models integrate L^T f over their quadrature (per unit parametric measure).
/// Only (x, y) matter; points outside the image are clamped to it (EdgePotential), where the
/// force is that of the nearest border sample. The potential is shared, not copied. Throws Error
/// for a null potential or a bad frame.
Force image_edge_force(std::shared_ptr<const ImageEdgePotential> potential,
                       const ImageFrame& frame = {});

/// The same for a volume: -grad_x P(x) with P = -c |grad(G_sigma * V)| in 3-D.
Force volume_edge_force(std::shared_ptr<const VolumeEdgePotential> potential,
                        const ImageFrame& frame = {});

}  // namespace dnurbs
