#include "dnurbs/dynamics/swung/swung_boundary_conditions.h"

#include <algorithm>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// The in-plane coordinates of every control point of one curve (offset: its first x).
void add_curve(int offset, int count, int per_control_point, std::vector<int>& coordinates) {
  for (int i = 0; i < count; ++i) {
    coordinates.push_back(offset + per_control_point * i);
    coordinates.push_back(offset + per_control_point * i + 1);
  }
}

// The in-plane coordinates of the control points whose basis functions do not vanish at
// parameter u of a curve (Piegl & Tiller, The NURBS Book, A2.2: the p + 1 functions of u's span).
void add_active_at(const KnotVector& knots, double u, int offset, int per_control_point,
                   std::vector<int>& coordinates) {
  PlanarCurveSample sample;
  planar_curve_basis(knots, u, sample);
  for (int a = 0; a <= sample.degree; ++a) {
    if (sample.basis(0, a) != 0.0) {
      const int point = sample.control_point[static_cast<size_t>(a)];
      coordinates.push_back(offset + per_control_point * point);
      coordinates.push_back(offset + per_control_point * point + 1);
    }
  }
}

}  // namespace

std::vector<int> swung_point_coordinates(const SwungLayout& layout, int i) {
  const int count = layout.profile_count + layout.trajectory_count;
  if (i < 0 || i >= count) {
    throw make_error("swung surface point ", i, " does not exist: points 0..",
                     layout.profile_count - 1, " are the profile's control points, ",
                     layout.profile_count, "..", count - 1, " the trajectory's");
  }
  const int offset = i < layout.profile_count ? layout.profile_offset(i)
                                              : layout.trajectory_offset(i - layout.profile_count);
  return {offset, offset + 1};
}

std::vector<int> swung_border_coordinates(const SwungSurface& surface, const SwungLayout& layout,
                                          const ParameterDomain& domain) {
  const int per = layout.per_control_point;
  const int trajectory = layout.trajectory_offset(0);
  std::vector<int> coordinates;
  // Edges u = const: the profile's end control points and the whole trajectory.
  for (const auto& [is_border, u] :
       {std::pair{!domain.periodic_u && !domain.pole_u_min, domain.u_min},
        std::pair{!domain.periodic_u && !domain.pole_u_max, domain.u_max}}) {
    if (is_border) {
      add_active_at(surface.profile().knots(), u, 0, per, coordinates);
      add_curve(trajectory, layout.trajectory_count, per, coordinates);
    }
  }
  // Edges v = const: the whole profile and the trajectory's end control points.
  for (const auto& [is_border, v] :
       {std::pair{!domain.periodic_v && !domain.pole_v_min, domain.v_min},
        std::pair{!domain.periodic_v && !domain.pole_v_max, domain.v_max}}) {
    if (is_border) {
      add_curve(0, layout.profile_count, per, coordinates);
      add_active_at(surface.trajectory().knots(), v, trajectory, per, coordinates);
    }
  }
  std::sort(coordinates.begin(), coordinates.end());
  coordinates.erase(std::unique(coordinates.begin(), coordinates.end()), coordinates.end());
  return coordinates;
}

}  // namespace dnurbs
