#include "casmap/pipeline/stage_yaml.hpp"

#include <string>

namespace casmap::pipeline::detail {

void EmitStageSection(YAML::Emitter& out, const mapper::StageSection& section) {
    out << YAML::Key << std::string(section.stage) << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const mapper::StageParam& p : section.params) {
        out << YAML::Key << p.key << YAML::Value << p.value;
    }
    out << YAML::EndMap;
}

}  // namespace casmap::pipeline::detail
