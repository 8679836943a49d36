// bench/face_mesh: the three refinement criteria of Goldenstein et al. 2005 (section 5.2) on the
// face, in the form of their figure 2 and section 6 (bench/face_mesh/README.md).
//
// The hand-crafted base mesh in (u, v) (examples/faces/face_base_uv.obj, figure 2a) is made
// compliant (make_compliant, figure 2b) and refined over the neutral face of a geometry image
// (DeformableFace, q = 0) by unconditional refinement (figure 2c), the normals criterion of
// section 5.2.2 (figure 2d) and the surface contour error criterion of section 5.2.3 (figure 2e).
// One error bound for all: the unconditional mesh's largest error (eq 7) and its mean error (eq 6,
// area-weighted), sampled at barycentric order 16. Each adaptive criterion gets its loosest
// setting whose mesh is within both, so no mesh is worse than the unconditional one on average or
// at its worst: the normals criterion the largest angle (0.8 rad times powers of 0.8), the error
// criterion the largest threshold on a triangle's mean error (8 times the unconditional mesh's
// mean times powers of 0.8) with the largest error bounded by the unconditional mesh's. The same
// with the largest error alone is listed too.
// Refinement times (a RestrictedMesh built on the compliant base and refined, sampling included,
// as the paper's "refinement of the base mesh") are medians of interleaved runs
// (bench/common/interleaved_medians.h), reported as ratios to the unconditional time.
//
// face_refinement_bench [--quick] [--out DIR] [--face GEOMETRY_IMAGE] [--base OBJ]

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bench/common/bench_arguments.h"
#include "bench/common/interleaved_medians.h"
#include "dnurbs/core/error.h"
#include "dnurbs/surface/adaptive_tessellation.h"
#include "dnurbs/surface/compliant_triangulation.h"
#include "dnurbs/surface/deformable_face.h"
#include "dnurbs/surface/restricted_mesh.h"

namespace dnurbs::bench {
namespace {

constexpr int kErrorOrder = 16;  // barycentric sampling of the reported errors
constexpr int kMaxLevel = 12;    // depth limit of the adaptive criteria (edges / 64)

struct Options {
  std::string face = DNURBS_EXAMPLES_DIR "/faces/face_ada.gim";
  std::string base = DNURBS_EXAMPLES_DIR "/faces/face_base_uv.obj";
  std::string out;
  double budget = 1.0;
  int min_repeats = 7;
};

// The "v u v 0" and "f a b c" lines of an OBJ in the (u, v) plane.
std::pair<Eigen::MatrixX2d, Eigen::MatrixX3i> read_uv_obj(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) {
    throw make_error("face_refinement_bench: cannot open '", path, "'");
  }
  std::vector<Eigen::Vector2d> uv;
  std::vector<Eigen::Vector3i> triangles;
  std::string line;
  for (int number = 1; std::getline(stream, line); ++number) {
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "v") {
      Eigen::Vector2d p;
      fields >> p.x() >> p.y();
      uv.push_back(p);
    } else if (kind == "f") {
      Eigen::Vector3i t;
      fields >> t.x() >> t.y() >> t.z();
      triangles.emplace_back(t - Eigen::Vector3i::Ones());
    } else {
      continue;
    }
    if (!fields) {
      throw make_error("face_refinement_bench: '", path, "' line ", number, " is not ", kind,
                       " with its numbers");
    }
  }
  Eigen::MatrixX2d uv_matrix(static_cast<Eigen::Index>(uv.size()), 2);
  for (size_t k = 0; k < uv.size(); ++k) {
    uv_matrix.row(static_cast<Eigen::Index>(k)) = uv[k].transpose();
  }
  Eigen::MatrixX3i triangle_matrix(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t k = 0; k < triangles.size(); ++k) {
    triangle_matrix.row(static_cast<Eigen::Index>(k)) = triangles[k].transpose();
  }
  return {uv_matrix, triangle_matrix};
}

// One criterion: the refinement of the compliant base that step() repeats.
class RefinementSetup {
 public:
  RefinementSetup(const ParametricSurface& surface, const BlockTriangulation& base,
                  RefinementTest test, int max_level)
      : surface_(surface), base_(base), test_(std::move(test)), max_level_(max_level) {}
  RestrictedMesh refined() const {
    RestrictedMesh mesh(surface_, base_);
    mesh.refine(test_, max_level_);
    return mesh;
  }
  void step() { triangles_ += refined().triangle_count(); }

 private:
  const ParametricSurface& surface_;
  const BlockTriangulation& base_;
  RefinementTest test_;
  int max_level_;
  long triangles_ = 0;  // keeps the timed work observable
};

struct Row {
  std::string mesh;
  std::string setting;
  int vertices = 0;
  int triangles = 0;
  int paper_vertices = 0;
  int paper_triangles = 0;
  double max_error = 0.0;
  double mean_error = 0.0;
  int timed = -1;  // index into the timed setups, or -1
};

int run(const Options& options) {
  const auto [uv, triangles] = read_uv_obj(options.base);
  const DeformableFace face = DeformableFace::read(options.face);
  const ParametricSurface surface = face.surface(Eigen::VectorXd::Zero(face.parameter_count()));
  const CompliantTriangulation compliant = make_compliant(uv, triangles);
  const BlockTriangulation& base = compliant.mesh;

  std::vector<Row> rows;
  rows.push_back({"base (figure 2a)", "hand-crafted Delaunay", static_cast<int>(uv.rows()),
                  static_cast<int>(triangles.rows()), 113, 195, 0.0, 0.0, -1});
  std::ostringstream made;
  made << compliant.paired_blocks << " blocks + " << compliant.boundary_splits
       << " boundary splits";
  const SurfaceError base_error = mesh_surface_error(RestrictedMesh(surface, base), kErrorOrder);
  rows.push_back({"compliant (figure 2b)", made.str(), static_cast<int>(base.uv.rows()),
                  static_cast<int>(base.triangles.rows()), 233, 414, base_error.max,
                  base_error.mean, -1});

  std::vector<std::unique_ptr<RefinementSetup>> setups;
  auto add = [&](Row row, RefinementTest test, int max_level) {
    setups.push_back(std::make_unique<RefinementSetup>(surface, base, std::move(test), max_level));
    const RestrictedMesh mesh = setups.back()->refined();
    row.vertices = mesh.parameter_vertex_count();
    row.triangles = mesh.triangle_count();
    const SurfaceError error = mesh_surface_error(mesh, kErrorOrder);
    row.max_error = error.max;
    row.mean_error = error.mean;
    row.timed = static_cast<int>(setups.size()) - 1;
    rows.push_back(row);
    return error;
  };
  // Goldenstein et al. 2005, section 5.2.1: the paper's unconditional mesh has 16 times the
  // triangles of its compliant base (6624 / 414), four bisections; three are listed too
  add({"unconditional depth 3", "depth 3", 0, 0, 0, 0, 0.0, 0.0, -1}, depth_criterion(3), 3);
  const SurfaceError bound =
      add({"unconditional (figure 2c)", "depth 4", 0, 0, 3416, 6624, 0.0, 0.0, -1},
          depth_criterion(4), 4);
  const int unconditional = static_cast<int>(setups.size()) - 1;
  // Is a mesh within the unconditional mesh's largest error (and, if `mean`, its mean error)?
  auto within = [&](const RestrictedMesh& mesh, bool mean) {
    const SurfaceError error = mesh_surface_error(mesh, kErrorOrder);
    return error.max <= bound.max && (!mean || error.mean <= bound.mean);
  };
  auto refined = [&](const RefinementTest& test) {
    return RefinementSetup(surface, base, test, kMaxLevel).refined();
  };
  int normals_index = -1;
  int error_index = -1;
  for (const bool mean : {true, false}) {
    const char* matched = mean ? "largest and mean error" : "largest error";
    // Section 5.2.2: the largest angle (ridge and end points alike) whose mesh is within
    double angle = 0.8;
    while (angle > 1e-3 && !within(refined(normals_criterion(angle, angle)), mean)) {
      angle *= 0.8;
    }
    std::ostringstream normals;
    normals << "angle " << angle << " rad (" << matched << ")";
    add({mean ? "normals (figure 2d)" : "normals (largest error only)", normals.str(), 0, 0,
         mean ? 1917 : 0, mean ? 3674 : 0, 0.0, 0.0, -1},
        normals_criterion(angle, angle), kMaxLevel);
    normals_index = mean ? static_cast<int>(setups.size()) - 1 : normals_index;
    // Section 5.2.3: a triangle's largest error (eq 7) above the unconditional mesh's, or its
    // mean error (eq 6) above a threshold, the largest (8 times the unconditional mesh's mean
    // times powers of 0.8) whose mesh is within; without the mean, the largest error alone
    double mean_error = mean ? 8.0 * bound.mean : std::numeric_limits<double>::infinity();
    while (mean && mean_error > 1e-3 * bound.mean &&
           !within(refined(surface_error_criterion(surface, bound.max, mean_error)), mean)) {
      mean_error *= 0.8;
    }
    std::ostringstream error;
    error << "max " << bound.max << " mm";
    if (mean) {
      error << " and mean " << mean_error << " mm";
    }
    error << " (" << matched << ")";
    add({mean ? "surface error (figure 2e)" : "surface error (largest error only)", error.str(), 0,
         0, mean ? 1351 : 0, mean ? 2567 : 0, 0.0, 0.0, -1},
        surface_error_criterion(surface, bound.max, mean_error), kMaxLevel);
    error_index = mean ? static_cast<int>(setups.size()) - 1 : error_index;
  }

  const std::vector<double> seconds =
      interleaved_medians(setups, options.budget, options.min_repeats, 1000);
  std::ofstream csv;
  if (!options.out.empty()) {
    std::filesystem::create_directories(options.out);
    csv.open(std::filesystem::path(options.out) / "face_refinement.csv");
    csv << "mesh,setting,vertices,triangles,paper_vertices,paper_triangles,"
           "vertices_over_base,paper_vertices_over_base,triangles_over_base,"
           "paper_triangles_over_base,max_error_mm,mean_error_mm,seconds,time_over_unconditional\n";
  }
  std::printf("%-34s %9s %9s %9s %9s %12s %12s %12s\n", "mesh", "vertices", "triangles", "paper V",
              "paper T", "max err [mm]", "mean err", "t / uncond.");
  for (const Row& row : rows) {
    const double time_ratio = row.timed >= 0 ? seconds[static_cast<size_t>(row.timed)] /
                                                   seconds[static_cast<size_t>(unconditional)]
                                             : 0.0;
    std::printf("%-34s %9d %9d %9d %9d %12.4g %12.4g %12.3g  %s\n", row.mesh.c_str(), row.vertices,
                row.triangles, row.paper_vertices, row.paper_triangles, row.max_error,
                row.mean_error, time_ratio, row.setting.c_str());
    if (csv.is_open()) {
      auto ratio = [](int a, int b) { return b > 0 ? static_cast<double>(a) / b : 0.0; };
      csv << row.mesh << "," << row.setting << "," << row.vertices << "," << row.triangles << ","
          << row.paper_vertices << "," << row.paper_triangles << ","
          << ratio(row.vertices, rows[0].vertices) << ","
          << ratio(row.paper_vertices, rows[0].paper_vertices) << ","
          << ratio(row.triangles, rows[0].triangles) << ","
          << ratio(row.paper_triangles, rows[0].paper_triangles) << "," << row.max_error << ","
          << row.mean_error << ","
          << (row.timed >= 0 ? seconds[static_cast<size_t>(row.timed)] : 0.0) << "," << time_ratio
          << "\n";
    }
  }
  std::printf(
      "normals / unconditional time %.3g (paper 0.7 s / 0.7 s = 1), error-based / "
      "unconditional %.3g (paper 2.5 s / 0.7 s = 3.57); unconditional %.4g s\n",
      seconds[static_cast<size_t>(normals_index)] / seconds[static_cast<size_t>(unconditional)],
      seconds[static_cast<size_t>(error_index)] / seconds[static_cast<size_t>(unconditional)],
      seconds[static_cast<size_t>(unconditional)]);
  return 0;
}

}  // namespace
}  // namespace dnurbs::bench

int main(int argc, char** argv) {
  dnurbs::bench::Options options;
  const auto unknown = dnurbs::bench::read_bench_arguments(
      argc, argv,
      [&] {
        options.budget = 0.01;
        options.min_repeats = 1;
      },
      {{"--out", [&](const char* value) { options.out = value; }},
       {"--face", [&](const char* value) { options.face = value; }},
       {"--base", [&](const char* value) { options.base = value; }}});
  if (unknown) {
    std::cerr << "face_refinement_bench: unknown argument '" << *unknown
              << "' (usage: face_refinement_bench [--quick] [--out DIR] [--face GEOMETRY_IMAGE] "
                 "[--base OBJ])\n";
    return 2;
  }
  try {
    return dnurbs::bench::run(options);
  } catch (const dnurbs::Error& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
}
