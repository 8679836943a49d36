#include "dnurbs/surface/deformable_face.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

// The largest node count per direction a geometry image file may declare.
constexpr int kMaxGeometryImageNodes = 4097;

// 1 at x <= 0, (1 - x^2)^2 on [0, 1], 0 beyond: continuous with a continuous derivative at 1,
// and decreasing monotonically from 1 to 0 (the magnitudes of Goldenstein et al. 2005,
// section 3.4, from a maximum at the feature to zero at the border of its influence area).
double falloff(double x) {
  if (x <= 0.0) {
    return 1.0;
  }
  if (x >= 1.0) {
    return 0.0;
  }
  const double y = 1.0 - x * x;
  return y * y;
}

// The influence area of a muscle: the points within an elliptic distance 1 of a segment in
// (u, v), the distance measured after dividing u by radius_u and v by radius_v.
struct Influence {
  Eigen::Vector2d start;
  Eigen::Vector2d end;
  double radius_u = 1.0;
  double radius_v = 1.0;

  // falloff of the scaled distance to the segment: 1 on it, 0 outside the influence area.
  double weight(double u, double v) const {
    const Eigen::Vector2d scale(1.0 / radius_u, 1.0 / radius_v);
    const Eigen::Vector2d a = start.cwiseProduct(scale);
    const Eigen::Vector2d b = end.cwiseProduct(scale);
    const Eigen::Vector2d p = Eigen::Vector2d(u, v).cwiseProduct(scale);
    const Eigen::Vector2d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return falloff((p - a - t * ab).norm());
  }
};

constexpr double kMid = FaceLayout::kMidline;

// The frontalis of the face's left brow (Goldenstein et al. 2005, section 3.4): 8 mm up the
// forehead (tilted back as the forehead slopes) at the brow, falling to zero 0.06 below it (above
// the eye) and 0.2 above it, and 0.07 beyond its ends in u (inside u > 1/2).
Eigen::Vector3d frontalis_left(double u, double v) {
  const double radius_v = v < FaceLayout::kBrowV ? 0.06 : 0.2;
  const Influence brow{{kMid + FaceLayout::kBrowInner, FaceLayout::kBrowV},
                       {kMid + FaceLayout::kBrowOuter, FaceLayout::kBrowV},
                       0.07,
                       radius_v};
  return 8.0 * brow.weight(u, v) * Eigen::Vector3d(0.0, 1.0, -0.25).normalized();
}

// The zygomatic major of the left side: the lip corner and the cheek above it pulled 10 mm toward
// the temple (out, up and back on the face's frame: the temple sits about 35 mm out, 45 mm up
// and 30 mm back from the lip corner).
Eigen::Vector3d zygomatic_left(double u, double v) {
  const Influence muscle{
      {kMid + FaceLayout::kMouthHalfWidth, FaceLayout::kMouthV}, {kMid + 0.17, 0.42}, 0.07, 0.07};
  return 10.0 * muscle.weight(u, v) * Eigen::Vector3d(35.0, 45.0, -30.0).normalized();
}

// The risorius of the left side: the lip corner and the cheek beside it pulled 8 mm toward the
// ear (out and back).
Eigen::Vector3d risorius_left(double u, double v) {
  const Influence muscle{{kMid + FaceLayout::kMouthHalfWidth, FaceLayout::kMouthV},
                         {kMid + 0.18, FaceLayout::kMouthV},
                         0.07,
                         0.06};
  return 8.0 * muscle.weight(u, v) * Eigen::Vector3d(1.0, 0.0, -0.6).normalized();
}

// The mirror image of a left field: V_right(u, v) = diag(-1, 1, 1) V_left(1 - u, v).
Eigen::Vector3d mirrored(Eigen::Vector3d (*left)(double, double), double u, double v) {
  Eigen::Vector3d vector = left(1.0 - u, v);
  vector.x() = -vector.x();
  return vector;
}

// The jaw opening (Goldenstein et al. 2005, section 3.4): the chin moves 12 mm down and back as
// one constant opening area (elliptic radius below 0.45 about (1/2, kChinV)), falling to zero at
// the border of an ellipse of semi-axes 0.24 in u and 0.14 below / 0.2 above the chin. Between
// the lip corners the upper lip does not follow the jaw but rises 3 mm, so the lips part in an
// opening of height m(u) (12 J + 3) mm, m = 1 - t^2 with t the u-distance from the midline over
// the mouth's half width: zero at the corners, largest at the midline (a lens standing for the
// paper's elliptic opening; an exact ellipse sqrt(1 - t^2) has unbounded slope at the corners,
// which no finite refinement resolves). The jump from lower to upper lip is spread over a band
// of half-width 0.006 about the mouth line, pushed 6 mm into the mouth: the opening's inside.
Eigen::Vector3d jaw_open(double u, double v) {
  const double below_chin = v < FaceLayout::kChinV ? 0.14 : 0.2;
  const double radius = std::hypot((u - kMid) / 0.24, (v - FaceLayout::kChinV) / below_chin);
  const double constant_area = 0.45;
  const double jaw = falloff((radius - constant_area) / (1.0 - constant_area));
  const double t = (u - kMid) / FaceLayout::kMouthHalfWidth;
  const double mouth = std::max(0.0, 1.0 - t * t);
  const double s = v - FaceLayout::kMouthV;
  const double band = 0.006;
  const double upper_lip_height = 0.1;  // from the mouth line to the nose's base
  double upper = 0.0;  // 0 below the band, 1 on the upper lip, 0 again at the nose's base
  if (s >= band) {
    upper = falloff((s - band) / (upper_lip_height - band));
  } else if (s > -band) {
    upper = (s + band) / (2.0 * band);
  }
  const double inside = std::abs(s) < band ? 1.0 - (s / band) * (s / band) : 0.0;
  const Eigen::Vector3d jaw_direction = Eigen::Vector3d(0.0, -1.0, -0.35).normalized();
  return 12.0 * jaw * (1.0 - mouth * upper) * jaw_direction +
         mouth * (3.0 * upper * Eigen::Vector3d::UnitY() - 6.0 * inside * Eigen::Vector3d::UnitZ());
}

// The next non-comment line of a geometry image file, or false at its end.
bool next_line(std::istream& in, std::string& line, int& line_number) {
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') {
      return true;
    }
  }
  return false;
}

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> words;
  for (std::string word; stream >> word;) {
    words.push_back(word);
  }
  return words;
}

// The word as a finite double (the whole word), or nullopt.
std::optional<double> parse_finite(const std::string& word) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<int> parse_count(const std::string& word) {
  int value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

Eigen::Vector3d face_vector_field(FaceParameter parameter, double u, double v) {
  switch (parameter) {
    case FaceParameter::kFrontalisLeft:
      return frontalis_left(u, v);
    case FaceParameter::kFrontalisRight:
      return mirrored(frontalis_left, u, v);
    case FaceParameter::kZygomaticLeft:
      return zygomatic_left(u, v);
    case FaceParameter::kZygomaticRight:
      return mirrored(zygomatic_left, u, v);
    case FaceParameter::kRisoriusLeft:
      return risorius_left(u, v);
    case FaceParameter::kRisoriusRight:
      return mirrored(risorius_left, u, v);
    case FaceParameter::kJawOpen:
      return jaw_open(u, v);
  }
  throw make_error("face vector field: parameter ", static_cast<int>(parameter), " is unknown");
}

Eigen::Vector3d symmetric_face_vector_field(FaceMuscle muscle, double u, double v) {
  const auto left = static_cast<FaceParameter>(2 * static_cast<int>(muscle));
  const auto right = static_cast<FaceParameter>(2 * static_cast<int>(muscle) + 1);
  return face_vector_field(left, u, v) + face_vector_field(right, u, v);
}

FaceGeometryImage read_face_geometry_image(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw make_error("geometry image ", path, ": cannot open the file");
  }
  std::string line;
  int line_number = 0;
  auto fail = [&](const auto&... parts) {
    return make_error("geometry image ", path, ", line ", line_number, ": ", parts...);
  };
  // Header: magic and version, individual, node counts
  if (!next_line(in, line, line_number)) {
    throw fail("the file is empty");
  }
  if (split_words(line) != std::vector<std::string>{"dnurbs-geometry-image", "1"}) {
    throw fail("\"", line.substr(0, 60), "\" is not \"dnurbs-geometry-image 1\"");
  }
  std::vector<std::string> words;
  if (!next_line(in, line, line_number) || (words = split_words(line)).size() != 2 ||
      words[0] != "individual") {
    throw fail("expected \"individual <name>\", got \"", line.substr(0, 60), "\"");
  }
  const std::string individual = words[1];
  if (!next_line(in, line, line_number) || (words = split_words(line)).size() != 3 ||
      words[0] != "nodes") {
    throw fail("expected \"nodes <count_u> <count_v>\", got \"", line.substr(0, 60), "\"");
  }
  const std::optional<int> count_u = parse_count(words[1]);
  const std::optional<int> count_v = parse_count(words[2]);
  for (const auto& [count, word] : {std::pair{count_u, words[1]}, std::pair{count_v, words[2]}}) {
    if (!count || *count < 2 || *count > kMaxGeometryImageNodes) {
      throw fail("node count \"", word, "\" is not an integer in [2, ", kMaxGeometryImageNodes,
                 "]");
    }
  }
  // Samples, one node per line
  const Eigen::Index node_count = static_cast<Eigen::Index>(*count_u) * *count_v;
  Eigen::MatrixX3d samples(node_count, 3);
  for (Eigen::Index node = 0; node < node_count; ++node) {
    if (!next_line(in, line, line_number)) {
      throw fail("the file ends after ", node, " of ", node_count, " samples");
    }
    words = split_words(line);
    if (words.size() != 3) {
      throw fail("sample ", node, " has ", words.size(), " values, expected 3");
    }
    for (int axis = 0; axis < 3; ++axis) {
      const std::optional<double> value = parse_finite(words[static_cast<size_t>(axis)]);
      if (!value) {
        throw fail("sample ", node, " value \"", words[static_cast<size_t>(axis)].substr(0, 40),
                   "\" is not a finite number");
      }
      samples(node, axis) = *value;
    }
  }
  if (next_line(in, line, line_number)) {
    throw fail("more than the ", node_count, " samples of ", *count_u, " by ", *count_v, " nodes");
  }
  return {individual, SampledVectorField(ParameterDomain{}, *count_u, *count_v, samples)};
}

DeformableFace::DeformableFace(FaceGeometryImage geometry_image)
    : geometry_image_(std::move(geometry_image)) {
  const ParameterDomain& image_domain = geometry_image_.samples.domain();
  if (image_domain.u_min != 0.0 || image_domain.u_max != 1.0 || image_domain.v_min != 0.0 ||
      image_domain.v_max != 1.0 || image_domain.periodic_u || image_domain.periodic_v) {
    throw make_error("deformable face ", geometry_image_.individual,
                     ": the geometry image is not over the open unit square");
  }
  // Goldenstein et al. 2005, eq. 2: the face at rest is the constant field of the geometry image
  auto image = std::make_shared<const SampledVectorField>(geometry_image_.samples);
  field_.constant([image](double u, double v) { return (*image)(u, v); });
  // eq 4: one AddVector stage per muscle parameter, the same fields for every individual
  for (int k = 0; k < kFaceParameterCount; ++k) {
    const auto parameter = static_cast<FaceParameter>(k);
    field_.add_vector(
        [parameter](double u, double v) { return face_vector_field(parameter, u, v); }, k);
  }
}

DeformableFace DeformableFace::read(const std::string& geometry_image_path) {
  return DeformableFace(read_face_geometry_image(geometry_image_path));
}

int DeformableFace::parameter_count() const {
  return kFaceParameterCount;
}

const std::vector<std::string>& DeformableFace::parameter_names() const {
  static const std::vector<std::string> names = {
      "frontalis_left", "frontalis_right", "zygomatic_left", "zygomatic_right",
      "risorius_left",  "risorius_right",  "jaw_open"};
  return names;
}

void DeformableFace::check_parameters(const Eigen::VectorXd& q) const {
  if (q.size() != kFaceParameterCount) {
    throw make_error("deformable face ", geometry_image_.individual, ": ", q.size(),
                     " parameters, expected ", kFaceParameterCount);
  }
}

Eigen::Vector3d DeformableFace::point(const Eigen::VectorXd& q, double u, double v) const {
  check_parameters(q);
  return field_.apply(q, u, v);
}

ParametricSurface DeformableFace::surface(const Eigen::VectorXd& q) const {
  check_parameters(q);
  return deformation_field_surface(domain_, field_, q, NormalOrientation::kSuCrossSv);
}

}  // namespace dnurbs
