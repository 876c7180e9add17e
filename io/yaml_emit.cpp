#include "casmap/io/yaml_emit.hpp"

#include <stdexcept>

namespace casmap::io {

std::string EmittedText(const YAML::Emitter& out) {
    if (!out.good()) {
        throw std::logic_error("YAML emitter: " + out.GetLastError());
    }
    return std::string(out.c_str()) + "\n";
}

}  // namespace casmap::io
