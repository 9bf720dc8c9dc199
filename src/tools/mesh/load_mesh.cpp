#include "sphys/tools/load_mesh.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <exception>
#include <new>
#include <sstream>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "io/input_file.h"
#include "read_off.h"
#include "read_ply.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Assimp's own words, except where its validator speaks of its data structures rather than of
// the file.
std::string importer_message(const Assimp::Importer& importer) {
  std::string message = importer.GetErrorString();
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (message.find("mNumMeshes is 0") != std::string::npos) {
    return "no mesh found: not a mesh file, or a corrupt one";
  }
  if (message.find("contains no faces") != std::string::npos) return "the mesh has no triangles";
  return message.empty() ? "the file could not be read as a mesh" : message;
}

// assimp catches every exception a reader throws and reports it as the file's error. Running out
// of memory is no fault of the file and must stay an internal error, so that one is thrown again
// (by the exception itself: the text could as well be the file's own words).
void rethrow_if_out_of_memory(const Assimp::Importer& importer) {
  const std::exception_ptr& caught = importer.GetException();
  if (!caught) return;
  try {
    std::rethrow_exception(caught);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (...) {  // any other failure is the file's, reported with assimp's message
  }
}

bool has_extension(const fs::path& path, std::string_view extension) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == extension;
}

std::string format_point(const aiVector3D& v) {
  std::ostringstream out;
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

void append_triangles(const aiMesh& source, const fs::path& path, TriangleMesh& mesh) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (unsigned i = 0; i < source.mNumVertices; ++i) {
    const aiVector3D& v = source.mVertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      throw Error::in_file(path, "a vertex has a non-finite coordinate " + format_point(v));
    }
    mesh.vertices.emplace_back(v.x, v.y, v.z);
  }
  for (unsigned f = 0; f < source.mNumFaces; ++f) {
    const aiFace& face = source.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines carry no surface
    Triangle t{};
    for (unsigned k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= source.mNumVertices) {
        throw Error::in_file(path, "face " + std::to_string(f + 1) + " refers to vertex " +
                                       std::to_string(face.mIndices[k] + 1) + " of only " +
                                       std::to_string(source.mNumVertices));
      }
      t[k] = base + face.mIndices[k];
    }
    mesh.triangles.push_back(t);
  }
}

TriangleMesh read_with_assimp(const fs::path& path) {
  Assimp::Importer importer;
  // Keep only what a solid needs; ValidateDataStructure turns index errors into read errors.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TEXCOORDS | aiComponent_COLORS |
                                  aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_MATERIALS);
  const aiScene* scene = importer.ReadFile(
      path.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                         aiProcess_RemoveComponent | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    rethrow_if_out_of_memory(importer);
    throw Error::in_file(path, importer_message(importer));
  }
  if (scene->mNumMeshes == 0) {
    throw Error::in_file(path, "no mesh found (not a mesh file, or an unreadable one)");
  }

  TriangleMesh mesh;
  mesh.name = path.string();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) append_triangles(*scene->mMeshes[m], path, mesh);
  return mesh;
}

// Readers of our own for OFF and PLY, whose assimp readers trust the file's counts and indices
// (clamping indices, aborting, or looping for ever); assimp for the rest.
TriangleMesh read_by_extension(const fs::path& path) {
  if (has_extension(path, ".off")) return read_off(path);
  if (has_extension(path, ".ply")) return read_ply(path);
  return read_with_assimp(path);
}

}  // namespace

TriangleMesh load_mesh(const fs::path& path) {
  // Before any reader opens it: assimp would block on a named pipe or read a device for ever.
  if (check_input_file(path, InputKind::kMesh) == 0) throw Error::in_file(path, "file is empty");
  const TriangleMesh mesh = read_by_extension(path);
  if (mesh.triangles.empty()) throw Error::in_file(path, "the mesh has no triangles");
  return weld_vertices(mesh);
}

TriangleMesh weld_vertices(const TriangleMesh& mesh) {
  struct PositionHash {
    std::size_t operator()(const Vec3d& p) const {
      std::size_t h = 0;
      for (int k = 0; k < 3; ++k) {
        const double c = p[k] + 0.0;  // -0.0 and +0.0 are one position
        std::uint64_t bits = 0;
        std::memcpy(&bits, &c, sizeof bits);
        h = (h ^ bits) * 0x100000001b3ULL;
      }
      return h;
    }
  };
  struct PositionEqual {
    bool operator()(const Vec3d& a, const Vec3d& b) const { return a == b; }
  };

  TriangleMesh welded;
  welded.name = mesh.name;
  welded.triangles.reserve(mesh.triangles.size());
  std::unordered_map<Vec3d, std::uint32_t, PositionHash, PositionEqual> index_of;
  index_of.reserve(mesh.vertices.size());
  for (const Triangle& t : mesh.triangles) {
    Triangle w{};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3d& p = mesh.vertices[t[k]];
      const auto [it, inserted] =
          index_of.try_emplace(p, static_cast<std::uint32_t>(welded.vertices.size()));
      if (inserted) welded.vertices.push_back(p);
      w[k] = it->second;
    }
    welded.triangles.push_back(w);
  }
  return welded;
}

}  // namespace sphys::tools
