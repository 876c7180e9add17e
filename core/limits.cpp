#include "casmap/core/limits.hpp"

#include "casmap/core/input_error.hpp"

namespace casmap::core::limits {

void CheckLimit(const std::string& where,
                const std::string& field,
                std::uint64_t size,
                std::uint64_t limit,
                const std::string& what) {
    if (size > limit) {
        throw MakeInputError(where, field, std::to_string(size),
                             what + " limit " + std::to_string(limit) + ", see docs/limits.md");
    }
}

}  // namespace casmap::core::limits
