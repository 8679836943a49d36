#include "dnurbs/io/scene_spec.h"

namespace dnurbs {

void SceneModelSpec::run_fit(const Eigen::MatrixX3d& /*points*/) {
  throw make_error("a ", type(), " model has no \"fit\"");
}

}  // namespace dnurbs
