// Boundary conditions and bounds of the swung D-NURBS model's coordinates (Model::fix_point,
// Model::fix_border, the model's own curve fixes and Model::coordinate_lower_bounds), and the
// release of the scaling gauge coordinate when a fix already breaks the scaling
// (dynamics/swung/swung_gauge.h).

#include <algorithm>
#include <numeric>
#include <vector>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/swung/dnurbs_swung_surface.h"
#include "dnurbs/dynamics/swung/swung_boundary_conditions.h"
#include "dnurbs/dynamics/swung/swung_gauge.h"
#include "dnurbs/dynamics/swung/swung_parametric_surface.h"

namespace dnurbs {

void DNurbsSwungSurface::fix_coordinates(const std::vector<int>& coordinates) {
  if (gauge_coordinate_ >= 0) {
    gauge_requested_ = gauge_requested_ || std::find(coordinates.begin(), coordinates.end(),
                                                     gauge_coordinate_) != coordinates.end();
    if (fixes_swung_scaling_gauge(layout_, initial_coordinates_, gauge_coordinate_, coordinates)) {
      release_gauge();
    }
  }
  for (const int index : coordinates) {
    fix_coordinate(index);
  }
}

void DNurbsSwungSurface::release_gauge() {
  std::vector<int> kept;
  for (const int index : fixed_coordinates()) {
    if (index != gauge_coordinate_ || gauge_requested_) {
      kept.push_back(index);
    }
  }
  DNurbsSwungSettings settings = settings_;
  settings.fix_gauge = false;
  DNurbsSwungSurface released(surface_, material_, settings);
  for (const int index : kept) {
    released.fix_coordinate(index);
  }
  // The rest shape as it is now (set_rest_shape or moved by plastic flow), not as built
  if (has_rest_shape()) {
    released.set_rest_shape(rest_coordinates_);
  }
  released.plastic_flow_ = plastic_flow_;
  *this = std::move(released);
}

void DNurbsSwungSurface::fix_point(int i) {
  fix_coordinates(swung_point_coordinates(layout_, i));
}

void DNurbsSwungSurface::fix_border() {
  const std::vector<int> border =
      swung_border_coordinates(surface_, layout_, swung_parameter_domain(surface_));
  if (border.empty()) {
    throw make_error(
        "this swung surface is closed (periodic or seamed directions, poles on the "
        "axis): it has no border to fix");
  }
  fix_coordinates(border);
}

void DNurbsSwungSurface::fix_profile_point(int i) {
  const int offset = profile_offset(i);
  fix_coordinates({offset, offset + 1});
}

void DNurbsSwungSurface::fix_trajectory_point(int j) {
  const int offset = trajectory_offset(j);
  fix_coordinates({offset, offset + 1});
}

void DNurbsSwungSurface::fix_profile() {
  std::vector<int> profile(static_cast<size_t>(layout_.trajectory_offset(0)));
  std::iota(profile.begin(), profile.end(), 0);
  fix_coordinates(profile);
}

void DNurbsSwungSurface::fix_trajectory() {
  std::vector<int> trajectory(
      static_cast<size_t>(coordinate_count() - layout_.trajectory_offset(0)));
  std::iota(trajectory.begin(), trajectory.end(), layout_.trajectory_offset(0));
  fix_coordinates(trajectory);
}

void DNurbsSwungSurface::fix_poles() {
  if (surface_.profile().is_periodic()) {
    return;
  }
  std::vector<int> poles;
  for (const int i : {0, layout_.profile_count - 1}) {
    if (initial_coordinates_[layout_.profile_offset(i)] == 0.0) {
      poles.push_back(layout_.profile_offset(i));
    }
  }
  fix_coordinates(poles);
}

void DNurbsSwungSurface::coordinate_lower_bounds(VectorRef lower) const {
  if (layout_.mode != WeightMode::kFree) {
    return;
  }
  for (int index = 2; index < coordinate_count(); index += 3) {
    lower[index] = minimum_weight_;
  }
}

}  // namespace dnurbs
