#include "dnurbs/io/models/superquadric_scene.h"

#include <cmath>

#include <Eigen/Geometry>

#include "dnurbs/design/superquadric_fitting.h"
#include "dnurbs/io/json_messages.h"
#include "dnurbs/io/scene_model_keys.h"

namespace dnurbs {
namespace {

constexpr const char* kShapeKeys[] = {"a",  "a1", "a2", "a3", "e1",  "e2", "t1",
                                      "t2", "b1", "b2", "b3", "tau", "sx", "sy"};

// The "parts" keyword of a set of parts (the scene knows the three presets).
const char* parts_name(const DeformableSuperquadricParts& parts) {
  if (parts == DeformableSuperquadricParts::rigid()) {
    return "rigid";
  }
  return parts == DeformableSuperquadricParts::global() ? "global" : "full";
}

DeformableSuperquadricParts parts_of(const std::string& name) {
  return name == "rigid"    ? DeformableSuperquadricParts::rigid()
         : name == "global" ? DeformableSuperquadricParts::global()
                            : DeformableSuperquadricParts::full();
}

void read_shape_parameters(const SceneReader& reader, const JsonValue& shape,
                           const std::string& path, SuperquadricShapeParameters& parameters) {
  reader.object(shape, path,
                {kShapeKeys[0], kShapeKeys[1], kShapeKeys[2], kShapeKeys[3], kShapeKeys[4],
                 kShapeKeys[5], kShapeKeys[6], kShapeKeys[7], kShapeKeys[8], kShapeKeys[9],
                 kShapeKeys[10], kShapeKeys[11], kShapeKeys[12], kShapeKeys[13]});
  for (int k = 0; k < 14; ++k) {
    double& x = parameters(k);
    if (k < 4) {
      reader.number_key(shape, path, kShapeKeys[k], x, 0.0, true);
    } else if (k < 6) {
      reader.number_key(shape, path, kShapeKeys[k], x, 0.1, false);
      if (x > 4.0) {
        reader.fail(join_json_path(path, kShapeKeys[k]),
                    "expected a squareness in 0.1..4, got " + format_json_number(x));
      }
    } else {
      reader.number_key(shape, path, kShapeKeys[k], x);
    }
  }
}

void read_pose_and_mesh(const SceneReader& reader, const JsonValue& model, const std::string& path,
                        SceneSuperquadric& spec) {
  if (const JsonValue* shape = reader.find(model, "shape")) {
    read_shape_parameters(reader, *shape, join_json_path(path, "shape"), spec.shape);
  }
  if (const JsonValue* centre = reader.find(model, "centre")) {
    spec.centre = reader.point(*centre, join_json_path(path, "centre"));
  }
  if (const JsonValue* orientation = reader.find(model, "orientation")) {
    spec.orientation = reader.vector<4>(*orientation, join_json_path(path, "orientation"),
                                        "a quaternion [w, x, y, z]");
    if (std::abs(spec.orientation.norm() - 1.0) > 1e-6) {
      reader.fail(join_json_path(path, "orientation"),
                  "expected a unit quaternion [w, x, y, z], got one of norm " +
                      format_json_number(spec.orientation.norm()));
    }
  }
  if (const JsonValue* parts = reader.find(model, "parts")) {
    spec.settings.parts =
        parts_of(reader.choice(*parts, join_json_path(path, "parts"), {"rigid", "global", "full"}));
  }
  if (const JsonValue* cells = reader.find(model, "mesh_cells")) {
    const std::string cells_path = join_json_path(path, "mesh_cells");
    if (!cells->is_array() || cells->size() != 2) {
      reader.fail(cells_path, "expected [cells_u, cells_v], got " + describe_json_value(*cells));
    }
    spec.settings.mesh_cells_u =
        reader.integer((*cells)[0], json_index_path(cells_path, 0), 2, 1024);
    spec.settings.mesh_cells_v =
        reader.integer((*cells)[1], json_index_path(cells_path, 1), 3, 1024);
  }
  reader.integer_key(model, path, "quadrature_points", spec.settings.quadrature_points, 1, 16);
  reader.number_key(model, path, "regularization", spec.settings.regularization, 0.0, false);
}

void read_material(const SceneReader& reader, const JsonValue& model, const std::string& path,
                   DeformableSuperquadricSettings& settings) {
  const JsonValue material = model_material(
      reader, model, path,
      {"mass_density", "damping_alpha", "damping_beta", "shape_stiffness", "local_stiffness"});
  const std::string material_path = join_json_path(path, "material");
  reader.number_key(material, material_path, "mass_density", settings.mass_density, 0.0, true);
  reader.number_key(material, material_path, "damping_alpha", settings.damping_alpha, 0.0, false);
  reader.number_key(material, material_path, "damping_beta", settings.damping_beta, 0.0, false);
  double shape_stiffness = settings.shape_stiffness(0);
  reader.number_key(material, material_path, "shape_stiffness", shape_stiffness, 0.0, false);
  settings.shape_stiffness = SuperquadricShapeParameters::Constant(shape_stiffness);
  if (const JsonValue* local = reader.find(material, "local_stiffness")) {
    const Eigen::Vector3d k =
        reader.point(*local, join_json_path(material_path, "local_stiffness"));
    if ((k.array() < 0.0).any()) {
      reader.fail(join_json_path(material_path, "local_stiffness"),
                  "expected [membrane_u, membrane_v, spring] >= 0");
    }
    settings.local_stiffness = {k.x(), k.y(), k.z()};
  }
}

}  // namespace

SceneSuperquadric::SceneSuperquadric()
    : shape(
          (SuperquadricShapeParameters() << 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0).finished()) {
  settings.local_stiffness = {1.0, 1.0, 0.0};
}

std::unique_ptr<SceneModelSpec> SceneSuperquadric::clone() const {
  return std::make_unique<SceneSuperquadric>(*this);
}

void SceneSuperquadric::write(JsonOut& model) const {
  if (fit) {
    model["fit"] = fit_json(*fit, false);
  } else {
    JsonOut parameters;
    for (int k = 0; k < 14; ++k) {
      parameters[kShapeKeys[k]] = shape(k);
    }
    model["shape"] = parameters;
    model["centre"] = json_array<3>(centre);
    model["orientation"] = json_array<4>(orientation);
  }
  model["parts"] = parts_name(settings.parts);
  model["mesh_cells"] = {settings.mesh_cells_u, settings.mesh_cells_v};
  model["quadrature_points"] = settings.quadrature_points;
  model["regularization"] = settings.regularization;
  const FeStiffnessCoefficients& local = settings.local_stiffness;
  model["material"] = {{"mass_density", settings.mass_density},
                       {"damping_alpha", settings.damping_alpha},
                       {"damping_beta", settings.damping_beta},
                       {"shape_stiffness", settings.shape_stiffness(0)},
                       {"local_stiffness", json_array<3>(Eigen::Vector3d(
                                               local.membrane_u, local.membrane_v, local.spring))}};
}

std::unique_ptr<Model> SceneSuperquadric::build() const {
  if (pending_fit() != nullptr) {
    throw make_error("the superquadric's \"fit\" has not been run (fit_initial_shapes)");
  }
  const Eigen::Quaterniond rotation(orientation(0), orientation(1), orientation(2), orientation(3));
  return std::make_unique<DeformableSuperquadricModel>(shape, centre, rotation, settings);
}

const SceneFit* SceneSuperquadric::pending_fit() const {
  return fit && !fitted ? &*fit : nullptr;
}

void SceneSuperquadric::run_fit(const Eigen::MatrixX3d& points) {
  SuperquadricFitSettings fit_settings;
  fit_settings.max_evaluations = fit.value().max_evaluations;
  fit_settings.fit_twist = fit.value().twist;
  fit_settings.fit_shear = fit.value().shear;
  fit_settings.fit_bend_shape = fit.value().bend_shape;
  const SuperquadricFitResult result = fit_superquadric(points, fit_settings);
  shape = result.shape;
  centre = result.centre;
  const Eigen::Quaterniond rotation = Eigen::Quaterniond(result.rotation).normalized();
  orientation = Eigen::Vector4d(rotation.w(), rotation.x(), rotation.y(), rotation.z());
  fitted = true;
}

std::optional<std::pair<std::unique_ptr<SceneModelSpec>, std::string>>
SceneSuperquadric::naive_variant() const {
  const std::string name = parts_name(settings.parts);
  if (name == "full") {
    return std::nullopt;
  }
  auto naive = std::make_unique<SceneSuperquadric>(*this);
  naive->settings.parts = DeformableSuperquadricParts::full();
  return std::pair{std::unique_ptr<SceneModelSpec>(std::move(naive)),
                   name + " parts only (naive: rigid, global and local parts)"};
}

std::unique_ptr<SceneModelSpec> read_superquadric_scene(const SceneReader& reader,
                                                        const JsonValue& model,
                                                        const std::string& path) {
  check_model_keys(reader, model, path, "superquadric",
                   {"shape", "centre", "orientation", "fit", "parts", "mesh_cells",
                    "quadrature_points", "regularization"});
  auto spec = std::make_unique<SceneSuperquadric>();
  spec->fit = read_fit(reader, model, path, false, {"shape", "centre", "orientation"});
  read_pose_and_mesh(reader, model, path, *spec);
  read_material(reader, model, path, spec->settings);
  return spec;
}

}  // namespace dnurbs
