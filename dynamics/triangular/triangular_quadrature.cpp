#include "dynamics/triangular/triangular_quadrature.h"

#include <algorithm>

#include "core/error.h"
#include "nurbs/triangular_polynomial_cells.h"

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
  const TriangleRule& base = interior_positive_dunavant_rule(degree);
  const TriangleRule rule = subdivided_rule(base, std::max(1, subdivisions));
  const Triangulation& triangulation = basis_->triangulation();
  const int per_triangle = basis_->functions_per_triangle();
  TriangularBasisValues values;
  entry_begin_.push_back(0);
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
    // The sub-triangles integrated: the s^2 of the composite rule, or the fans of the
    // polynomial cells (each convex cell split from its first corner).
    std::vector<std::array<Eigen::Vector2d, 3>> pieces;
    if (subdivisions > 0) {
      pieces.push_back(
          {triangulation.corner(e, 0), triangulation.corner(e, 1), triangulation.corner(e, 2)});
    } else {
      for (const ConvexPolygon& cell : polynomial_cells(*basis_, e)) {
        for (size_t k = 1; k + 1 < cell.size(); ++k) {
          pieces.push_back({cell[0], cell[k], cell[k + 1]});
        }
      }
    }
    const TriangleRule& used = subdivisions > 0 ? rule : base;
    for (const auto& piece : pieces) {
      const double area = 0.5 * signed_double_area(piece[0], piece[1], piece[2]);
      for (int g = 0; g < used.point_count(); ++g) {
        add_point(e,
                  used.barycentric(g, 0) * piece[0] + used.barycentric(g, 1) * piece[1] +
                      used.barycentric(g, 2) * piece[2],
                  area * used.weights[g], values);
      }
    }
  }
  element_begin_.push_back(static_cast<int>(parameter_.size()));
}

void TriangularQuadrature::add_point(int e, const Eigen::Vector2d& u, double weight,
                                     TriangularBasisValues& values) {
  parameter_.push_back(u);
  weight_.push_back(weight);
  element_of_.push_back(e);
  // Cache the non-zero B-splines (the list of evaluate_in_triangle is the element's list).
  basis_->evaluate_in_triangle(e, u, order_, values);
  for (int a = 0; a < values.count; ++a) {
    if (values.value.col(a).cwiseAbs().maxCoeff() == 0.0) {
      continue;
    }
    entry_local_.push_back(a);
    for (int r = 0; r < 6; ++r) {
      entry_value_.push_back(values.value(r, a));
    }
  }
  entry_begin_.push_back(static_cast<int>(entry_local_.size()));
}

void TriangularQuadrature::basis_at(int point, TriangularBasisValues& values,
                                    std::vector<int>& local) const {
  const int begin = entry_begin_[static_cast<size_t>(point)];
  const int end = entry_begin_[static_cast<size_t>(point) + 1];
  const auto& functions = element_functions_[static_cast<size_t>(element_of(point))];
  values.triangle = element_of(point);
  values.count = end - begin;
  values.function.resize(static_cast<size_t>(values.count));
  local.resize(static_cast<size_t>(values.count));
  values.value.resize(6, values.count);
  for (int k = 0; k < values.count; ++k) {
    const auto entry = static_cast<size_t>(begin) + static_cast<size_t>(k);
    const int a = entry_local_[entry];
    local[static_cast<size_t>(k)] = a;
    values.function[static_cast<size_t>(k)] = functions[static_cast<size_t>(a)];
    values.value.col(k) = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&entry_value_[6 * entry]);
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
