#pragma once
// Closed polygonal contours in the plane, the shape of T-snakes (McInerney & Terzopoulos,
// T-snakes: Topology adaptive snakes, Medical Image Analysis 4(2) 2000): signed area, winding
// number, and the test that no two elements of a set of contours intersect.

#include <vector>

#include <Eigen/Core>

namespace dnurbs {

/// A closed polygon.
///
/// Contour  #N by 2 node positions; element i joins node i to node (i + 1) mod N.
using Contour = Eigen::MatrixX2d;

/// Signed area by the shoelace formula: positive for counter-clockwise contours in the (x, y)
/// frame (outer boundaries of T-snake regions), negative for clockwise ones (holes).
double signed_area(const Contour& contour);

/// The winding number of `point` (2 coordinates) about all `contours` (sum over contours):
/// counter-clockwise loops around the point count +1, clockwise ones -1. Points on a contour get
/// the value of the half-open crossing rule (upward elements include their lower end).
int winding_number(const std::vector<Contour>& contours, const Eigen::Vector2d& point);

/// True if two elements of `contours` intersect: two non-adjacent elements (of one contour or of
/// two) that touch or cross, or two adjacent elements that fold back onto each other. A set of
/// contours for which this is false bounds a region without self-intersections. O(E log E + K)
/// by a sweep over the elements' x-extents (E elements, K overlapping x-extent pairs).
bool contours_intersect(const std::vector<Contour>& contours);

}  // namespace dnurbs
