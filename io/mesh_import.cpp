#include "casmap/io/mesh_import.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <string>

#include "casmap/core/input_error.hpp"

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

}  // namespace

core::MeshShape ImportMesh(const std::filesystem::path& path, const Eigen::Vector3d& scale) {
    const std::string name = path.string();
    for (int i = 0; i < 3; ++i) {
        if (!(scale[i] > 0.0) || !std::isfinite(scale[i])) {
            throw MakeInputError(name, "scale", std::to_string(scale[i]), "must be > 0");
        }
    }
    if (!std::filesystem::is_regular_file(path)) {
        throw MakeInputError(name, "mesh", "", "file not found");
    }
    Assimp::Importer importer;
    // Triangulate polygons; SortByPType separates points/lines; no unit or axis conversion, so
    // `scale` alone maps file units to metres.
    const aiScene* scene = importer.ReadFile(
        name, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
    if (scene == nullptr || scene->mRootNode == nullptr) {
        throw MakeInputError(name, "mesh", "",
                             std::string("unreadable: ") + importer.GetErrorString());
    }
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

}  // namespace casmap::io
