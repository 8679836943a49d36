#include "dnurbs/nurbs/swung_refinement.h"

#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/knot_insertion.h"

namespace dnurbs {
namespace {

// `count` knots inside every non-empty span, evenly spaced (Piegl & Tiller A5.4 inserts them).
NurbsCurve refine_uniformly(const NurbsCurve& curve, int count, const char* name) {
  if (count < 0) {
    throw make_error("swung surface refinement: ", name, " knots per span is ", count,
                     ", must be >= 0");
  }
  if (count == 0) {
    return curve;
  }
  const KnotVector& knots = curve.knots();
  std::vector<double> inserted;
  for (const int span : knots.non_empty_spans()) {
    const double start = knots[span];
    const double length = knots[span + 1] - start;
    for (int i = 1; i <= count; ++i) {
      inserted.push_back(start + length * i / (count + 1));
    }
  }
  return refine_knots(curve, inserted);
}

}  // namespace

SwungSurface refine_swung_surface(const SwungSurface& surface, int profile_knots,
                                  int trajectory_knots) {
  return SwungSurface(refine_uniformly(surface.profile(), profile_knots, "profile"),
                      refine_uniformly(surface.trajectory(), trajectory_knots, "trajectory"),
                      surface.alpha());
}

}  // namespace dnurbs
