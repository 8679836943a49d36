#include "dnurbs/sculpt/sculpt_frame.h"

#include <bit>
#include <cstring>

#include "dnurbs/core/error.h"

namespace dnurbs {
namespace {

static_assert(std::endian::native == std::endian::little,
              "sculpt frames are little endian; add byte swapping for this platform");
constexpr char kMagic[4] = {'D', 'N', 'F', '1'};

void put_word(std::string& out, std::uint32_t word) {
  char bytes[4];
  std::memcpy(bytes, &word, 4);
  out.append(bytes, 4);
}

void put_rows(std::string& out, const Eigen::MatrixX3d& rows) {
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const auto value = static_cast<float>(rows(i, k));
      char bytes[4];
      std::memcpy(bytes, &value, 4);
      out.append(bytes, 4);
    }
  }
}

class FrameReader {
 public:
  explicit FrameReader(const std::string& frame) : frame_(frame) {}

  std::uint32_t word() {
    need(4, "a 32-bit word");
    std::uint32_t value = 0;
    std::memcpy(&value, frame_.data() + offset_, 4);
    offset_ += 4;
    return value;
  }

  Eigen::MatrixX3d rows(std::uint32_t count, const char* what) {
    need(static_cast<std::size_t>(count) * 12, what);
    Eigen::MatrixX3d result(count, 3);
    for (std::uint32_t i = 0; i < count; ++i) {
      for (int k = 0; k < 3; ++k) {
        float value = 0.0F;
        std::memcpy(&value, frame_.data() + offset_, 4);
        offset_ += 4;
        result(i, k) = value;
      }
    }
    return result;
  }

  std::size_t offset() const { return offset_; }

 private:
  void need(std::size_t bytes, const char* what) const {
    if (frame_.size() - offset_ < bytes) {
      throw make_error("sculpt frame truncated at byte ", offset_, ": expected ", what, " (", bytes,
                       " bytes), ", frame_.size() - offset_, " left");
    }
  }

  const std::string& frame_;
  std::size_t offset_ = 0;
};

}  // namespace

std::string encode_sculpt_frame(std::uint32_t frame_number,
                                const std::vector<SculptFrameModel>& models) {
  std::size_t bytes = 12;
  for (const SculptFrameModel& model : models) {
    if (model.mesh == nullptr || model.mesh->normals.rows() != model.mesh->vertices.rows()) {
      throw make_error("sculpt frame: model ", model.index, " has ",
                       model.mesh == nullptr ? 0 : model.mesh->normals.rows(), " normals for ",
                       model.mesh == nullptr ? 0 : model.mesh->vertices.rows(), " vertices");
    }
    bytes += 12 + 24 * static_cast<std::size_t>(model.mesh->vertices.rows()) +
             12 * static_cast<std::size_t>(model.control_points.rows());
  }
  std::string out;
  out.reserve(bytes);
  out.append(kMagic, 4);
  put_word(out, frame_number);
  put_word(out, static_cast<std::uint32_t>(models.size()));
  for (const SculptFrameModel& model : models) {
    put_word(out, static_cast<std::uint32_t>(model.index));
    put_word(out, static_cast<std::uint32_t>(model.mesh->vertices.rows()));
    put_word(out, static_cast<std::uint32_t>(model.control_points.rows()));
    put_rows(out, model.mesh->vertices);
    put_rows(out, model.mesh->normals);
    put_rows(out, model.control_points);
  }
  return out;
}

DecodedSculptFrame decode_sculpt_frame(const std::string& frame) {
  if (frame.size() < 4 || std::memcmp(frame.data(), kMagic, 4) != 0) {
    throw make_error("sculpt frame: expected the magic \"DNF1\" at byte 0");
  }
  FrameReader reader(frame);
  reader.word();
  DecodedSculptFrame result;
  result.frame_number = reader.word();
  const std::uint32_t count = reader.word();
  for (std::uint32_t m = 0; m < count; ++m) {
    DecodedSculptFrame::Model model;
    model.index = static_cast<int>(reader.word());
    const std::uint32_t vertices = reader.word();
    const std::uint32_t control_points = reader.word();
    model.positions = reader.rows(vertices, "vertex positions");
    model.normals = reader.rows(vertices, "vertex normals");
    model.control_points = reader.rows(control_points, "control points");
    result.models.push_back(std::move(model));
  }
  if (reader.offset() != frame.size()) {
    throw make_error("sculpt frame: ", frame.size() - reader.offset(),
                     " bytes left after the last model");
  }
  return result;
}

}  // namespace dnurbs
