#include "dnurbs/dynamics/core/image_force.h"

#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

void ImageFrame::validate() const {
  if (!origin.allFinite()) {
    throw make_error("image frame origin (", origin.x(), ", ", origin.y(), ", ", origin.z(),
                     ") is not finite");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!(spacing[axis] > 0.0) || !std::isfinite(spacing[axis])) {
      throw make_error("image frame spacing ", "xyz"[axis], " = ", spacing[axis],
                       " is not positive and finite");
    }
  }
}

namespace {

// -grad_x P at model-space x for a potential of Dimension 2 or 3 (eq. 1.5).
template <int Dimension>
Force edge_force(std::shared_ptr<const EdgePotential<Dimension>> potential,
                 const ImageFrame& frame) {
  if (!potential) {
    throw make_error("edge potential force has no potential");
  }
  frame.validate();
  using Point = typename EdgePotential<Dimension>::Point;
  const Point origin = frame.origin.head<Dimension>();
  const Point spacing = frame.spacing.head<Dimension>();
  return [potential = std::move(potential), origin, spacing](
             const Model& model, double /*t*/, ConstVectorRef q, ConstVectorRef /*qd*/,
             VectorRef generalized) {
    model.add_distributed_force(
        q,
        [&](const MaterialSample& sample) -> Eigen::Vector3d {
          const Point pixel = (sample.position.head<Dimension>() - origin).cwiseQuotient(spacing);
          // The chain rule of x = origin + spacing .* p: grad_x P = grad_p P ./ spacing.
          const Point gradient = potential->gradient(pixel).cwiseQuotient(spacing);
          Eigen::Vector3d force = Eigen::Vector3d::Zero();
          force.head<Dimension>() = -gradient;
          return force;
        },
        generalized);
  };
}

}  // namespace

Force image_edge_force(std::shared_ptr<const ImageEdgePotential> potential,
                       const ImageFrame& frame) {
  return edge_force<2>(std::move(potential), frame);
}

Force volume_edge_force(std::shared_ptr<const VolumeEdgePotential> potential,
                        const ImageFrame& frame) {
  return edge_force<3>(std::move(potential), frame);
}

}  // namespace dnurbs
