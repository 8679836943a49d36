#include "dnurbs/vision/contour.h"

#include <algorithm>
#include <cmath>

namespace dnurbs {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Orientation of c relative to the line a -> b: +1 left, -1 right, 0 collinear.
int orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double value = cross(b - a, c - a);
  return (value > 0.0) - (value < 0.0);
}

/// Whether c, known collinear with a -> b, lies within the bounding box of a and b.
bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

/// Closed segments p0p1 and q0q1 share a point.
bool segments_touch(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                    const Eigen::Vector2d& q1) {
  const int o1 = orientation(p0, p1, q0);
  const int o2 = orientation(p0, p1, q1);
  const int o3 = orientation(q0, q1, p0);
  const int o4 = orientation(q0, q1, p1);
  if (o1 != o2 && o3 != o4) {
    return true;  // the general case of the classic orientation test
  }
  return (o1 == 0 && on_segment(p0, p1, q0)) || (o2 == 0 && on_segment(p0, p1, q1)) ||
         (o3 == 0 && on_segment(q0, q1, p0)) || (o4 == 0 && on_segment(q0, q1, p1));
}

struct Element {
  int contour;
  int index;
  double min_x;
  double max_x;
};

}  // namespace

double signed_area(const Contour& contour) {
  double twice_area = 0.0;
  const Eigen::Index n = contour.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    twice_area += contour(i, 0) * contour(j, 1) - contour(j, 0) * contour(i, 1);
  }
  return 0.5 * twice_area;
}

int winding_number(const std::vector<Contour>& contours, const Eigen::Vector2d& point) {
  int winding = 0;
  for (const Contour& contour : contours) {
    const Eigen::Index n = contour.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d a = contour.row(i);
      const Eigen::Vector2d b = contour.row((i + 1) % n);
      // Crossing-number rule with half-open elements: an upward element counts +1 and a
      // downward one -1 when it crosses the horizontal ray to the right of the point.
      if (a.y() <= point.y() && point.y() < b.y() && orientation(a, b, point) > 0) {
        ++winding;
      } else if (b.y() <= point.y() && point.y() < a.y() && orientation(a, b, point) < 0) {
        --winding;
      }
    }
  }
  return winding;
}

bool contours_intersect(const std::vector<Contour>& contours) {
  std::vector<Element> elements;
  for (int c = 0; c < static_cast<int>(contours.size()); ++c) {
    const Contour& contour = contours[static_cast<std::size_t>(c)];
    for (int i = 0; i < static_cast<int>(contour.rows()); ++i) {
      const int j = (i + 1) % static_cast<int>(contour.rows());
      elements.push_back(
          {c, i, std::min(contour(i, 0), contour(j, 0)), std::max(contour(i, 0), contour(j, 0))});
    }
  }
  std::sort(elements.begin(), elements.end(),
            [](const Element& a, const Element& b) { return a.min_x < b.min_x; });
  const auto node = [&](int c, int i) -> Eigen::Vector2d {
    const Contour& contour = contours[static_cast<std::size_t>(c)];
    return contour.row(i % static_cast<int>(contour.rows()));
  };
  // Sweep: each element is tested against the later elements whose x-extent starts before its
  // own ends.
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& a = elements[e];
    const Eigen::Vector2d a0 = node(a.contour, a.index);
    const Eigen::Vector2d a1 = node(a.contour, a.index + 1);
    for (std::size_t f = e + 1; f < elements.size() && elements[f].min_x <= a.max_x; ++f) {
      const Element& b = elements[f];
      const Eigen::Vector2d b0 = node(b.contour, b.index);
      const Eigen::Vector2d b1 = node(b.contour, b.index + 1);
      const int n = static_cast<int>(contours[static_cast<std::size_t>(a.contour)].rows());
      const bool same = a.contour == b.contour;
      if (same && (b.index == (a.index + 1) % n || a.index == (b.index + 1) % n)) {
        // Adjacent elements share a node; they intersect only if one folds back along the other.
        const bool a_first = b.index == (a.index + 1) % n;
        const Eigen::Vector2d shared = a_first ? a1 : a0;
        const Eigen::Vector2d before = a_first ? a0 : b0;
        const Eigen::Vector2d after = a_first ? b1 : a1;
        if (n > 2 && cross(shared - before, after - shared) == 0.0 &&
            (shared - before).dot(after - shared) < 0.0) {
          return true;
        }
        continue;
      }
      if (segments_touch(a0, a1, b0, b1)) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace dnurbs
