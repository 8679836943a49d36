#include "dnurbs/constraints/constraint.h"

#include <cmath>

#include "dnurbs/core/error.h"

namespace dnurbs {

ModelView model_view(const System& system, int model, ConstVectorRef q, ConstVectorRef qd) {
  const Model& m = system.model(model);
  return ModelView{m, q.segment(system.coordinate_offset(model), m.coordinate_count()),
                   qd.segment(system.velocity_offset(model), m.velocity_count()),
                   system.velocity_offset(model)};
}

void append_jacobian_block(const SparseMatrix& block, int row_offset, int velocity_offset,
                           double scale, ConstraintRows& rows) {
  for (int column = 0; column < block.outerSize(); ++column) {
    for (SparseMatrix::InnerIterator it(block, column); it; ++it) {
      rows.jacobian->emplace_back(rows.row + row_offset + static_cast<int>(it.row()),
                                  velocity_offset + column, scale * it.value());
    }
  }
}

void check_material_point(const System& system, int model, const Eigen::Vector2d& u,
                          const char* what) {
  if (model < 0 || model >= system.model_count()) {
    throw make_error(what, ": model index ", model, " is out of range (the system has ",
                     system.model_count(), " models)");
  }
  if (!std::isfinite(u.x()) || !std::isfinite(u.y())) {
    throw make_error(what, ": material point (", u.x(), ", ", u.y(), ") is not finite");
  }
  // Evaluating the position checks the parameter against the model's domain.
  system.model(model).position(system.coordinates(model), u);
}

}  // namespace dnurbs
