#include "dnurbs/io/mesh_export.h"

#include <array>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <assimp/DefaultIOSystem.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/IOStream.hpp>

#include "dnurbs/core/error.h"
#include "dnurbs/core/input_file.h"
#include "dnurbs/io/atomic_write.h"
#include "dnurbs/io/gltf_extensions.h"
#include "dnurbs/io/mesh_up_axis.h"
#include "dnurbs/io/output_path.h"

namespace dnurbs {
namespace {

// A file written for assimp with every failure kept: a short fwrite (a full disk, a file size
// limit), a failed seek, flush or close. Assimp's exporters do not look at the counts its
// streams return, and its default stream ignores fflush and fclose, so a full disk gave a cut
// file and success.
class CheckedWriteStream : public Assimp::IOStream {
 public:
  // `failures` receives the first failure of this file when it is closed (by Close or by the
  // destructor: assimp's exporters delete their streams themselves)
  CheckedWriteStream(std::FILE* file, std::filesystem::path target,
                     std::vector<std::string>* failures)
      : file_(file), target_(std::move(target)), failures_(failures) {}
  CheckedWriteStream(const CheckedWriteStream&) = delete;
  CheckedWriteStream& operator=(const CheckedWriteStream&) = delete;
  ~CheckedWriteStream() override { close(); }

  size_t Read(void* /*buffer*/, size_t /*size*/, size_t /*count*/) override {
    return 0;  // opened for writing only
  }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    const size_t written = file_ != nullptr ? std::fwrite(buffer, size, count, file_) : 0;
    note(written == count);
    return written;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const int whence = origin == aiOrigin_SET   ? SEEK_SET
                       : origin == aiOrigin_CUR ? SEEK_CUR
                                                : SEEK_END;
    const bool ok = file_ != nullptr && offset <= static_cast<size_t>(LONG_MAX) &&
                    std::fseek(file_, static_cast<long>(offset), whence) == 0;
    note(ok);
    return ok ? aiReturn_SUCCESS : aiReturn_FAILURE;
  }
  size_t Tell() const override {
    const long position = file_ != nullptr ? std::ftell(file_) : -1;
    return position < 0 ? 0 : static_cast<size_t>(position);
  }
  size_t FileSize() const override {
    if (file_ == nullptr) {
      return 0;
    }
    const long here = std::ftell(file_);
    std::fseek(file_, 0, SEEK_END);
    const long end = std::ftell(file_);
    std::fseek(file_, here, SEEK_SET);
    return end < 0 ? 0 : static_cast<size_t>(end);
  }
  void Flush() override { note(file_ != nullptr && std::fflush(file_) == 0); }

  // Flushes and closes (once), reporting the first failure of this file, if any.
  void close() {
    if (file_ != nullptr) {
      note(std::fflush(file_) == 0 && std::ferror(file_) == 0);
      note(std::fclose(file_) == 0);
      file_ = nullptr;
      if (!error_.empty()) {
        failures_->push_back(error_);
      }
    }
  }

 private:
  void note(bool ok) {
    if (!ok && error_.empty()) {
      error_ = target_.string() + ": " + (errno != 0 ? std::strerror(errno) : "write failed");
    }
  }

  std::FILE* file_;
  std::filesystem::path target_;
  std::vector<std::string>* failures_;
  std::string error_;  // "<target>: <reason>" of the first failure
};

// An assimp file system that sends every file opened for writing to a temporary sibling
// (through CheckedWriteStream) and remembers where it belongs, so that the export becomes
// visible only by the final renames, and only if every write succeeded. Streams are closed by
// deleting them (DefaultIOSystem::Close, or the exporter itself): CheckedWriteStream's destructor
// flushes, closes and reports, so no stream type needs telling apart here.
class TemporaryFileSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    const std::string open_mode = mode;
    if (open_mode.find_first_of("wa") == std::string::npos) {
      return Assimp::DefaultIOSystem::Open(file, mode);
    }
    const std::filesystem::path target = file;
    const std::filesystem::path temporary = temporary_sibling_path(target);
    std::FILE* handle = std::fopen(temporary.c_str(), "wb");
    if (handle == nullptr) {
      failures_.push_back(target.string() + ": cannot create a temporary file in its directory: " +
                          std::strerror(errno));
      return nullptr;
    }
    files_.emplace_back(temporary, target);
    return new CheckedWriteStream(handle, target, &failures_);
  }

  // (temporary, target) of every file written so far
  const std::vector<std::pair<std::filesystem::path, std::filesystem::path>>& files() const {
    return files_;
  }
  // What failed, in order ("" when nothing did)
  std::string failure() const { return failures_.empty() ? std::string() : failures_.front(); }

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;
  std::vector<std::string> failures_;
};

void remove_temporaries(const TemporaryFileSystem& file_system) {
  for (const auto& [temporary, target] : file_system.files()) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  }
}

// Each format with its file extension (lower case) and assimp's exporter id.
struct MeshFormatName {
  MeshFormat format;
  std::string_view extension;
  const char* assimp_id;
};
constexpr std::array<MeshFormatName, 5> kMeshFormatNames = {{{MeshFormat::kObj, ".obj", "obj"},
                                                             {MeshFormat::kStl, ".stl", "stlb"},
                                                             {MeshFormat::kPly, ".ply", "plyb"},
                                                             {MeshFormat::kGltf, ".gltf", "gltf2"},
                                                             {MeshFormat::kGlb, ".glb", "glb2"}}};

// Diffuse colors given to the meshes in turn
constexpr std::array<std::array<float, 3>, 6> kPalette = {{{0.80f, 0.52f, 0.25f},
                                                           {0.30f, 0.55f, 0.80f},
                                                           {0.45f, 0.70f, 0.35f},
                                                           {0.75f, 0.35f, 0.45f},
                                                           {0.60f, 0.50f, 0.75f},
                                                           {0.70f, 0.70f, 0.70f}}};

void check_mesh(const TriangleMesh& mesh, size_t index) {
  const auto name = "mesh " + std::to_string(index) + " (\"" + mesh.name + "\")";
  if (mesh.normals.rows() != 0 && mesh.normals.rows() != mesh.vertices.rows()) {
    throw make_error(name, " has ", mesh.normals.rows(), " normals for ", mesh.vertices.rows(),
                     " vertices");
  }
  if (mesh.uv.rows() != 0 && mesh.uv.rows() != mesh.vertices.rows()) {
    throw make_error(name, " has ", mesh.uv.rows(), " texture coordinates for ",
                     mesh.vertices.rows(), " vertices");
  }
  if (mesh.triangles.size() > 0 &&
      (mesh.triangles.minCoeff() < 0 || mesh.triangles.maxCoeff() >= mesh.vertices.rows())) {
    throw make_error(name, " has a triangle index outside 0..", mesh.vertices.rows() - 1);
  }
  if (!mesh.vertices.allFinite()) {
    throw make_error(name, " has a non-finite vertex");
  }
  // The files hold single precision (ai_real): a vertex beyond its range would be written as inf
  constexpr double kLargest = std::numeric_limits<ai_real>::max();
  for (Eigen::Index row = 0; row < mesh.vertices.rows(); ++row) {
    if (mesh.vertices.row(row).cwiseAbs().maxCoeff() > kLargest) {
      throw make_error(name, " has vertex ", row, " = (", mesh.vertices(row, 0), ", ",
                       mesh.vertices(row, 1), ", ", mesh.vertices(row, 2),
                       ") beyond the single precision of mesh files (", kLargest, ")");
    }
  }
}

aiMesh* to_assimp_mesh(const TriangleMesh& mesh, unsigned material) {
  auto result = std::make_unique<aiMesh>();
  result->mName = aiString(mesh.name);
  result->mMaterialIndex = material;
  result->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const auto vertex_count = static_cast<unsigned>(mesh.vertices.rows());
  result->mNumVertices = vertex_count;
  result->mVertices = new aiVector3D[vertex_count];
  for (unsigned i = 0; i < vertex_count; ++i) {
    const int row = static_cast<int>(i);
    result->mVertices[i] = aiVector3D(static_cast<ai_real>(mesh.vertices(row, 0)),
                                      static_cast<ai_real>(mesh.vertices(row, 1)),
                                      static_cast<ai_real>(mesh.vertices(row, 2)));
  }
  if (mesh.normals.rows() == mesh.vertices.rows() && vertex_count > 0) {
    result->mNormals = new aiVector3D[vertex_count];
    for (unsigned i = 0; i < vertex_count; ++i) {
      const int row = static_cast<int>(i);
      result->mNormals[i] = aiVector3D(static_cast<ai_real>(mesh.normals(row, 0)),
                                       static_cast<ai_real>(mesh.normals(row, 1)),
                                       static_cast<ai_real>(mesh.normals(row, 2)));
    }
  }
  if (mesh.uv.rows() == mesh.vertices.rows() && vertex_count > 0) {
    result->mTextureCoords[0] = new aiVector3D[vertex_count];
    result->mNumUVComponents[0] = 2;
    for (unsigned i = 0; i < vertex_count; ++i) {
      const int row = static_cast<int>(i);
      result->mTextureCoords[0][i] = aiVector3D(static_cast<ai_real>(mesh.uv(row, 0)),
                                                static_cast<ai_real>(mesh.uv(row, 1)), 0);
    }
  }
  const auto face_count = static_cast<unsigned>(mesh.triangles.rows());
  result->mNumFaces = face_count;
  result->mFaces = new aiFace[face_count];
  for (unsigned f = 0; f < face_count; ++f) {
    aiFace& face = result->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) {
      face.mIndices[k] = static_cast<unsigned>(mesh.triangles(static_cast<int>(f), k));
    }
  }
  return result.release();
}

aiMaterial* make_material(const std::string& name, size_t index) {
  auto material = std::make_unique<aiMaterial>();
  const aiString material_name(name);
  material->AddProperty(&material_name, AI_MATKEY_NAME);
  const auto& rgb = kPalette[index % kPalette.size()];
  const aiColor3D diffuse(rgb[0], rgb[1], rgb[2]);
  material->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
  const aiColor4D base(rgb[0], rgb[1], rgb[2], 1.0f);
  material->AddProperty(&base, 1, AI_MATKEY_BASE_COLOR);
  return material.release();
}

// One mesh, one material and one child node of the root per TriangleMesh; `y_up`: the vertices
// and normals turned into a Y-up file's frame (io/mesh_up_axis.h)
std::unique_ptr<aiScene> build_scene(const std::vector<TriangleMesh>& meshes, bool y_up) {
  auto scene = std::make_unique<aiScene>();
  const auto count = static_cast<unsigned>(meshes.size());
  scene->mRootNode = new aiNode("dnurbs");
  scene->mNumMeshes = count;
  scene->mMeshes = new aiMesh*[count]();
  scene->mNumMaterials = count;
  scene->mMaterials = new aiMaterial*[count]();
  scene->mRootNode->mNumChildren = count;
  scene->mRootNode->mChildren = new aiNode*[count]();
  for (unsigned i = 0; i < count; ++i) {
    const TriangleMesh& mesh = meshes[i];
    // A name goes into the file as text (OBJ "o"/"g"/"usemtl", MTL "newmtl", glTF JSON): only a
    // plain name (io/output_path.h), so that none can break a line or inject records
    const std::string name = output_file_stem(mesh.name, "mesh_" + std::to_string(i));
    TriangleMesh named = y_up ? rotated_mesh(mesh, z_up_to_y_up()) : mesh;
    named.name = name;
    scene->mMeshes[i] = to_assimp_mesh(named, i);
    scene->mMaterials[i] = make_material(name + "_material", i);
    auto* node = new aiNode(name);
    node->mParent = scene->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{i};
    scene->mRootNode->mChildren[i] = node;
  }
  return scene;
}

}  // namespace

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  const std::string extension = lowercase_extension(path);
  for (const MeshFormatName& entry : kMeshFormatNames) {
    if (extension == entry.extension) {
      return entry.format;
    }
  }
  throw make_error(path.string(), ": unknown mesh file extension \"", path.extension().string(),
                   "\" (expected .obj, .stl, .ply, .gltf or .glb)");
}

std::string assimp_format_id(MeshFormat format) {
  for (const MeshFormatName& entry : kMeshFormatNames) {
    if (entry.format == format) {
      return entry.assimp_id;
    }
  }
  throw make_error("unknown mesh format ", static_cast<int>(format));
}

void export_meshes(const std::vector<TriangleMesh>& meshes, const std::filesystem::path& path,
                   UpAxis up) {
  const MeshFormat format = mesh_format_from_path(path);
  if (meshes.empty()) {
    throw make_error(path.string(), ": no meshes to export");
  }
  for (size_t i = 0; i < meshes.size(); ++i) {
    check_mesh(meshes[i], i);
  }
  const std::unique_ptr<aiScene> scene = build_scene(
      meshes, format == MeshFormat::kGltf || format == MeshFormat::kGlb || up == UpAxis::kY);

  Assimp::Exporter exporter;
  auto* file_system = new TemporaryFileSystem;
  exporter.SetIOHandler(file_system);  // the exporter owns it from here on
  const aiReturn status = exporter.Export(scene.get(), assimp_format_id(format), path.string());
  // A write, flush or close that failed (a full disk): nothing is published, the old files stay
  if (const std::string failure = file_system->failure(); !failure.empty()) {
    remove_temporaries(*file_system);
    throw make_error(path.string(), ": the export failed (", failure, "); no file was changed");
  }
  if (status != aiReturn_SUCCESS) {
    remove_temporaries(*file_system);
    const std::string reason = exporter.GetErrorString();
    throw make_error(path.string(), ": assimp could not export the meshes",
                     reason.empty() ? std::string() : ": " + reason);
  }
  // assimp lists glTF extensions the document does not use; keep only the used ones
  if (format == MeshFormat::kGltf || format == MeshFormat::kGlb) {
    for (const auto& [temporary, target] : file_system->files()) {
      const std::string extension = lowercase_extension(target);
      if (extension == ".gltf" || extension == ".glb") {
        try {
          drop_unused_gltf_extensions(temporary, format == MeshFormat::kGlb);
        } catch (const Error&) {
          remove_temporaries(*file_system);
          throw;
        }
      }
    }
  }
  // Publish every written file by renaming it; on failure remove the rest
  for (const auto& [temporary, target] : file_system->files()) {
    std::error_code error;
    std::filesystem::rename(temporary, target, error);
    if (error) {
      remove_temporaries(*file_system);
      throw make_error(target.string(),
                       ": cannot rename the exported temporary file to it: ", error.message());
    }
  }
}

void export_mesh(const TriangleMesh& mesh, const std::filesystem::path& path) {
  export_meshes({mesh}, path);
}

}  // namespace dnurbs
