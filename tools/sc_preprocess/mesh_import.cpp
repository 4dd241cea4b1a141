// SPDX-License-Identifier: MIT
#include "mesh_import.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

namespace sc::tools {

namespace {

constexpr unsigned kImportFlags = aiProcess_JoinIdenticalVertices | aiProcess_Triangulate;
/// Node trees deeper than this are refused: the walk is recursive, and no mesh file
/// of OBJ, STL or PLY makes more than two levels.
constexpr int kMaxNodeDepth = 256;

sc::Status invalid(const std::string& what) { return {sc::ErrorCode::InvalidArgument, what}; }

/// Collects the triangles of every mesh under a node, in the file's frame; equal
/// positions become one vertex (files often split vertices by normal or group).
/// Nothing assimp hands over is trusted: indices and mesh references are checked,
/// since a reader bug on a malformed file must not become one here.
class Merger {
 public:
  explicit Merger(const aiScene& scene) : scene_(scene) {}

  sc::Status add(const aiNode& node, const aiMatrix4x4& parent, int depth) {
    if (depth > kMaxNodeDepth) return invalid("node tree deeper than 256 levels");
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
      const unsigned id = node.mMeshes[m];
      if (id >= scene_.mNumMeshes || scene_.mMeshes[id] == nullptr)
        return invalid("a node refers to a missing mesh");
      if (sc::Status s = addMesh(*scene_.mMeshes[id], transform); !s.ok()) return s;
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) {
      if (node.mChildren[c] == nullptr) return invalid("a node has a missing child");
      if (sc::Status s = add(*node.mChildren[c], transform, depth + 1); !s.ok()) return s;
    }
    return sc::Status::success();
  }
  ImportedMesh take() { return {std::move(mesh_), skipped_}; }

 private:
  sc::Status addMesh(const aiMesh& mesh, const aiMatrix4x4& transform) {
    std::vector<int> index(mesh.mNumVertices, -1);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {  // points and lines
        ++skipped_;
        continue;
      }
      sc::Tri tri;
      for (int k = 0; k < 3; ++k) {
        const unsigned v = face.mIndices[k];
        if (v >= mesh.mNumVertices || mesh.mVertices == nullptr)
          return invalid("a face refers to a missing vertex");
        if (index[v] < 0) index[v] = vertexOf(transform * mesh.mVertices[v]);
        if (index[v] < 0) return invalid("a vertex position is not finite");
        tri[k] = index[v];
      }
      mesh_.triangles.push_back(tri);
    }
    return sc::Status::success();
  }
  /// The welded vertex at `p`; -1 when `p` is not finite.
  int vertexOf(const aiVector3D& p) {
    const std::array<double, 3> key{p.x, p.y, p.z};
    for (double c : key)
      if (!std::isfinite(c)) return -1;
    const auto [it, inserted] = welded_.emplace(key, static_cast<int>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.emplace_back(key[0], key[1], key[2]);
    return it->second;
  }

  const aiScene& scene_;
  sc::MeshData mesh_;
  std::map<std::array<double, 3>, int> welded_;
  int skipped_ = 0;
};

/// The merged mesh of an imported scene; `source` names the input in messages.
sc::Result<ImportedMesh> merge(const aiScene* scene, const Assimp::Importer& importer,
                               const std::string& source) {
  if (scene == nullptr || scene->mRootNode == nullptr)
    return invalid("cannot read '" + source + "': " + importer.GetErrorString());
  Merger merger(*scene);
  if (sc::Status s = merger.add(*scene->mRootNode, aiMatrix4x4(), 0); !s.ok())
    return invalid("'" + source + "': " + s.message());
  ImportedMesh out = merger.take();
  if (out.mesh.triangles.empty()) return invalid("'" + source + "' has no triangles");
  return out;
}

/// Leaves only the reader of `extension` registered: bytes in memory are read as that
/// format or not at all (otherwise assimp would try every reader whose signature
/// check passes). False when no reader has that extension.
bool keepOnlyReaderOf(Assimp::Importer& importer, const char* extension) {
  const Assimp::BaseImporter* wanted = importer.GetImporter(extension);
  if (wanted == nullptr) return false;
  for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    // Unregistering hands the reader back to us; the importer deletes the rest.
    if (reader != wanted && importer.UnregisterLoader(reader) == aiReturn_SUCCESS) delete reader;
  }
  return true;
}

/// The lower-case extension of `path`, without the dot ("" when it has none).
std::string extensionOf(const std::string& path) {
  const std::size_t dot = path.find_last_of("./");
  if (dot == std::string::npos || path[dot] != '.') return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// Files above this are refused unread (the largest meshes used here are a few MB).
constexpr off_t kMaxFileBytes = off_t{1} << 30;

/// Opens `path` without blocking (a FIFO would wait for a writer) and keeps it only
/// when it is a regular file; its size in `size`.
sc::Status openRegular(const std::string& path, int& fd, off_t& size) {
  fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return invalid("cannot open '" + path + "': " + std::strerror(errno));
  struct stat st {};
  std::string problem;
  if (::fstat(fd, &st) != 0)
    problem = std::strerror(errno);
  else if (!S_ISREG(st.st_mode))
    problem = "not a regular file";
  else if (st.st_size > kMaxFileBytes)
    problem = "larger than 1 GiB";
  if (problem.empty()) {
    size = st.st_size;
    return sc::Status::success();
  }
  ::close(fd);
  return invalid("cannot read '" + path + "': " + problem);
}

/// The bytes of the regular file at `path`.
sc::Status readRegularFile(const std::string& path, std::vector<char>& bytes) {
  int fd = -1;
  off_t size = 0;
  if (sc::Status s = openRegular(path, fd, size); !s.ok()) return s;
  bytes.resize(static_cast<std::size_t>(size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (done != bytes.size()) return invalid("cannot read '" + path + "': short read");
  return sc::Status::success();
}

}  // namespace

sc::Result<ImportedMesh> importMeshFile(const std::string& path) {
  const std::string extension = extensionOf(path);
  if (hasStrictReader(extension)) {
    std::vector<char> bytes;
    if (sc::Status s = readRegularFile(path, bytes); !s.ok()) return s;
    return parseStrict(bytes.data(), bytes.size(), extension, path);
  }
  int fd = -1;
  off_t size = 0;
  if (sc::Status s = openRegular(path, fd, size); !s.ok()) return s;
  ::close(fd);
  Assimp::Importer importer;
  return merge(importer.ReadFile(path, kImportFlags), importer, path);
}

sc::Result<ImportedMesh> importMeshMemory(const void* data, std::size_t size, const char* format) {
  Assimp::Importer importer;
  const std::string source = std::string("<memory>.") + format;
  if (data == nullptr || size == 0) return invalid("'" + source + "' is empty");
  if (hasStrictReader(format))
    return parseStrict(static_cast<const char*>(data), size, format, source);
  if (!keepOnlyReaderOf(importer, format)) return invalid("no reader for '" + source + "'");
  return merge(importer.ReadFileFromMemory(data, size, kImportFlags, format), importer, source);
}

}  // namespace sc::tools
