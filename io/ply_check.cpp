#include "casmap/io/ply_check.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"

namespace casmap::io {
namespace {

namespace limits = core::limits;

enum class Kind { kInt, kUnsigned, kFloat };

struct Type {
    Kind kind = Kind::kInt;
    int bytes = 0;
};

std::optional<Type> ParseType(std::string_view word) {
    struct Named {
        const char* name;
        Type type;
    };
    static constexpr std::array<Named, 16> kTypes = {{
        {"char", {Kind::kInt, 1}},
        {"int8", {Kind::kInt, 1}},
        {"uchar", {Kind::kUnsigned, 1}},
        {"uint8", {Kind::kUnsigned, 1}},
        {"short", {Kind::kInt, 2}},
        {"int16", {Kind::kInt, 2}},
        {"ushort", {Kind::kUnsigned, 2}},
        {"uint16", {Kind::kUnsigned, 2}},
        {"int", {Kind::kInt, 4}},
        {"int32", {Kind::kInt, 4}},
        {"uint", {Kind::kUnsigned, 4}},
        {"uint32", {Kind::kUnsigned, 4}},
        {"float", {Kind::kFloat, 4}},
        {"float32", {Kind::kFloat, 4}},
        {"double", {Kind::kFloat, 8}},
        {"float64", {Kind::kFloat, 8}},
    }};
    for (const Named& t : kTypes) {
        if (word == t.name) {
            return t.type;
        }
    }
    return std::nullopt;
}

struct Property {
    std::string name;
    Type type;                  // the value type (a list's index type)
    std::optional<Type> count;  // set for a list: the type of its length
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

enum class Format { kAscii, kLittle, kBig };

// Splits on spaces and tabs.
std::vector<std::string_view> Words(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') {
            ++i;
        }
        if (i > start) {
            words.push_back(line.substr(start, i - start));
        }
    }
    return words;
}

std::string Quote(std::string_view text) {
    std::string out;
    for (const char c : text.substr(0, 32)) {
        out += (c >= 0x20 && c < 0x7f) ? c : '?';
    }
    return text.size() > 32 ? out + "..." : out;
}

class Checker {
public:
    Checker(std::string_view bytes, std::string name) : bytes_(bytes), name_(std::move(name)) {}

    void Run() {
        ParseHeader();
        if (format_ == Format::kAscii) {
            CheckAsciiBody();
        } else {
            CheckBinaryBody();
        }
    }

private:
    [[noreturn]] void Fail(const std::string& field,
                           std::string_view value,
                           const std::string& rule) const {
        throw MakeInputError(name_, field, Quote(value), rule);
    }
    std::string Line() const { return "PLY line " + std::to_string(line_number_); }

    // The next line (without its \n or \r\n); false at the end of the bytes.
    bool NextLine(std::string_view& line) {
        if (pos_ >= bytes_.size()) {
            return false;
        }
        const std::size_t end = bytes_.find('\n', pos_);
        line = bytes_.substr(pos_, end == std::string_view::npos ? end : end - pos_);
        pos_ = end == std::string_view::npos ? bytes_.size() : end + 1;
        if (!line.empty() && line.back() == '\r') {
            line.remove_suffix(1);
        }
        ++line_number_;
        return true;
    }

    void ParseHeader() {
        std::string_view line;
        if (!NextLine(line) || line != "ply") {
            Fail("PLY line 1", line, "must be exactly \"ply\"");
        }
        bool has_format = false;
        while (true) {
            if (!NextLine(line)) {
                Fail("PLY header", "", "has no end_header line");
            }
            if (line.find('\0') != std::string_view::npos) {
                Fail(Line(), line, "holds a NUL byte");
            }
            const std::vector<std::string_view> w = Words(line);
            if (w.empty()) {
                Fail(Line(), line, "is empty inside the header");
            }
            if (w[0] == "comment" || w[0] == "obj_info") {
                continue;
            }
            if (w[0] == "end_header" && w.size() == 1) {
                break;
            }
            if (w[0] == "format") {
                if (has_format || w.size() != 3 || w[2] != "1.0") {
                    Fail(Line(), line, "must be the one \"format <encoding> 1.0\" line");
                }
                if (w[1] == "ascii") {
                    format_ = Format::kAscii;
                } else if (w[1] == "binary_little_endian") {
                    format_ = Format::kLittle;
                } else if (w[1] == "binary_big_endian") {
                    format_ = Format::kBig;
                } else {
                    Fail(Line(), w[1],
                         "encoding must be ascii, binary_little_endian or "
                         "binary_big_endian");
                }
                has_format = true;
            } else if (w[0] == "element" && w.size() == 3) {
                AddElement(w[1], w[2]);
            } else if (w[0] == "property" && !elements_.empty()) {
                AddProperty(w, line);
            } else {
                Fail(Line(), line,
                     "must be format, comment, obj_info, element, property (after an "
                     "element) or end_header");
            }
        }
        if (!has_format) {
            Fail("PLY header", "", "has no format line");
        }
    }

    void AddElement(std::string_view name, std::string_view count_text) {
        char* end = nullptr;
        const std::string text(count_text);
        errno = 0;
        const unsigned long long count = std::strtoull(text.c_str(), &end, 10);
        if (text[0] == '-' || *end != '\0' || errno != 0) {
            Fail("PLY header: element " + Quote(name), count_text, "must be a count");
        }
        const std::string field = "PLY header: element " + Quote(name);
        limits::CheckLimit(name_, field, count, limits::kMaxMeshElements, "mesh element");
        if (count > bytes_.size()) {
            Fail(field, count_text,
                 "more elements than the file has bytes (" + std::to_string(bytes_.size()) + ")");
        }
        elements_.push_back({std::string(name), count, {}});
    }

    void AddProperty(const std::vector<std::string_view>& w, std::string_view line) {
        Property p;
        if (w.size() == 5 && w[1] == "list") {
            p.count = ParseType(w[2]);
            const std::optional<Type> index = ParseType(w[3]);
            if (!p.count || p.count->kind == Kind::kFloat || !index) {
                Fail(Line(), line, "a list needs an integer length type and a value type");
            }
            p.type = *index;
            p.name = w[4];
        } else if (w.size() == 3) {
            const std::optional<Type> type = ParseType(w[1]);
            if (!type) {
                Fail(Line(), w[1],
                     "is not a PLY type (char, uchar, short, ushort, int, uint, "
                     "float, double or their sized names)");
            }
            p.type = *type;
            p.name = w[2];
        } else {
            Fail(Line(), line,
                 "must be \"property <type> <name>\" or \"property list <type> "
                 "<type> <name>\"");
        }
        elements_.back().properties.push_back(std::move(p));
    }

    // The vertex count a face's indices must stay below (no vertex element: no bound).
    std::optional<std::uint64_t> VertexCount() const {
        for (const Element& e : elements_) {
            if (e.name == "vertex") {
                return e.count;
            }
        }
        return std::nullopt;
    }
    static bool IsIndexList(const Element& e, const Property& p) {
        return e.name == "face" && p.count &&
               (p.name == "vertex_indices" || p.name == "vertex_index");
    }

    void CheckListLength(std::uint64_t length, const std::string& where) const {
        limits::CheckLimit(name_, where + ": list length", length, limits::kMaxPolygonCorners,
                           "polygon corner");
    }
    void CheckIndex(double index, const std::string& where) const {
        const std::optional<std::uint64_t> vertices = VertexCount();
        if (vertices && !(index >= 0 && index < static_cast<double>(*vertices))) {
            Fail(where, std::to_string(static_cast<long long>(index)),
                 "vertex index must be 0.." + std::to_string(*vertices) + " - 1");
        }
    }

    // One ASCII value of `type`: the whole token is a number, an integer for integer types,
    // inside the type's range.
    double AsciiValue(std::string_view token, Type type, const std::string& where) const {
        const std::string text(token);
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(text.c_str(), &end);
        if (*end != '\0' || text.empty() || errno == ERANGE || !std::isfinite(value)) {
            Fail(where, token, "must be a finite number");
        }
        if (type.kind != Kind::kFloat) {
            const double lo =
                type.kind == Kind::kUnsigned ? 0.0 : -std::ldexp(1.0, 8 * type.bytes - 1);
            const double hi = type.kind == Kind::kUnsigned
                                  ? std::ldexp(1.0, 8 * type.bytes) - 1
                                  : std::ldexp(1.0, 8 * type.bytes - 1) - 1;
            if (value != std::floor(value) || value < lo || value > hi) {
                Fail(where, token, "must be an integer of the property's type");
            }
        }
        return value;
    }

    void CheckAsciiBody() {
        std::string_view line;
        for (const Element& e : elements_) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                if (!NextLine(line)) {
                    Fail("PLY body", "",
                         "ends before " + Quote(e.name) + " " + std::to_string(i) + " of " +
                             std::to_string(e.count));
                }
                const std::vector<std::string_view> w = Words(line);
                std::size_t k = 0;
                const std::string where =
                    Line() + " (" + Quote(e.name) + " " + std::to_string(i) + ")";
                for (const Property& p : e.properties) {
                    std::uint64_t n = 1;
                    if (p.count) {
                        if (k >= w.size()) {
                            Fail(where, line, "has fewer values than the header declares");
                        }
                        n = static_cast<std::uint64_t>(AsciiValue(w[k++], *p.count, where));
                        CheckListLength(n, where);
                    }
                    for (std::uint64_t j = 0; j < n; ++j) {
                        if (k >= w.size()) {
                            Fail(where, line, "has fewer values than the header declares");
                        }
                        const double value = AsciiValue(w[k++], p.type, where);
                        if (IsIndexList(e, p)) {
                            CheckIndex(value, where);
                        }
                    }
                }
                if (k != w.size()) {
                    Fail(where, line, "has more values than the header declares");
                }
            }
        }
        while (NextLine(line)) {
            if (!Words(line).empty()) {
                Fail(Line(), line, "lies after the last element the header declares");
            }
        }
    }

    // One binary value at pos_, in the file's byte order, as a double (integers up to 32 bits
    // and floats are exact or compared only for range).
    double BinaryValue(Type type, const std::string& what) {
        const auto bytes = static_cast<std::size_t>(type.bytes);
        if (bytes_.size() - pos_ < bytes) {
            Fail("PLY body at byte " + std::to_string(pos_), "",
                 what + " is cut off by the end of the file");
        }
        std::array<unsigned char, 8> raw{};
        for (std::size_t b = 0; b < bytes; ++b) {
            const std::size_t from = format_ == Format::kLittle ? b : bytes - 1 - b;
            raw[b] = static_cast<unsigned char>(bytes_[pos_ + from]);
        }
        pos_ += bytes;
        std::uint64_t u = 0;
        std::memcpy(&u, raw.data(), 8);  // little-endian host
        switch (type.kind) {
            case Kind::kUnsigned:
                return static_cast<double>(u);
            case Kind::kInt: {
                const int shift = 64 - 8 * type.bytes;
                return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
            }
            case Kind::kFloat:
                if (bytes == 4) {
                    float f = 0;
                    std::memcpy(&f, raw.data(), 4);
                    return f;
                }
                double d = 0;
                std::memcpy(&d, raw.data(), 8);
                return d;
        }
        return 0.0;
    }

    void CheckBinaryBody() {
        for (const Element& e : elements_) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                const std::string what = Quote(e.name) + " " + std::to_string(i);
                for (const Property& p : e.properties) {
                    const std::size_t at = pos_;
                    std::uint64_t n = 1;
                    if (p.count) {
                        const double length = BinaryValue(*p.count, what);
                        if (length < 0) {
                            Fail("PLY body at byte " + std::to_string(at), std::to_string(length),
                                 "list length must not be negative");
                        }
                        n = static_cast<std::uint64_t>(length);
                        CheckListLength(n, "PLY body at byte " + std::to_string(at));
                    }
                    for (std::uint64_t j = 0; j < n; ++j) {
                        const std::size_t value_at = pos_;
                        const double value = BinaryValue(p.type, what);
                        if (IsIndexList(e, p)) {
                            CheckIndex(value, "PLY body at byte " + std::to_string(value_at));
                        }
                    }
                }
            }
        }
    }

    std::string_view bytes_;
    std::string name_;
    std::size_t pos_ = 0;
    std::size_t line_number_ = 0;
    Format format_ = Format::kAscii;
    std::vector<Element> elements_;
};

}  // namespace

void CheckPly(std::string_view bytes, const std::string& name) { Checker(bytes, name).Run(); }

}  // namespace casmap::io
