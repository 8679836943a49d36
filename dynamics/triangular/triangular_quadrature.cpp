#include "dnurbs/dynamics/triangular/triangular_quadrature.h"

#include <algorithm>

#include "dnurbs/core/error.h"
#include "dnurbs/nurbs/simplex_spline.h"
#include "dnurbs/nurbs/triangular_polynomial_cells.h"

namespace dnurbs {

TriangularQuadrature::TriangularQuadrature(std::shared_ptr<const TriangularBSplineBasis> basis,
                                           int degree, int subdivisions, int order)
    : basis_(std::move(basis)), order_(order) {
  if (!basis_) {
    throw make_error("triangular quadrature without a basis");
  }
  if (degree < 1 || degree > kMaxDunavantDegree) {
    throw make_error("triangular quadrature degree ", degree, " is outside 1..",
                     kMaxDunavantDegree);
  }
  if (subdivisions < 0 || subdivisions > 64) {
    throw make_error("triangular quadrature subdivisions ", subdivisions,
                     " is outside 0..64 (0: exact polynomial cells)");
  }
  if (order < 0 || order > 2) {
    throw make_error("triangular quadrature derivative order ", order, " is outside 0..2");
  }
  // Exact cells: Taylor polynomials of degree n are the B-splines' pieces. Composite rule: each
  // point is its own piece (origin at the point), with the derivatives up to `order` there.
  taylor_order_ = subdivisions == 0 ? basis_->degree() : order_;
  const TriangleRule& base = interior_positive_dunavant_rule(degree);
  const TriangleRule composite = subdivided_rule(base, std::max(1, subdivisions));
  const Triangulation& triangulation = basis_->triangulation();
  const int per_triangle = basis_->functions_per_triangle();
  piece_begin_.push_back(0);
  for (int e = 0; e < triangulation.triangle_count(); ++e) {
    // The element's B-splines: those of every triangle whose knots' hull meets it.
    std::vector<int> functions;
    for (const int s : basis_->overlapping_triangles(e)) {
      for (int b = 0; b < per_triangle; ++b) {
        functions.push_back(s * per_triangle + b);
      }
    }
    max_local_count_ = std::max(max_local_count_, static_cast<int>(functions.size()));
    element_functions_.push_back(std::move(functions));
    element_begin_.push_back(static_cast<int>(parameter_.size()));
    const std::array<Eigen::Vector2d, 3> corners = {
        triangulation.corner(e, 0), triangulation.corner(e, 1), triangulation.corner(e, 2)};
    if (subdivisions > 0) {
      // One piece per point of the composite rule, evaluated from inside the element.
      for (int g = 0; g < composite.point_count(); ++g) {
        const Eigen::Vector2d u = composite.barycentric(g, 0) * corners[0] +
                                  composite.barycentric(g, 1) * corners[1] +
                                  composite.barycentric(g, 2) * corners[2];
        const Eigen::Vector2d direction = triangulation.centroid(e) - u;
        const int piece = add_piece(
            e, u, direction.norm() > 0.0 ? direction : Triangulation::half_open_direction());
        add_point(e, piece, u, triangulation.area(e) * composite.weights[g]);
      }
      continue;
    }
    // One piece per polynomial cell, with the rule on the triangles of its fan.
    for (const ConvexPolygon& cell : polynomial_cells(*basis_, e)) {
      Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& corner : cell) {
        centroid += corner / static_cast<double>(cell.size());
      }
      const int piece = add_piece(e, centroid, Triangulation::half_open_direction());
      for (size_t k = 1; k + 1 < cell.size(); ++k) {
        const double area = 0.5 * signed_double_area(cell[0], cell[k], cell[k + 1]);
        for (int g = 0; g < base.point_count(); ++g) {
          add_point(e, piece,
                    base.barycentric(g, 0) * cell[0] + base.barycentric(g, 1) * cell[k] +
                        base.barycentric(g, 2) * cell[k + 1],
                    area * base.weights[g]);
        }
      }
    }
  }
  element_begin_.push_back(static_cast<int>(parameter_.size()));
}

int TriangularQuadrature::add_piece(int e, const Eigen::Vector2d& origin,
                                    const Eigen::Vector2d& direction) {
  // Taylor coefficients D^(a,b) N / (a! b!) of the non-zero B-splines at the origin.
  std::vector<int> functions;
  Eigen::MatrixXd derivatives;
  std::vector<double> scratch;
  basis_->derivatives_in_triangle(e, origin, direction, taylor_order_, functions, derivatives,
                                  scratch);
  for (int a = 0; a <= taylor_order_; ++a) {
    for (int b = 0; a + b <= taylor_order_; ++b) {
      double factorial = 1.0;
      for (int k = 2; k <= a; ++k) {
        factorial *= k;
      }
      for (int k = 2; k <= b; ++k) {
        factorial *= k;
      }
      derivatives.row(derivative_index(a, b)) /= factorial;
    }
  }
  for (Eigen::Index k = 0; k < derivatives.cols(); ++k) {
    if (derivatives.col(k).cwiseAbs().maxCoeff() == 0.0) {
      continue;
    }
    entry_local_.push_back(static_cast<int>(k));
    entry_coefficient_.insert(entry_coefficient_.end(), derivatives.col(k).data(),
                              derivatives.col(k).data() + derivatives.rows());
  }
  piece_origin_.push_back(origin);
  piece_begin_.push_back(static_cast<int>(entry_local_.size()));
  return static_cast<int>(piece_origin_.size()) - 1;
}

void TriangularQuadrature::add_point(int e, int piece, const Eigen::Vector2d& u, double weight) {
  parameter_.push_back(u);
  weight_.push_back(weight);
  element_of_.push_back(e);
  point_piece_.push_back(piece);
}

void TriangularQuadrature::basis_at(int point, TriangularBasisValues& values,
                                    std::vector<int>& local) const {
  const auto piece = static_cast<size_t>(point_piece_[static_cast<size_t>(point)]);
  const int begin = piece_begin_[piece];
  const int end = piece_begin_[piece + 1];
  const auto& functions = element_functions_[static_cast<size_t>(element_of(point))];
  values.triangle = element_of(point);
  values.count = end - begin;
  values.function.resize(static_cast<size_t>(values.count));
  local.resize(static_cast<size_t>(values.count));
  values.value.setZero(6, values.count);
  // Powers of the offset from the piece's origin (the origin itself for composite pieces).
  const Eigen::Vector2d d = parameter(point) - piece_origin_[piece];
  std::array<double, kMaxSimplexDerivativeOrder + 1> du{};
  std::array<double, kMaxSimplexDerivativeOrder + 1> dv{};
  du[0] = dv[0] = 1.0;
  for (int k = 1; k <= taylor_order_; ++k) {
    du[static_cast<size_t>(k)] = du[static_cast<size_t>(k - 1)] * d.x();
    dv[static_cast<size_t>(k)] = dv[static_cast<size_t>(k - 1)] * d.y();
  }
  auto power = [](const std::array<double, kMaxSimplexDerivativeOrder + 1>& p, int k) {
    return k < 0 ? 0.0 : p[static_cast<size_t>(k)];
  };
  const auto stride = static_cast<size_t>(derivative_count(taylor_order_));
  for (int k = 0; k < values.count; ++k) {
    const auto entry = static_cast<size_t>(begin) + static_cast<size_t>(k);
    const int a_local = entry_local_[entry];
    local[static_cast<size_t>(k)] = a_local;
    values.function[static_cast<size_t>(k)] = functions[static_cast<size_t>(a_local)];
    const double* c = &entry_coefficient_[stride * entry];
    // Sum of c_ab du^a dv^b and its derivatives up to the order cached.
    for (int a = 0; a <= taylor_order_; ++a) {
      for (int b = 0; a + b <= taylor_order_; ++b) {
        const double coefficient = c[derivative_index(a, b)];
        values.value(0, k) += coefficient * power(du, a) * power(dv, b);
        if (order_ >= 1) {
          values.value(1, k) += coefficient * a * power(du, a - 1) * power(dv, b);
          values.value(2, k) += coefficient * b * power(du, a) * power(dv, b - 1);
        }
        if (order_ >= 2) {
          values.value(3, k) += coefficient * a * (a - 1) * power(du, a - 2) * power(dv, b);
          values.value(4, k) += coefficient * a * b * power(du, a - 1) * power(dv, b - 1);
          values.value(5, k) += coefficient * b * (b - 1) * power(du, a) * power(dv, b - 2);
        }
      }
    }
  }
}

AssemblyPattern TriangularQuadrature::assembly_pattern() const {
  const int local = max_local_count_;
  std::vector<int> element_nodes;
  element_nodes.reserve(static_cast<size_t>(element_count()) * static_cast<size_t>(local));
  for (const auto& functions : element_functions_) {
    for (int a = 0; a < local; ++a) {
      element_nodes.push_back(a < static_cast<int>(functions.size())
                                  ? functions[static_cast<size_t>(a)]
                                  : functions.front());
    }
  }
  return make_assembly_pattern(basis_->function_count(), local, element_nodes);
}

}  // namespace dnurbs
