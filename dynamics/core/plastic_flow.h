#pragma once
// Plastic flow of a rest shape: a model whose energy is measured from a rest shape (the D-NURBS
// rest shape of dynamics/dnurbs/dnurbs_model.h) keeps a push as a dent when its rest shape
// yields, the inelastic behaviour of Terzopoulos & Fleischer (Modeling inelastic deformation:
// viscoelasticity, plasticity, fracture, SIGGRAPH 1988): the reference shape is changed where the
// deformation exceeds a yield limit. Here the deformation of a node is the distance s = |x - r|
// of its position x from its rest position r, both read from a model's coordinate vector and its
// rest vector: three coordinates of a point in space (grid nodes, control points of a net), or
// the two in-plane coordinates of a planar curve's control point (the profile and trajectory of a
// swung surface). Up to `yield` it is elastic;
// beyond it the rest position flows towards x at `rate` (a viscoplastic rule),
//   dr/dt = rate (|s| - yield) s / |s|                      where |s| > yield,
// integrated over a step of dt as
//   r <- r + c (|s| - yield) s / |s|,   c = min(1, rate dt),
// so that the excess e = |s| - yield of a node held still decays as e_n = (1 - c)^n e_0, and
// c = 1 returns it to the yield surface at once (perfect plasticity).

#include <Eigen/Core>

namespace dnurbs {

/// The yield rule of a rest shape (file comment).
struct PlasticFlow {
  double yield = 0.0;  ///< distance a node moves from its rest position elastically (>= 0)
  double rate = 1.0;   ///< flow rate of the excess beyond yield, per unit time (> 0)
};

/// Throws Error naming the value unless yield >= 0 and rate > 0, both finite.
void check_plastic_flow(const PlasticFlow& flow);

/// One step of dt (> 0) of the rule on every node of `q` and `rest` (the same size, a multiple
/// of `stride` >= `dimension`): node a's position is the `dimension` (2 or 3) entries from
/// stride a on, the others (a free weight) do not flow. Returns the number of nodes that yielded.
int flow_rest_positions(const PlasticFlow& flow, double dt, int stride,
                        const Eigen::Ref<const Eigen::VectorXd>& q,
                        Eigen::Ref<Eigen::VectorXd> rest, int dimension = 3);

/// Throws Error naming the size or the first non-finite entry unless `rest` has `size` finite
/// entries (rest coordinates given back to a model, Model::restore_flowing_rest_coordinates).
void check_rest_coordinates(const Eigen::Ref<const Eigen::VectorXd>& rest, Eigen::Index size);

}  // namespace dnurbs
