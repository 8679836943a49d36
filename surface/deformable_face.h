#pragma once
// The deformable, retargetable face of Goldenstein et al. 2005 (sections 3.4 and 6): a face at
// rest given by a geometry image over the normalized (u, v) square (a constant deformation field,
// eq 2), followed by AddVector fields (eq 4) for the frontalis (brow raise), the zygomatic major
// (smile toward the temples), the risorius (lip corners toward the ears), each split into left
// and right halves for asymmetric movement, and the jaw opening. The fields are functions of
// (u, v) only: because (u, v) is normalized across faces, the same fields animate every
// individual (retargeting, section 6).
//
// Frames and units: x points to the face's own left, y up, z out of the face (toward a viewer
// in front of it), in millimetres; u runs from the face's right (u = 0) to its left (u = 1), v
// from under the chin (v = 0) to the top of the forehead (v = 1); the midline is u = 1/2. The
// normal S_u x S_v points out of the face.
//
// Geometry image files (written by scripts/generate_face.py), text:
//   dnurbs-geometry-image 1
//   individual <name>
//   nodes <count_u> <count_v>
//   <x> <y> <z>        count_u * count_v lines, node (i, j) on line i * count_v + j, u outer
// Lines starting with '#' (and blank lines) are comments anywhere. Node (i, j) sits at
// (i / (count_u - 1), j / (count_v - 1)); between nodes the image is interpolated bilinearly
// (SampledVectorField).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "dnurbs/surface/deformation_field.h"
#include "dnurbs/surface/parametric_surface.h"

namespace dnurbs {

/// The canonical (u, v) layout shared by every individual: where the features sit in the
/// normalized square (scripts/generate_face.py places the same features at the same places).
struct FaceLayout {
  static constexpr double kMidline = 0.5;           ///< u of the nose and the chin
  static constexpr double kMouthV = 18.0 / 64;      ///< v of the line where the lips meet
  static constexpr double kMouthHalfWidth = 0.085;  ///< u from the midline to a lip corner
  static constexpr double kNoseTipV = 27.0 / 64;    ///< v of the nose tip (a node of 65 x 65)
  static constexpr double kEyeV = 0.60;             ///< v of the eyes' centres
  static constexpr double kEyeOffset = 0.16;        ///< u from the midline to an eye's centre
  static constexpr double kBrowV = 0.70;            ///< v of the eyebrows
  static constexpr double kBrowInner = 0.08;        ///< u from the midline to a brow's inner end
  static constexpr double kBrowOuter = 0.26;        ///< u from the midline to a brow's outer end
  static constexpr double kChinV = 0.16;            ///< v of the chin's centre
};

/// The parameters of DeformableFace, in the order of q. Each AddVector field k is V_k(u, v)
/// scaled by q_k; q_k = 1 is a full expression (a brow raised by 8 mm, a 10 mm smile pull, an 8 mm
/// risorius pull, a jaw opened by 12 mm at the chin), negative q_k the opposite movement.
enum class FaceParameter {
  kFrontalisLeft,
  kFrontalisRight,
  kZygomaticLeft,
  kZygomaticRight,
  kRisoriusLeft,
  kRisoriusRight,
  kJawOpen,
};
inline constexpr int kFaceParameterCount = 7;

/// The symmetric muscle fields that the left/right pairs split.
enum class FaceMuscle { kFrontalis, kZygomatic, kRisorius };

/// V_k(u, v) of parameter k (3-vector, mm per unit q_k), the same for every individual
/// (Goldenstein et al. 2005, section 3.4). Each field vanishes on the border of the unit square
/// and outside its influence area (compact support) and is continuous; a left field vanishes for
/// u <= 1/2, a right one for u >= 1/2.
Eigen::Vector3d face_vector_field(FaceParameter parameter, double u, double v);

/// The symmetric field of a muscle, mirror-symmetric about the midline (x changes sign): the sum
/// of its left and right halves, which never overlap (so the sum is exact).
Eigen::Vector3d symmetric_face_vector_field(FaceMuscle muscle, double u, double v);

/// A geometry image read from a file (format in the comment at the top of this header).
struct FaceGeometryImage {
  std::string individual;
  SampledVectorField samples;  ///< over the unit square, open in both directions
};

/// Reads a geometry image file. Throws Error naming the file, the line and the bad value: a
/// missing or wrong header, node counts below 2 or above 4097, a line without exactly three
/// finite numbers, too few or too many sample lines.
FaceGeometryImage read_face_geometry_image(const std::string& path);

/// A face: the cascade p(u, v; q) = V_geometry_image(u, v) + sum_k q_k V_k(u, v)
/// (Goldenstein et al. 2005, eqs. 2 and 4) over the unit square. The V_k are
/// face_vector_field, in millimetres of the face's frame and not scaled per individual: every
/// face moves by the same vectors at the same (u, v) (retargeting, section 6).
class DeformableFace {
 public:
  /// The face of a geometry image (retargeting: any individual, the same fields).
  explicit DeformableFace(FaceGeometryImage geometry_image);
  /// Reads the geometry image (read_face_geometry_image; throws Error naming the file).
  static DeformableFace read(const std::string& geometry_image_path);

  /// kFaceParameterCount.
  int parameter_count() const;
  /// frontalis_left, frontalis_right, zygomatic_left, zygomatic_right, risorius_left,
  /// risorius_right, jaw_open (the order of FaceParameter).
  const std::vector<std::string>& parameter_names() const;
  /// The individual's name from the file.
  const std::string& individual() const { return geometry_image_.individual; }
  const SampledVectorField& geometry_image() const { return geometry_image_.samples; }
  /// The cascade: one constant stage (the geometry image), then one AddVector stage per
  /// parameter, stage k + 1 using q_k.
  const DeformationField& field() const { return field_; }
  /// The unit square, open in both directions.
  const ParameterDomain& domain() const { return domain_; }

  /// p(u, v; q), 3-vector. Throws Error unless q has parameter_count() entries.
  Eigen::Vector3d point(const Eigen::VectorXd& q, double u, double v) const;
  /// The deformed face as a surface over domain(), normal S_u x S_v (out of the face). Throws
  /// Error unless q has parameter_count() entries.
  ParametricSurface surface(const Eigen::VectorXd& q) const;

 private:
  void check_parameters(const Eigen::VectorXd& q) const;

  FaceGeometryImage geometry_image_;
  ParameterDomain domain_;
  DeformationField field_;
};

}  // namespace dnurbs
