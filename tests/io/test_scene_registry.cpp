// The scene registry: the built-in types are listed in order, and a model type added from outside
// the library (the example of docs/adding-a-model.md, a point mass) parses, writes back, builds
// and runs through the same paths as the built-in ones.

#include "dnurbs/io/scene_registry.h"

#include <memory>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "dnurbs/dynamics/core/model_tessellation.h"
#include "dnurbs/io/scene.h"
#include "dnurbs/io/scene_model_keys.h"
#include "dnurbs/io/scene_simulation.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

// The example model: one point of mass m, q = x (3 coordinates), x(u) = q for every u.
// M = m I_3 (constant), no damping, no stiffness; a distributed force density f gives m-weighted
// f (its "parametric measure" is 1, like a curve over [0, 1]).
class PointMass final : public Model {
 public:
  PointMass(const Eigen::Vector3d& position, double mass) : position_(position) {
    if (!(mass > 0.0) || !std::isfinite(mass)) {
      throw make_error("point mass ", mass, " must be positive and finite");
    }
    SparseMatrix identity(3, 3);
    identity.setIdentity();
    matrices_.mass = mass * identity;
    matrices_.damping = SparseMatrix(3, 3);
    matrices_.stiffness = SparseMatrix(3, 3);
  }
  std::unique_ptr<Model> clone() const override { return std::make_unique<PointMass>(*this); }
  int coordinate_count() const override { return 3; }
  Eigen::VectorXd initial_coordinates() const override { return position_; }
  int parametric_dimension() const override { return 1; }
  Eigen::Vector3d position(ConstVectorRef q, const Eigen::Vector2d& /*u*/) const override {
    return q.head<3>();
  }
  SparseMatrix position_jacobian(ConstVectorRef /*q*/,
                                 const Eigen::Vector2d& /*u*/) const override {
    SparseMatrix identity(3, 3);
    identity.setIdentity();
    return identity;
  }
  bool matrices_are_constant() const override { return true; }
  const ModelMatrices* constant_matrices() const override { return &matrices_; }
  void assemble_matrices(ConstVectorRef /*q*/, ModelMatrices& matrices) const override {
    matrices = matrices_;
  }
  void add_distributed_force(ConstVectorRef q, const ForceDensity& density,
                             VectorRef force) const override {
    MaterialSample sample;
    sample.position = q.head<3>();
    sample.mass_density = matrices_.mass.coeff(0, 0);
    force.head<3>() += density(sample);
  }
  ParameterDomain parameter_domain(ConstVectorRef /*q*/) const override { return {}; }
  // A point is meshed as a small tetrahedron around it.
  TriangleMesh tessellate(ConstVectorRef q, const ModelTessellationSettings& /*settings*/,
                          std::string name) const override {
    TriangleMesh mesh;
    mesh.name = std::move(name);
    mesh.vertices.resize(4, 3);
    mesh.vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
    mesh.vertices = (0.01 * mesh.vertices).rowwise() + q.head<3>().transpose();
    mesh.triangles.resize(4, 3);
    mesh.triangles << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
    return mesh;
  }

 private:
  Eigen::VectorXd position_;
  ModelMatrices matrices_;
};

// Its scene keys: "position" and "material": {"mass"}.
struct ScenePointMass final : SceneModelSpec {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double mass = 1.0;
  std::unique_ptr<SceneModelSpec> clone() const override {
    return std::make_unique<ScenePointMass>(*this);
  }
  std::string type() const override { return "point_mass"; }
  void write(JsonOut& model) const override {
    model["position"] = json_array<3>(position);
    model["material"] = {{"mass", mass}};
  }
  std::unique_ptr<Model> build() const override {
    return std::make_unique<PointMass>(position, mass);
  }
};

std::unique_ptr<SceneModelSpec> read_point_mass_scene(const SceneReader& reader,
                                                      const JsonValue& model,
                                                      const std::string& path) {
  check_model_keys(reader, model, path, "point_mass", {"position"});
  auto spec = std::make_unique<ScenePointMass>();
  if (const JsonValue* position = reader.find(model, "position")) {
    spec->position = reader.point(*position, join_json_path(path, "position"));
  }
  const JsonValue material = model_material(reader, model, path, {"mass"});
  reader.number_key(material, join_json_path(path, "material"), "mass", spec->mass, 0.0, true);
  return spec;
}

// Registered once for the whole test program (the registry is process-wide).
void register_point_mass() {
  static const bool registered = [] {
    register_scene_model_type({"point_mass", &read_point_mass_scene, false, false, false});
    return true;
  }();
  (void)registered;
}

const char* const kFallingPoint = R"json({
  "models": [{"name": "ball", "type": "point_mass", "position": [0, 0, 1],
              "material": {"mass": 2}}],
  "forces": [{"type": "gravity"}],
  "integrator": {"scheme": "newmark", "dt": 0.1},
  "run": {"steps": 10}
})json";

TEST(SceneRegistry, BuiltInTypesAreListedInOrder) {
  const std::vector<const char*> names = type_names(scene_model_types());
  ASSERT_GE(names.size(), 6u);
  EXPECT_STREQ(names[0], "dnurbs_curve");
  EXPECT_STREQ(names[5], "snake");
  EXPECT_EQ(type_names(scene_force_types()).size(), 8u);
  EXPECT_EQ(type_names(scene_constraint_types()).size(), 6u);
}

TEST(SceneRegistry, AModelAddedFromOutsideParsesWritesAndRuns) {
  register_point_mass();
  const Scene scene = parse_scene_json(kFallingPoint, "falling.json");
  EXPECT_EQ(scene_model_type(scene.models[0]), "point_mass");
  EXPECT_TRUE(parse_scene_json(scene_to_json(scene)) == scene);
  SceneSimulation simulation(scene);
  for (int i = 0; i < scene.step_count(); ++i) {
    simulation.step();
  }
  // Newmark's average acceleration is exact for a constant force: z = 1 - g t^2 / 2 at t = 1
  // (rounding of 10 steps: 1e-14)
  const Eigen::Vector3d x = simulation.system().coordinates(0);
  EXPECT_NEAR(x.z(), 1.0 - 0.5 * 9.81, 1e-14);
  EXPECT_NEAR(x.head<2>().norm(), 0.0, 1e-15);
  EXPECT_EQ(simulation.meshes(8).front().vertex_count(), 4);
}

TEST(SceneRegistry, ItsKeysAreCheckedLikeEveryOtherModel) {
  register_point_mass();
  const std::string text = R"({"models": [{"type": "point_mass", "materal": {}}],
                               "run": {"steps": 1}})";
  EXPECT_THAT(testing::error_message([&] { parse_scene_json(text, "bad.json"); }),
              ::testing::HasSubstr("bad.json: models[0].materal: unknown key for a point_mass"));
}

TEST(SceneRegistry, BadRegistrationsAreRefused) {
  EXPECT_THAT(testing::error_message([] {
                register_scene_model_type({"snake", &read_point_mass_scene, false, true, false});
              }),
              ::testing::HasSubstr("\"snake\" is already registered"));
  EXPECT_THAT(testing::error_message([] {
                register_scene_model_type({"Bad Name", &read_point_mass_scene, false, true, false});
              }),
              ::testing::HasSubstr("\"Bad Name\" is not"));
  EXPECT_THAT(testing::error_message([] {
                register_scene_model_type({"no_reader", nullptr, false, true, false});
              }),
              ::testing::HasSubstr("has no reader"));
}

}  // namespace
}  // namespace dnurbs
