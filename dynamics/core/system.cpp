#include "dnurbs/dynamics/core/system.h"

#include <atomic>
#include <cmath>
#include <utility>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// Revisions are unique across every System of the process, so that an integrator that steps
// several systems never takes one's layout and factorization for another's.
std::uint64_t next_revision() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

namespace {

// Block-diagonal stack of square sparse matrices (each block's columns are sorted, so entries
// are inserted in order into a matrix reserved once).
SparseMatrix block_diagonal(const std::vector<const SparseMatrix*>& blocks) {
  Eigen::Index size = 0;
  for (const SparseMatrix* block : blocks) {
    size += block->rows();
  }
  SparseMatrix result(size, size);
  Eigen::VectorXi sizes(size);
  Eigen::Index offset = 0;
  for (const SparseMatrix* block : blocks) {
    for (Eigen::Index j = 0; j < block->cols(); ++j) {
      sizes[offset + j] = static_cast<int>(block->col(j).nonZeros());
    }
    offset += block->cols();
  }
  result.reserve(sizes);
  offset = 0;
  for (const SparseMatrix* block : blocks) {
    for (Eigen::Index j = 0; j < block->outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(*block, j); it; ++it) {
        result.insert(offset + it.row(), offset + j) = it.value();
      }
    }
    offset += block->cols();
  }
  result.makeCompressed();
  return result;
}

void check_finite(ConstVectorRef x, const char* what) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      throw make_error(what, " entry ", i, " is ", x[i]);
    }
  }
}

}  // namespace

System::System(const System& other)
    : coordinate_offsets_(other.coordinate_offsets_),
      velocity_offsets_(other.velocity_offsets_),
      forces_(other.forces_),
      springs_(other.springs_),
      fixed_(other.fixed_),
      coordinates_(other.coordinates_),
      velocities_(other.velocities_),
      accelerations_(other.accelerations_),
      accelerations_valid_(other.accelerations_valid_),
      time_(other.time_),
      revision_(other.revision_),
      constant_(other.constant_),
      kronecker_(other.kronecker_),
      constant_matrices_(other.constant_matrices_),
      scalar_matrices_(other.scalar_matrices_) {
  models_.reserve(other.models_.size());
  for (const auto& model : other.models_) {
    models_.push_back(model->clone());
  }
}

System& System::operator=(const System& other) {
  if (this != &other) {
    System copy(other);
    *this = std::move(copy);
  }
  return *this;
}

int System::add_model(const Model& model) {
  const int coordinate_offset = coordinate_count();
  const int velocity_offset = velocity_count();
  models_.push_back(model.clone());
  coordinate_offsets_.push_back(coordinate_offset);
  velocity_offsets_.push_back(velocity_offset);
  const Eigen::VectorXd q = model.initial_coordinates();
  coordinates_.conservativeResize(coordinate_offset + model.coordinate_count());
  coordinates_.tail(model.coordinate_count()) = q;
  velocities_.conservativeResize(velocity_offset + model.velocity_count());
  velocities_.tail(model.velocity_count()).setZero();
  accelerations_.setZero(velocity_count());
  accelerations_valid_ = false;
  for (const int index : model.fixed_coordinates()) {
    fixed_.push_back(velocity_offset + index);
  }
  revision_ = next_revision();
  rebuild_caches();
  return model_count() - 1;
}

void System::rebuild_caches() {
  constant_ = true;
  kronecker_ = 3;
  for (const auto& model : models_) {
    constant_ = constant_ && model->matrices_are_constant();
    if (model->kronecker_block_size() != 3) {
      kronecker_ = 0;
    }
  }
  constant_matrices_ = ModelMatrices{};
  scalar_matrices_ = ModelMatrices{};
  if (!constant_) {
    kronecker_ = 0;
    return;
  }
  std::vector<const SparseMatrix*> mass;
  std::vector<const SparseMatrix*> damping;
  std::vector<const SparseMatrix*> stiffness;
  for (const auto& model : models_) {
    const ModelMatrices* matrices = model->constant_matrices();
    mass.push_back(&matrices->mass);
    damping.push_back(&matrices->damping);
    stiffness.push_back(&matrices->stiffness);
  }
  if (models_.size() == 1) {
    constant_matrices_ = *models_.front()->constant_matrices();
  } else {
    constant_matrices_.mass = block_diagonal(mass);
    constant_matrices_.damping = block_diagonal(damping);
    constant_matrices_.stiffness = block_diagonal(stiffness);
  }
  if (kronecker_ == 3) {
    mass.clear();
    damping.clear();
    stiffness.clear();
    for (const auto& model : models_) {
      const ModelMatrices* matrices = model->scalar_matrices();
      mass.push_back(&matrices->mass);
      damping.push_back(&matrices->damping);
      stiffness.push_back(&matrices->stiffness);
    }
    scalar_matrices_.mass = block_diagonal(mass);
    scalar_matrices_.damping = block_diagonal(damping);
    scalar_matrices_.stiffness = block_diagonal(stiffness);
  }
}

void System::fix_point(int model, int point) {
  check_index(model);
  models_[static_cast<size_t>(model)]->fix_point(point);
  refresh_fixed();
}

bool System::set_material_parameters(int i, ConstVectorRef values) {
  check_index(i);
  Model& m = *models_[static_cast<size_t>(i)];
  const Eigen::VectorXd current = m.material_parameters();
  if (current.size() == values.size() && current == values) {
    return false;
  }
  const bool matrices = m.set_material_parameters(values);
  accelerations_valid_ = false;
  if (matrices) {
    revision_ = next_revision();
    rebuild_caches();
  }
  return true;
}

void System::fix_border(int model) {
  check_index(model);
  models_[static_cast<size_t>(model)]->fix_border();
  refresh_fixed();
}

int System::flow_rest_shapes(double dt) {
  int yielded = 0;
  for (int i = 0; i < model_count(); ++i) {
    Model& m = *models_[static_cast<size_t>(i)];
    yielded += m.flow_rest_shape(
        coordinates_.segment(coordinate_offsets_[static_cast<size_t>(i)], m.coordinate_count()),
        dt);
  }
  return yielded;
}

Eigen::VectorXd System::flowing_rest_coordinates() const {
  std::vector<Eigen::VectorXd> parts;
  Eigen::Index size = 0;
  for (const auto& m : models_) {
    parts.push_back(m->flowing_rest_coordinates());
    size += parts.back().size();
  }
  Eigen::VectorXd stacked(size);
  Eigen::Index offset = 0;
  for (const auto& part : parts) {
    stacked.segment(offset, part.size()) = part;
    offset += part.size();
  }
  return stacked;
}

void System::restore_flowing_rest_coordinates(ConstVectorRef rest) {
  const Eigen::Index expected = flowing_rest_coordinates().size();
  if (rest.size() != expected) {
    throw make_error("rest coordinates: expected ", expected,
                     " (the models whose rest shape yields), got ", rest.size());
  }
  Eigen::Index offset = 0;
  for (const auto& m : models_) {
    const Eigen::Index size = m->flowing_rest_coordinates().size();
    if (size > 0) {
      m->restore_flowing_rest_coordinates(rest.segment(offset, size));
      offset += size;
    }
  }
}

void System::refresh_fixed() {
  fixed_.clear();
  for (int i = 0; i < model_count(); ++i) {
    for (const int index : models_[static_cast<size_t>(i)]->fixed_coordinates()) {
      fixed_.push_back(velocity_offsets_[static_cast<size_t>(i)] + index);
      velocities_[velocity_offsets_[static_cast<size_t>(i)] + index] = 0.0;
    }
  }
  accelerations_valid_ = false;
  revision_ = next_revision();
}

void System::check_index(int i) const {
  if (i < 0 || i >= model_count()) {
    throw make_error("model index ", i, " is outside 0..", model_count() - 1);
  }
}

const Model& System::model(int i) const {
  check_index(i);
  return *models_[static_cast<size_t>(i)];
}

int System::coordinate_offset(int i) const {
  check_index(i);
  return coordinate_offsets_[static_cast<size_t>(i)];
}

int System::velocity_offset(int i) const {
  check_index(i);
  return velocity_offsets_[static_cast<size_t>(i)];
}

Eigen::VectorXd::ConstSegmentReturnType System::coordinates(int i) const {
  return coordinates_.segment(coordinate_offset(i), model(i).coordinate_count());
}

Eigen::VectorXd::ConstSegmentReturnType System::velocities(int i) const {
  return velocities_.segment(velocity_offset(i), model(i).velocity_count());
}

void System::set_coordinates(int i, ConstVectorRef q) {
  if (q.size() != model(i).coordinate_count()) {
    throw make_error("model ", i, " has ", model(i).coordinate_count(), " coordinates, got ",
                     q.size());
  }
  check_finite(q, "coordinate");
  coordinates_.segment(coordinate_offset(i), q.size()) = q;
  accelerations_valid_ = false;
}

void System::set_velocities(int i, ConstVectorRef qd) {
  if (qd.size() != model(i).velocity_count()) {
    throw make_error("model ", i, " has ", model(i).velocity_count(), " velocities, got ",
                     qd.size());
  }
  check_finite(qd, "velocity");
  velocities_.segment(velocity_offset(i), qd.size()) = qd;
  for (const int index : fixed_) {
    velocities_[index] = 0.0;
  }
  accelerations_valid_ = false;
}

void System::set_state(ConstVectorRef q, ConstVectorRef qd, double time) {
  if (q.size() != coordinate_count() || qd.size() != velocity_count()) {
    throw make_error("state sizes ", q.size(), " and ", qd.size(), " differ from the system's ",
                     coordinate_count(), " and ", velocity_count());
  }
  check_finite(q, "coordinate");
  check_finite(qd, "velocity");
  set_time(time);
  coordinates_ = q;
  velocities_ = qd;
  for (const int index : fixed_) {
    velocities_[index] = 0.0;
  }
  accelerations_valid_ = false;
}

void System::set_time(double time) {
  if (!std::isfinite(time)) {
    throw make_error("time ", time, " is not finite");
  }
  time_ = time;
}

void System::set_accelerations(ConstVectorRef a) {
  if (a.size() != velocity_count()) {
    throw make_error("acceleration has ", a.size(), " entries, the system ", velocity_count());
  }
  accelerations_ = a;
  accelerations_valid_ = true;
}

void System::commit_step(Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& a, double time) {
  if (q.size() != coordinate_count() || qd.size() != velocity_count() ||
      a.size() != velocity_count()) {
    throw make_error("committed state sizes ", q.size(), ", ", qd.size(), ", ", a.size(),
                     " differ from the system's ", coordinate_count(), " and ", velocity_count());
  }
  const double dt = time - time_;
  coordinates_.swap(q);
  velocities_.swap(qd);
  accelerations_.swap(a);
  accelerations_valid_ = true;
  time_ = time;
  if (dt > 0.0) {
    flow_rest_shapes(dt);  // plastic rest shapes yield towards the new state
  }
}

Eigen::Vector3d System::position(int i, const Eigen::Vector2d& u) const {
  return model(i).position(coordinates(i), u);
}

int System::add_force(int i, Force force) {
  check_index(i);
  if (!force) {
    throw make_error("empty force added to model ", i);
  }
  forces_.emplace_back(i, std::move(force));
  return static_cast<int>(forces_.size()) - 1;
}

void System::add_applied_force(int index, double time, ConstVectorRef q, ConstVectorRef qd,
                               VectorRef force) const {
  if (index < 0 || index >= force_count()) {
    throw make_error("force index ", index, " is outside 0..", force_count() - 1);
  }
  const auto& [i, applied] = forces_[static_cast<size_t>(index)];
  const Model& m = *models_[static_cast<size_t>(i)];
  const int cq = coordinate_offsets_[static_cast<size_t>(i)];
  const int cv = velocity_offsets_[static_cast<size_t>(i)];
  applied(m, time, q.segment(cq, m.coordinate_count()), qd.segment(cv, m.velocity_count()),
          force.segment(cv, m.velocity_count()));
}

void System::add_applied_forces(double time, ConstVectorRef q, ConstVectorRef qd, VectorRef force,
                                bool include_springs) const {
  for (int index = 0; index < force_count(); ++index) {
    add_applied_force(index, time, q, qd, force);
  }
  if (include_springs) {
    add_spring_forces(time, q, force);
  }
}

int System::add_spring(int i, Spring spring) {
  check_index(i);
  if (!spring) {
    throw make_error("empty spring added to model ", i);
  }
  springs_.emplace_back(i, std::move(spring));
  return static_cast<int>(springs_.size()) - 1;
}

bool System::has_spring(int id) const {
  return id >= 0 && id < spring_id_count() && springs_[static_cast<size_t>(id)].first >= 0;
}

int System::spring_model(int id) const {
  if (!has_spring(id)) {
    throw make_error("there is no spring ", id, " (", spring_id_count(), " ids so far)");
  }
  return springs_[static_cast<size_t>(id)].first;
}

void System::set_spring(int id, Spring spring) {
  spring_model(id);  // checks the id
  if (!spring) {
    throw make_error("empty spring given to spring ", id);
  }
  springs_[static_cast<size_t>(id)].second = std::move(spring);
}

void System::remove_spring(int id) {
  spring_model(id);  // checks the id
  springs_[static_cast<size_t>(id)] = {-1, Spring()};
}

SpringState System::spring_state(int id, double time) const {
  spring_model(id);  // checks the id
  SpringState state = springs_[static_cast<size_t>(id)].second(time);
  check_spring_state(state, id, time);
  return state;
}

// f = L(u)^T k (target - x(u)) (Terzopoulos 2003, below eq. 1.26), model by model.
void System::add_spring_forces(double time, ConstVectorRef q, VectorRef force) const {
  for (int id = 0; id < spring_id_count(); ++id) {
    if (!has_spring(id)) {
      continue;
    }
    const SpringState state = spring_state(id, time);
    if (state.stiffness != 0.0) {
      add_spring_force(springs_[static_cast<size_t>(id)].first, state, q, force);
    }
  }
}

void System::add_spring_force(int i, const SpringState& state, ConstVectorRef q,
                              VectorRef force) const {
  const Model& m = model(i);
  const auto q_model = q.segment(coordinate_offsets_[static_cast<size_t>(i)], m.coordinate_count());
  const Eigen::Vector3d pull =
      state.stiffness * (state.target - m.position(q_model, state.parameter));
  m.add_point_force(q_model, state.parameter, pull,
                    force.segment(velocity_offsets_[static_cast<size_t>(i)], m.velocity_count()));
}

double System::spring_energy(double time, ConstVectorRef q) const {
  double energy = 0.0;
  for (int id = 0; id < spring_id_count(); ++id) {
    if (!has_spring(id)) {
      continue;
    }
    const SpringState state = spring_state(id, time);
    const int i = springs_[static_cast<size_t>(id)].first;
    const Model& m = *models_[static_cast<size_t>(i)];
    const auto q_model =
        q.segment(coordinate_offsets_[static_cast<size_t>(i)], m.coordinate_count());
    energy +=
        0.5 * state.stiffness * (m.position(q_model, state.parameter) - state.target).squaredNorm();
  }
  return energy;
}

void System::add_internal_forces(ConstVectorRef q, VectorRef force) const {
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    m.add_internal_force(q.segment(coordinate_offsets_[i], m.coordinate_count()),
                         force.segment(velocity_offsets_[i], m.velocity_count()));
  }
}

void System::add_inertial_forces(ConstVectorRef q, ConstVectorRef qd, VectorRef force) const {
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    m.add_inertial_force(q.segment(coordinate_offsets_[i], m.coordinate_count()),
                         qd.segment(velocity_offsets_[i], m.velocity_count()),
                         force.segment(velocity_offsets_[i], m.velocity_count()));
  }
}

bool System::matrices_are_constant() const {
  return constant_;
}

const ModelMatrices* System::constant_matrices() const {
  return constant_ ? &constant_matrices_ : nullptr;
}

void System::assemble_matrices(ConstVectorRef q, ModelMatrices& matrices) const {
  if (constant_) {
    matrices = constant_matrices_;
    return;
  }
  if (models_.size() == 1) {
    models_.front()->assemble_matrices(q, matrices);
    return;
  }
  std::vector<ModelMatrices> parts(models_.size());
  std::vector<const SparseMatrix*> mass;
  std::vector<const SparseMatrix*> damping;
  std::vector<const SparseMatrix*> stiffness;
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    m.assemble_matrices(q.segment(coordinate_offsets_[i], m.coordinate_count()), parts[i]);
    mass.push_back(&parts[i].mass);
    damping.push_back(&parts[i].damping);
    stiffness.push_back(&parts[i].stiffness);
  }
  matrices.mass = block_diagonal(mass);
  matrices.damping = block_diagonal(damping);
  matrices.stiffness = block_diagonal(stiffness);
}

int System::kronecker_block_size() const {
  return kronecker_;
}

const ModelMatrices* System::scalar_matrices() const {
  return kronecker_ != 0 ? &scalar_matrices_ : nullptr;
}

void System::advance_coordinates(ConstVectorRef q, ConstVectorRef dv,
                                 Eigen::Ref<Eigen::VectorXd> q_out) const {
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    m.advance_coordinates(q.segment(coordinate_offsets_[i], m.coordinate_count()),
                          dv.segment(velocity_offsets_[i], m.velocity_count()),
                          q_out.segment(coordinate_offsets_[i], m.coordinate_count()));
  }
}

void System::project_state(Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd) const {
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    m.project_state(q.segment(coordinate_offsets_[i], m.coordinate_count()),
                    qd.segment(velocity_offsets_[i], m.velocity_count()));
  }
}

double System::kinetic_energy() const {
  double energy = 0.0;
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    energy += m.kinetic_energy(coordinates_.segment(coordinate_offsets_[i], m.coordinate_count()),
                               velocities_.segment(velocity_offsets_[i], m.velocity_count()));
  }
  return energy;
}

double System::potential_energy() const {
  double energy = 0.0;
  for (size_t i = 0; i < models_.size(); ++i) {
    const Model& m = *models_[i];
    energy +=
        m.potential_energy(coordinates_.segment(coordinate_offsets_[i], m.coordinate_count()));
  }
  return energy;
}

}  // namespace dnurbs
