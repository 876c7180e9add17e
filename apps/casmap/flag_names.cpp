#include "apps/casmap/flag_names.hpp"

#include "casmap/core/input_error.hpp"

namespace casmap::app {

void WithFlagNames(const FlagNames& names, const std::function<void()>& body) {
    try {
        body();
    } catch (const InputError& e) {
        if (!e.where().empty()) {
            throw;  // an error inside a file (rig.yaml:3:3) names that file's field, not a flag
        }
        const std::string& field = e.field();
        for (const auto& [name, flag] : names) {
            if (field == name) {
                throw e.WithField(flag);
            }
            if (field.size() > name.size() && field.compare(0, name.size(), name) == 0 &&
                (field[name.size()] == ' ' || field[name.size()] == '[')) {
                throw e.WithField(flag + field.substr(name.size()));
            }
        }
        throw;
    }
}

}  // namespace casmap::app
