#include "dnurbs/dynamics/integrators/implicit_springs.h"

#include <algorithm>

#include "dnurbs/core/error.h"

namespace dnurbs {

int BlockSprings::term_count() const {
  int count = 0;
  for (const Entry& entry : entries_) {
    count += entry.term_count;
  }
  return count;
}

// The rank-one terms of one spring at q: u = N(u) on the free nodes (node block; rows 1 and 2
// of L checked to repeat row 0 on the y and z coordinates), or the three rows of L on the free
// velocities; zero entries (basis functions that vanish at a knot) are left out.
void BlockSprings::evaluate(const System& system, const Layout& layout, ConstVectorRef q,
                            const SpringState& state) {
  const Model& model = system.model(layout.model);
  const SparseMatrix jacobian = model.position_jacobian(q, state.parameter);
  gap_ = state.target - model.position(q, state.parameter);
  for (Term& term : scratch_) {
    term.rows.clear();
    term.values.clear();
  }
  scratch_count_ = layout.kronecker ? 1 : 3;
  for (Eigen::Index j = 0; j < jacobian.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(jacobian, j); it; ++it) {
      if (it.value() == 0.0) {
        continue;
      }
      const auto column = static_cast<int>(j);
      const auto row = static_cast<int>(it.row());
      if (!layout.kronecker) {
        const int free = layout.free->free_index(column);
        if (free >= 0) {
          scratch_[static_cast<size_t>(row)].rows.push_back(free);
          scratch_[static_cast<size_t>(row)].values.push_back(it.value());
        }
        continue;
      }
      // L = N^T (x) I_3: entry (r, 3 node + r) = N_node
      if (column % 3 != row || (row > 0 && jacobian.coeff(0, column - row) != it.value())) {
        throw make_error("model ", layout.model,
                         " declares the S (x) I_3 layout but its position Jacobian at u = (",
                         state.parameter.x(), ", ", state.parameter.y(), ") has entry (", row, ", ",
                         column, ") = ", it.value(), ", not N^T (x) I_3");
      }
      const int free = layout.free->free_index(column / 3);
      if (row == 0 && free >= 0) {
        scratch_[0].rows.push_back(free);
        scratch_[0].values.push_back(it.value());
      }
    }
  }
}

bool BlockSprings::update(const System& system, const Layout& layout, double time, ConstVectorRef q,
                          double position_coefficient, bool target_form, LowRankUpdate* solver) {
  const Model& model = system.model(layout.model);
  const auto q_model = q.segment(layout.coordinate_offset, model.coordinate_count());
  bool changed = false;
  for (Entry& entry : entries_) {
    entry.seen = false;
  }
  std::array<double, 3> pull{};
  for (int id = 0; id < system.spring_id_count(); ++id) {
    if (!system.has_spring(id) || system.spring_model(id) != layout.model) {
      continue;
    }
    const SpringState state = system.spring_state(id, time);
    if (state.stiffness == 0.0) {
      continue;  // off: its terms are removed below
    }
    evaluate(system, layout, q_model, state);
    auto found = std::find_if(entries_.begin(), entries_.end(),
                              [id](const Entry& entry) { return entry.spring == id; });
    if (found == entries_.end()) {
      entries_.emplace_back();
      found = entries_.end() - 1;
      found->spring = id;
    }
    Entry& entry = *found;
    entry.seen = true;
    const double stiffness = position_coefficient * state.stiffness;
    for (int r = 0; r < scratch_count_; ++r) {
      Term& term = entry.terms[static_cast<size_t>(r)];
      const Term& fresh = scratch_[static_cast<size_t>(r)];
      // Target form: t = (target - x(q_iter, u)) / c_K, so that the pull c_K k u t^T is
      // k L^T (target - x); x, y, z on a node block, coordinate r of the gap on a velocity one.
      std::span<const double> target;
      if (target_form) {
        if (layout.kronecker) {
          for (int c = 0; c < 3; ++c) {
            pull[static_cast<size_t>(c)] = gap_[c] / position_coefficient;
          }
          target = std::span<const double>(pull.data(), 3);
        } else {
          pull[0] = gap_[r] / position_coefficient;
          target = std::span<const double>(pull.data(), 1);
        }
      }
      if (term.id < 0 || term.rows != fresh.rows || term.values != fresh.values ||
          entry.stiffness != stiffness) {
        term.rows.assign(fresh.rows.begin(), fresh.rows.end());
        term.values.assign(fresh.values.begin(), fresh.values.end());
        if (solver == nullptr) {
          term.id = 0;  // summed into the matrix (add_to_matrix): no solver id
        } else if (term.id < 0) {
          term.id = solver->add_term(term.rows, term.values, stiffness, target);
        } else {
          solver->move_term(term.id, term.rows, term.values, stiffness, target);
        }
        changed = true;
      } else if (solver != nullptr) {
        solver->set_target(term.id, target);
      }
    }
    entry.stiffness = stiffness;
    entry.term_count = scratch_count_;
  }
  // Springs removed or switched off
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->seen) {
      ++it;
      continue;
    }
    if (solver != nullptr) {
      for (int r = 0; r < it->term_count; ++r) {
        solver->remove_term(it->terms[static_cast<size_t>(r)].id);
      }
    }
    it = entries_.erase(it);
    changed = true;
  }
  return changed;
}

void BlockSprings::add_to_matrix(SparseMatrix& matrix) const {
  for (const Entry& entry : entries_) {
    for (int r = 0; r < entry.term_count; ++r) {
      const Term& term = entry.terms[static_cast<size_t>(r)];
      for (size_t a = 0; a < term.rows.size(); ++a) {
        for (size_t b = 0; b < term.rows.size(); ++b) {
          matrix.coeffRef(term.rows[a], term.rows[b]) +=
              entry.stiffness * term.values[a] * term.values[b];
        }
      }
    }
  }
  matrix.makeCompressed();
}

}  // namespace dnurbs
