#pragma once
// The force region and the moving force of the PDE surface tool (Romero 2005, section 5 and
// figure 11): a force node with a centre, a force radius and a force. Every active node of a
// PdeSurface whose initial rest position lies within the force radius of the centre receives the
// force (Romero 2005, section 5: the nodes inside the force region get the force components, the
// other deformed nodes 0), so a larger force radius pushes more nodes (figure 11). The centre is a
// function of time: a moving force (figure 11, "the same force is displaced to another location").
//
// A moving force needs a deformation region that moves with it. Rebuilding the region around the
// centre at every step, as the thesis does, starts the nodes that enter it from rest (section 5:
// velocity 0 "if the node is newly deformed"), a jump in velocity wherever the surface was
// already moving there. swept_deformation_regions instead simulates, from the start, every node
// that the region passes over along the centre's path: a node entering the region around the
// current centre already carries the velocity the surface gives it, and inside the swept box the
// motion is that of the whole-surface solve up to the border of the swept box.

#include <vector>

#include <Eigen/Core>

#include "dnurbs/dynamics/core/spring.h"
#include "dnurbs/dynamics/core/system.h"
#include "dnurbs/dynamics/grid/pde_surface.h"

namespace dnurbs {

/// The force force(t) on each node of `surface` within `force_radius` of centre(t) at rest: a
/// PdeSurface (its active nodes, PdeSurface::nodes_within), or any model whose coordinates are
/// node positions, 3 per node from Model::control_point_offset. The nodes' rest positions are
/// read once, here, from surface.initial_coordinates(); the force acts on a model of the same
/// size (the System's copy of `surface`). Throws Error naming the value for a radius that is
/// negative or not finite, without a centre or force function, or for a model whose coordinates
/// are not 3 per node; applied to a model of another size, or at a time where the centre is not
/// finite, the force throws Error.
Force pde_force_region(const Model& surface, VectorOfTime centre, double force_radius,
                       VectorOfTime force);

/// The deformation regions that a region of `deformation_radius` sweeps while its centre follows
/// centre(t) for start <= t <= end: regions of radius deformation_radius + max_move around the
/// centre at equally spaced times, as many as it takes (doubled from 16, at most 65536) for
/// consecutive centres to be less than max_move apart, so that the region around any centre on
/// the way lies inside one of them. Pass them all to PdeSurface (the union of their boxes). A
/// centre that does not move gives one region. Throws Error naming the value for a radius or
/// max_move that is not positive and finite, end < start, a non-finite centre, or a path that
/// needs more than 65536 samples.
std::vector<DeformationRegion> swept_deformation_regions(const VectorOfTime& centre,
                                                         double deformation_radius, double start,
                                                         double end, double max_move);

}  // namespace dnurbs
