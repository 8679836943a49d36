#include "dnurbs/io/scene_prescribed.h"

#include <utility>

namespace dnurbs {

bool prescribe_scene_coordinates(const std::vector<SceneModel>& models, System& system,
                                 double time) {
  bool prescribed = false;
  for (size_t i = 0; i < models.size(); ++i) {
    const std::vector<std::pair<int, double>> values = models[i].spec->prescribed_coordinates(time);
    if (values.empty()) {
      continue;
    }
    const int model = static_cast<int>(i);
    Eigen::VectorXd q = system.coordinates(model);
    Eigen::VectorXd qd = system.velocities(model);
    for (const auto& [index, value] : values) {
      q(index) = value;
      qd(index) = 0.0;
    }
    system.set_coordinates(model, q);
    system.set_velocities(model, qd);
    prescribed = true;
  }
  return prescribed;
}

}  // namespace dnurbs
