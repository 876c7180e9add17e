#include "apps/casmap/flag_names.hpp"

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::app {
namespace {

bool IsWordChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/// `text` with every whole-word occurrence of a mapped name other than `own` replaced by its
/// flag (a rule names other fields; its own field's name there is a word: "... 500000 baud").
std::string ReplaceNames(const std::string& text, const FlagNames& names, const std::string& own) {
    std::string out;
    std::size_t at = 0;
    while (at < text.size()) {
        if (!IsWordChar(text[at])) {
            out += text[at++];
            continue;
        }
        std::size_t end = at;
        while (end < text.size() && IsWordChar(text[end])) {
            ++end;
        }
        const std::string word = text.substr(at, end - at);
        const auto it = names.find(word);
        // Not a part of a path or a flag: "/data/run.h5" and "--set" keep their words.
        const bool path_or_flag =
            (at > 0 && (text[at - 1] == '-' || text[at - 1] == '/' || text[at - 1] == '.')) ||
            (end < text.size() && text[end] == '/') ||
            (end + 1 < text.size() && text[end] == '.' && IsWordChar(text[end + 1]));
        const bool flag = it != names.end() && word != own && !path_or_flag;
        out += flag ? it->second : word;
        at = end;
    }
    return out;
}

}  // namespace

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

void WithCommandLineFlags(const FlagNames& names,
                          const std::function<void()>& body,
                          const FlagPaths& paths) {
    try {
        body();
    } catch (const InputError& e) {
        const auto path = paths.find(e.field());
        const auto about_path = [&](const std::string& p) {  // the path, or a file in it
            return !p.empty() && (e.where() == p || e.where().rfind(p + "/", 0) == 0);
        };
        if (path != paths.end() && about_path(path->second) && names.count(e.field()) != 0) {
            throw MakeInputError(e.where(), names.at(e.field()), e.value(),
                                 ReplaceNames(e.rule(), names, e.field()));
        }
        if (!e.where().empty() || e.field().empty()) {
            throw;
        }
        std::string field;
        for (const std::string& part : core::SplitList(e.field(), '/')) {
            std::string name = part;
            while (!name.empty() && name.front() == ' ') {
                name.erase(0, 1);
            }
            while (!name.empty() && name.back() == ' ') {
                name.pop_back();
            }
            const auto it = names.find(name);
            if (it == names.end()) {
                throw;
            }
            field += (field.empty() ? "" : " / ") + it->second;
        }
        throw MakeInputError("command line", field, e.value(),
                             ReplaceNames(e.rule(), names, e.field()));
    }
}

void WithWhereAsFlag(const std::string& where,
                     const std::string& flag,
                     const std::function<void()>& body) {
    try {
        body();
    } catch (const InputError& e) {
        if (e.where() != where) {
            throw;
        }
        throw MakeInputError(flag, e.field(), e.value(), e.rule());
    }
}

}  // namespace casmap::app
