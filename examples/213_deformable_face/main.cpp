// The deformable, retargetable face (Goldenstein et al. 2005, sections 3.4 and 6): the geometry
// images of three individuals (examples/faces, written by scripts/generate_face.py) animated by
// the same deformation fields over the normalized (u, v) square: at rest, smiling (zygomatic and
// risorius, both sides), raising both brows (frontalis), raising the left brow only (the split
// fields), and opening the jaw. Each face is tessellated adaptively until the surface error of
// every triangle is within 0.25 mm (the contour error criterion, section 5.2.3, eq 7) and written
// as <individual>_<expression>.obj (millimetres, y up, the face looking along +z).
// Usage: example_213_deformable_face [OUTPUT_DIRECTORY [INDIVIDUALS]] (default deformable_face/,
// all 3 individuals).

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "dnurbs/io/mesh_export.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/deformable_face.h"
#include "dnurbs/surface/restricted_mesh.h"
#include "examples/example_arguments.h"

int main(int argc, char** argv) {
  using namespace dnurbs;
  const auto out = examples::output_directory(argc, argv, "deformable_face");
  const std::vector<std::string> individuals = {"ada", "ben", "cleo"};
  const int count = std::min(examples::count_argument(argc, argv, 3, "the number of individuals"),
                             static_cast<int>(individuals.size()));

  // The expressions as q (FaceParameter order: frontalis L/R, zygomatic L/R, risorius L/R, jaw)
  auto expression = [](std::initializer_list<std::pair<FaceParameter, double>> values) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(kFaceParameterCount);
    for (const auto& [parameter, value] : values) {
      q(static_cast<int>(parameter)) = value;
    }
    return q;
  };
  const std::vector<std::pair<std::string, Eigen::VectorXd>> expressions = {
      {"rest", expression({})},
      {"smile", expression({{FaceParameter::kZygomaticLeft, 1.0},
                            {FaceParameter::kZygomaticRight, 1.0},
                            {FaceParameter::kRisoriusLeft, 0.4},
                            {FaceParameter::kRisoriusRight, 0.4}})},
      {"brow_raise",
       expression({{FaceParameter::kFrontalisLeft, 1.0}, {FaceParameter::kFrontalisRight, 1.0}})},
      {"left_brow_raise", expression({{FaceParameter::kFrontalisLeft, 1.0}})},
      {"jaw_open", expression({{FaceParameter::kJawOpen, 1.0}})},
  };
  const double max_error = 0.25;  // mm

  for (int index = 0; index < count; ++index) {
    const std::string& individual = individuals[static_cast<size_t>(index)];
    const DeformableFace face =
        DeformableFace::read(std::string(DNURBS_FACES_DIR) + "/face_" + individual + ".gim");
    for (const auto& [name, q] : expressions) {
      const ParametricSurface surface = face.surface(q);
      RestrictedMesh mesh(surface, 16, 16);
      mesh.refine(surface_error_criterion(surface, max_error));
      const SurfaceError error = mesh_surface_error(mesh, kDefaultErrorSampleOrder);
      const std::string file = individual + "_" + name;
      export_mesh(mesh.to_triangle_mesh(file), out / (file + ".obj"));
      std::printf("%-16s %-16s %5d triangles, max error %.3f mm (bound %.2f)\n", individual.c_str(),
                  name.c_str(), mesh.triangle_count(), error.max, max_error);
    }
    // What the fields do, the same on every individual (retargeting): how far the jaw opening
    // moves the upper lip away from the lower one at the midline, and how far a brow rises
    const double band = 0.006;  // the mouth band's half width in v (surface/deformable_face.cpp)
    const Eigen::VectorXd& rest = expressions[0].second;
    auto displacement = [&](const Eigen::VectorXd& q, double u, double v) {
      return Eigen::Vector3d(face.point(q, u, v) - face.point(rest, u, v));
    };
    const Eigen::VectorXd& jaw = expressions[4].second;
    const double lips_part = (displacement(jaw, 0.5, FaceLayout::kMouthV + band) -
                              displacement(jaw, 0.5, FaceLayout::kMouthV - band))
                                 .norm();
    const double brow_u = 0.5 + 0.5 * (FaceLayout::kBrowInner + FaceLayout::kBrowOuter);
    const double brow_rise = displacement(expressions[3].second, brow_u, FaceLayout::kBrowV).norm();
    std::printf("%-16s jaw open: lips part by %.2f mm; left brow rises %.2f mm\n",
                individual.c_str(), lips_part, brow_rise);
  }
  std::printf("faces in %s\n", out.string().c_str());
  return 0;
}
