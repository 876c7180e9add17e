#include "casmap/core/scene.hpp"

#include <set>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"

namespace casmap::core {
namespace {

// Sizes and positions beyond this many metres are typos (a scene is a test course, not a
// continent) and would make the ground-truth grid and the ray caster lose all precision.
const std::string kExtentRule =
    "allowed: 0 < size <= " + FormatNumber(limits::kMaxSceneExtentM) + " m, see docs/limits.md";

void CheckExtent(const Check& check, const std::string& field, double size_m) {
    check.That(size_m > 0.0 && size_m <= limits::kMaxSceneExtentM, field, size_m, kExtentRule);
}

void CheckShape(const Check& check, const std::string& field, const Shape& shape) {
    if (const auto* box = std::get_if<BoxShape>(&shape)) {
        for (int i = 0; i < 3; ++i) {
            CheckExtent(check, field + ".box.size_m[" + std::to_string(i) + "]", box->size_m[i]);
        }
    } else if (const auto* cylinder = std::get_if<CylinderShape>(&shape)) {
        CheckExtent(check, field + ".cylinder.radius_m", cylinder->radius_m);
        CheckExtent(check, field + ".cylinder.height_m", cylinder->height_m);
    } else if (const auto* mesh = std::get_if<MeshShape>(&shape)) {
        const auto vertices = static_cast<int>(mesh->vertices.size());
        check.That(!mesh->triangles.empty(), field + ".mesh", mesh->source_path,
                   "has no triangles");
        for (const Eigen::Vector3i& t : mesh->triangles) {
            check.That(t.minCoeff() >= 0 && t.maxCoeff() < vertices, field + ".mesh",
                       mesh->source_path, "a triangle names a vertex that does not exist");
        }
    }
}

void CheckObject(const Check& check, const std::string& field, const SceneObject& object) {
    check.That(!object.name.empty(), field + ".name", "", "must not be empty");
    CheckShape(check, field, object.shape);
    const Eigen::Vector3d& t = object.world_T_object.translation;
    check.That(
        t.allFinite() && object.world_T_object.rotation.coeffs().allFinite() &&
            t.cwiseAbs().maxCoeff() <= limits::kMaxSceneExtentM,
        field + ".pose",
        "[" + FormatNumber(t.x()) + ", " + FormatNumber(t.y()) + ", " + FormatNumber(t.z()) + "]",
        "position within +-" + FormatNumber(limits::kMaxSceneExtentM) + " m, see docs/limits.md");
    check.That(object.reflectivity >= 0.0 && object.reflectivity <= 1.0, field + ".reflectivity",
               object.reflectivity, "allowed: 0..1");
}

}  // namespace

void Scene::Validate() const {
    const Check check(source_path);
    check.That(!objects.empty(), "objects", "[]", "must be a non-empty list");
    std::set<std::string> names;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const std::string field = "objects[" + std::to_string(i) + "]";
        CheckObject(check, field, objects[i]);
        check.That(names.insert(objects[i].name).second, field + ".name", objects[i].name,
                   "duplicate name");
    }
}

}  // namespace casmap::core
