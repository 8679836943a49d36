#pragma once
// The edge potential of a volume image, for T-surfaces (Terzopoulos, Deformable Models: Classic,
// Topology-Adaptive and Generalized Formulations, section 3.2): EdgePotential<3> of
// vision/edge_potential.h, interpolated tricubically (64 samples around a point).

#include "dnurbs/vision/edge_potential.h"
#include "dnurbs/vision/volume.h"

namespace dnurbs {

/// P = -c |grad(G_sigma * V)| of one volume V, with the smoothed volume G_sigma * V: the external
/// potential of T-surfaces (TSurface). Points and gradients are Eigen::Vector3d in voxel units;
/// samples() and smoothed() are volumes of the size of V.
using VolumeEdgePotential = EdgePotential<3>;

extern template class EdgePotential<3>;

}  // namespace dnurbs
