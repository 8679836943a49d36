#include "dnurbs/dynamics/dnurbs/local_sculpting.h"

#include <algorithm>
#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

void check_margin(int margin) {
  if (margin < 0) {
    throw make_error("local sculpting: margin ", margin, " is negative");
  }
}

void check_parameter(double u) {
  if (!std::isfinite(u)) {
    throw make_error("local sculpting: parameter ", u, " is not finite");
  }
}

// Marks the indices within `margin` of [first, last] (a run of consecutive control point
// indices along one direction), wrapping for periodic directions and clipping for open ones.
void mark_range(int first, int last, int margin, int count, bool periodic,
                std::vector<char>& marked) {
  for (int i = first - margin; i <= last + margin; ++i) {
    if (periodic) {
      marked[static_cast<size_t>(((i % count) + count) % count)] = 1;
    } else if (i >= 0 && i < count) {
      marked[static_cast<size_t>(i)] = 1;
    }
  }
}

// The control point indices along one direction driven on the span of u (first basis index
// span - p, before wrapping).
int first_driven_index(const KnotVector& knots, double u) {
  check_parameter(u);
  return knots.find_span(u) - knots.degree();
}

std::vector<int> marked_indices(const std::vector<char>& marked) {
  std::vector<int> indices;
  for (size_t i = 0; i < marked.size(); ++i) {
    if (marked[i]) {
      indices.push_back(static_cast<int>(i));
    }
  }
  return indices;
}

template <class Model>
int freeze_outside(Model& model, const std::vector<int>& kept) {
  int frozen = 0;
  for (int i = 0; i < model.control_point_count(); ++i) {
    if (!std::binary_search(kept.begin(), kept.end(), i)) {
      model.fix_control_point(i);
      ++frozen;
    }
  }
  return frozen;
}

}  // namespace

std::vector<int> sculpted_control_points(const NurbsSurface& surface, const SculptedRegion& region,
                                         int margin) {
  check_margin(margin);
  const KnotVector& knots_u = surface.knots_u();
  const KnotVector& knots_v = surface.knots_v();
  const int count_u = surface.control_point_count_u();
  const int count_v = surface.control_point_count_v();
  std::vector<char> marked(static_cast<size_t>(count_u) * static_cast<size_t>(count_v), 0);
  // One block of the control net: rows [u0, u1] by columns [v0, v1], grown by the margin
  auto mark_block = [&](int u0, int u1, int v0, int v1) {
    std::vector<char> rows(static_cast<size_t>(count_u), 0);
    std::vector<char> columns(static_cast<size_t>(count_v), 0);
    mark_range(u0, u1, margin, count_u, knots_u.is_periodic(), rows);
    mark_range(v0, v1, margin, count_v, knots_v.is_periodic(), columns);
    for (int i = 0; i < count_u; ++i) {
      for (int j = 0; j < count_v && rows[static_cast<size_t>(i)]; ++j) {
        if (columns[static_cast<size_t>(j)]) {
          marked[static_cast<size_t>(surface.control_point_index(i, j))] = 1;
        }
      }
    }
  };
  for (const Eigen::Vector2d& uv : region.parameters) {
    const int first_u = first_driven_index(knots_u, uv.x());
    const int first_v = first_driven_index(knots_v, uv.y());
    mark_block(first_u, first_u + knots_u.degree(), first_v, first_v + knots_v.degree());
  }
  for (const int index : region.control_points) {
    if (index < 0 || index >= count_u * count_v) {
      throw make_error("local sculpting: control point ", index, " is outside 0..",
                       count_u * count_v - 1);
    }
    mark_block(index / count_v, index / count_v, index % count_v, index % count_v);
  }
  return marked_indices(marked);
}

std::vector<int> sculpted_control_points(const NurbsCurve& curve, const SculptedRegion& region,
                                         int margin) {
  check_margin(margin);
  const KnotVector& knots = curve.knots();
  const int count = curve.control_point_count();
  std::vector<char> marked(static_cast<size_t>(count), 0);
  for (const Eigen::Vector2d& uv : region.parameters) {
    const int first = first_driven_index(knots, uv.x());
    mark_range(first, first + knots.degree(), margin, count, knots.is_periodic(), marked);
  }
  for (const int index : region.control_points) {
    if (index < 0 || index >= count) {
      throw make_error("local sculpting: control point ", index, " is outside 0..", count - 1);
    }
    mark_range(index, index, margin, count, knots.is_periodic(), marked);
  }
  return marked_indices(marked);
}

int freeze_outside_sculpted_region(DNurbsSurface& model, const SculptedRegion& region, int margin) {
  return freeze_outside(model, sculpted_control_points(model.initial_surface(), region, margin));
}

int freeze_outside_sculpted_region(DNurbsCurve& model, const SculptedRegion& region, int margin) {
  return freeze_outside(model, sculpted_control_points(model.initial_curve(), region, margin));
}

}  // namespace dnurbs
