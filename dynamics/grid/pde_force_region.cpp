#include "dnurbs/dynamics/grid/pde_force_region.h"

#include <cmath>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {

Force pde_force_region(const Model& surface, VectorOfTime centre, double force_radius,
                       VectorOfTime force) {
  if (!(force_radius >= 0.0) || !std::isfinite(force_radius)) {
    throw make_error("force radius ", force_radius, " is not non-negative and finite");
  }
  if (!centre || !force) {
    throw make_error("force region has no ", !centre ? "centre" : "force", " function");
  }
  const int size = surface.velocity_count();
  if (surface.coordinate_count() != size || size % 3 != 0) {
    throw make_error("a force region acts on node positions, 3 coordinates per node: a model of ",
                     surface.coordinate_count(), " coordinates and ", size,
                     " velocities has no such nodes");
  }
  // The nodes' rest positions, once (Romero 2005, section 5: the force region is found at rest)
  const Eigen::VectorXd initial = surface.initial_coordinates();
  std::vector<int> offsets(static_cast<size_t>(size / 3));
  Eigen::VectorXd rest(size);
  for (int a = 0; a < size / 3; ++a) {
    offsets[static_cast<size_t>(a)] = surface.control_point_offset(a);
    rest.segment<3>(3 * a) = initial.segment<3>(offsets[static_cast<size_t>(a)]);
  }
  return [centre = std::move(centre), force_radius, force = std::move(force), size,
          offsets = std::move(offsets),
          rest = std::move(rest)](const Model& model, double t, ConstVectorRef /*q*/,
                                  ConstVectorRef /*qd*/, VectorRef generalized) {
    if (model.velocity_count() != size) {
      throw make_error("a force region found on a model of ", size,
                       " velocities is applied to a model of ", model.velocity_count());
    }
    const Eigen::Vector3d at = centre(t);
    if (!at.allFinite()) {
      throw make_error("force region centre (", at.x(), ", ", at.y(), ", ", at.z(), ") at t = ", t,
                       " is not finite");
    }
    // Romero 2005, section 5: every node of the force region receives the force components
    const Eigen::Vector3d f = force(t);
    for (const int node : nodes_within(rest, at, force_radius)) {
      generalized.segment<3>(offsets[static_cast<size_t>(node)]) += f;
    }
  };
}

std::vector<DeformationRegion> swept_deformation_regions(const VectorOfTime& centre,
                                                         double deformation_radius, double start,
                                                         double end, double max_move) {
  if (!(deformation_radius > 0.0) || !std::isfinite(deformation_radius)) {
    throw make_error("deformation radius ", deformation_radius, " is not positive and finite");
  }
  if (!(max_move > 0.0) || !std::isfinite(max_move)) {
    throw make_error("swept region max_move = ", max_move, " is not positive and finite");
  }
  if (!centre || !std::isfinite(start) || !std::isfinite(end) || !(end >= start)) {
    throw make_error("swept region time span [", start, ", ", end,
                     "] is not a finite interval with a centre function");
  }
  constexpr int kMaxSamples = 65536;
  for (int count = 16; count <= kMaxSamples; count *= 2) {
    std::vector<Eigen::Vector3d> centres;
    bool fine = true;
    for (int s = 0; s <= count; ++s) {
      const Eigen::Vector3d at = centre(start + (end - start) * s / count);
      if (!at.allFinite()) {
        throw make_error("swept region centre (", at.x(), ", ", at.y(), ", ", at.z(),
                         ") is not finite");
      }
      fine = fine && (centres.empty() || (at - centres.back()).norm() < max_move);
      centres.push_back(at);
    }
    if (!fine) {
      continue;
    }
    std::vector<DeformationRegion> regions;
    for (const Eigen::Vector3d& at : centres) {
      if (regions.empty() || (at - regions.back().centre).norm() > 0.0) {
        regions.push_back({at, deformation_radius + max_move});
      }
    }
    return regions;
  }
  throw make_error("swept region path needs more than ", kMaxSamples,
                   " samples for steps under max_move = ", max_move);
}

}  // namespace dnurbs
