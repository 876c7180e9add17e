#include "casmap/io/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/ply_check.hpp"

// Debian's assimp is built with ASSIMP_BUILD_DEBUG: a failed internal consistency check
// (ai_assert, e.g. "numOut != pMesh->mNumFaces" in TriangulateProcess on a malformed PLY)
// calls this function, whose library version prints and aborts the whole process. This
// definition interposes it (the executable's symbol wins over the shared library's) and throws
// instead; Importer::ReadFile swallows the exception and returns no scene, which becomes an
// InputError below. Found by io/fuzz/mesh_fuzz.
namespace Assimp {
void aiAssertViolation(const char* failed_expression, const char* file, int line);
void aiAssertViolation(const char* failed_expression, const char* file, int line) {
    throw std::runtime_error(std::string("assimp consistency check failed: ") + failed_expression +
                             " (" + file + ":" + std::to_string(line) + ")");
}
}  // namespace Assimp

namespace casmap::io {
namespace {

// Appends the triangles of `node` and its children, with the accumulated node transform.
void AppendNode(const aiScene& scene,
                const aiNode& node,
                const aiMatrix4x4& parent,
                const Eigen::Vector3d& scale,
                core::MeshShape& out) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned int m = 0; m < node.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
        const int base = static_cast<int>(out.vertices.size());
        for (unsigned int v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D p = transform * mesh.mVertices[v];
            out.vertices.emplace_back(static_cast<float>(p.x * scale.x()),
                                      static_cast<float>(p.y * scale.y()),
                                      static_cast<float>(p.z * scale.z()));
        }
        for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) {
                continue;  // points and lines carry no surface
            }
            out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                       base + static_cast<int>(face.mIndices[1]),
                                       base + static_cast<int>(face.mIndices[2]));
        }
    }
    for (unsigned int c = 0; c < node.mNumChildren; ++c) {
        AppendNode(scene, *node.mChildren[c], transform, scale, out);
    }
}

namespace limits = core::limits;

// Binary STL: an 80-byte header, a 32-bit triangle count, 50 bytes per triangle.
void CheckStlHeader(std::string_view head, std::uint64_t file_bytes, const std::string& name) {
    if (head.size() < 84 || head.substr(0, 5) == "solid") {
        return;  // ASCII STL: grows with the file
    }
    std::uint32_t count = 0;
    std::memcpy(&count, head.data() + 80, sizeof(count));  // little-endian on every target we run
    limits::CheckLimit(name, "STL header: triangle count", count, limits::kMaxMeshElements,
                       "mesh element");
    if (84 + 50 * static_cast<std::uint64_t>(count) > file_bytes) {
        throw MakeInputError(name, "STL header: triangle count", std::to_string(count),
                             "needs " +
                                 std::to_string(84 + 50 * static_cast<std::uint64_t>(count)) +
                                 " bytes, the file has " + std::to_string(file_bytes));
    }
}

// PLY files (assimp's PLY reader takes any file whose first three bytes are "ply" in any case)
// are checked whole
// (io/ply_check.hpp); `whole` returns the file's bytes, read only for a PLY file.
template <typename Whole>
void CheckFile(std::string_view head,
               std::uint64_t file_bytes,
               const std::string& hint,
               const std::string& name,
               Whole whole) {
    limits::CheckLimit(name, "file size (bytes)", file_bytes, limits::kMaxFileBytes, "mesh file");
    const auto lower = [&](std::size_t i) {
        return i < head.size()
                   ? static_cast<char>(std::tolower(static_cast<unsigned char>(head[i])))
                   : '\0';
    };
    if (lower(0) == 'p' && lower(1) == 'l' && lower(2) == 'y') {
        CheckPly(whole(), name);
    } else if (hint == "stl" || hint == "STL") {
        CheckStlHeader(head, file_bytes, name);
    }
}

// Reading only validates; the polygons are checked (CheckPolygons) before assimp triangulates
// them and separates points and lines from triangles.
constexpr unsigned int kReadProcess = aiProcess_ValidateDataStructure;
constexpr unsigned int kPostProcess = aiProcess_Triangulate | aiProcess_SortByPType;

// assimp triangulates a polygon of k > 4 corners by ear clipping, in time ~k^2 (a 32 000-corner
// polygon: 20 s): bound each polygon and all of them before it runs (docs/limits.md).
void CheckPolygons(const aiScene& scene, const std::string& name) {
    std::uint64_t total = 0;
    for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[m];
        for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
            const std::uint64_t corners = mesh.mFaces[f].mNumIndices;
            if (corners <= 4) {
                continue;
            }
            limits::CheckLimit(name, "mesh polygon corners", corners, limits::kMaxPolygonCorners,
                               "polygon corner");
            total += corners;
            limits::CheckLimit(name, "mesh corners of polygons with more than 4", total,
                               limits::kMaxPolygonCornersTotal, "polygon corner");
        }
    }
}

// Reads with `read` (validation only), checks the polygons, then triangulates.
template <typename Read>
const aiScene* ImportChecked(Assimp::Importer& importer, const std::string& name, Read read) {
    try {
        const aiScene* scene = read();
        if (scene == nullptr || scene->mRootNode == nullptr) {
            return scene;
        }
        CheckPolygons(*scene, name);
        return importer.ApplyPostProcessing(kPostProcess);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw MakeInputError(name, "mesh", "", std::string("unreadable: ") + e.what());
    }
}

void CheckScale(const std::string& name, const Eigen::Vector3d& scale) {
    for (int i = 0; i < 3; ++i) {
        if (!(scale[i] > 0.0) || !std::isfinite(scale[i])) {
            throw MakeInputError(name, "scale", core::FormatNumber(scale[i]), "must be > 0");
        }
    }
}

// Converts what assimp read; counts are checked before our own vectors grow.
core::MeshShape ToShape(const aiScene* scene,
                        const Assimp::Importer& importer,
                        const std::string& name,
                        const Eigen::Vector3d& scale) {
    if (scene == nullptr || scene->mRootNode == nullptr) {
        throw MakeInputError(name, "mesh", "",
                             std::string("unreadable: ") + importer.GetErrorString());
    }
    std::uint64_t vertices = 0;
    std::uint64_t faces = 0;
    for (unsigned int m = 0; m < scene->mNumMeshes; ++m) {
        vertices += scene->mMeshes[m]->mNumVertices;
        faces += scene->mMeshes[m]->mNumFaces;
    }
    limits::CheckLimit(name, "mesh vertices", vertices, limits::kMaxMeshElements, "mesh element");
    limits::CheckLimit(name, "mesh faces", faces, limits::kMaxMeshElements, "mesh element");
    core::MeshShape shape;
    shape.source_path = name;
    AppendNode(*scene, *scene->mRootNode, aiMatrix4x4(), scale, shape);
    if (shape.triangles.empty()) {
        throw MakeInputError(name, "mesh", "", "holds no triangle");
    }
    for (const Eigen::Vector3f& v : shape.vertices) {
        if (!v.allFinite()) {
            throw MakeInputError(name, "mesh", "", "has a non-finite vertex");
        }
    }
    return shape;
}

}  // namespace

core::MeshShape ImportMeshFromMemory(std::string_view bytes,
                                     const std::string& format_hint,
                                     const std::string& name,
                                     const Eigen::Vector3d& scale) {
    CheckScale(name, scale);
    CheckFile(bytes.substr(0, 65536), bytes.size(), format_hint, name, [&] { return bytes; });
    Assimp::Importer importer;
    const aiScene* scene = ImportChecked(importer, name, [&] {
        return importer.ReadFileFromMemory(bytes.data(), bytes.size(), kReadProcess,
                                           format_hint.c_str());
    });
    return ToShape(scene, importer, name, scale);
}

core::MeshShape ImportMesh(const std::filesystem::path& path, const Eigen::Vector3d& scale) {
    const std::string name = path.string();
    CheckScale(name, scale);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        throw MakeInputError(name, "mesh", "", "file not found");
    }
    std::string head(65536, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    std::string hint = path.extension().string();
    hint = hint.empty() ? hint : hint.substr(1);
    std::string whole;
    CheckFile(head, std::filesystem::file_size(path, ec), hint, name, [&] {
        in.clear();
        in.seekg(0);
        whole.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        return std::string_view(whole);
    });
    Assimp::Importer importer;
    // Triangulate polygons; SortByPType separates points/lines; no unit or axis conversion, so
    // `scale` alone maps file units to metres.
    const aiScene* scene =
        ImportChecked(importer, name, [&] { return importer.ReadFile(name, kReadProcess); });
    return ToShape(scene, importer, name, scale);
}

}  // namespace casmap::io
