#include "casmap/io/output_set.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

#include "casmap/core/input_error.hpp"

namespace casmap::io {
namespace fs = std::filesystem;

namespace {

fs::path FolderOf(const fs::path& path) {
    return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// The PID of a ".<name>.tmp<PID>" entry, or 0 if `name` is not such a temporary.
long TemporaryPid(const std::string& name) {
    const std::size_t at = name.rfind(".tmp");
    if (name.empty() || name[0] != '.' || at == std::string::npos || at == 0 ||
        at + 4 >= name.size() || name.size() - at > 14) {
        return 0;
    }
    long pid = 0;
    for (std::size_t i = at + 4; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9') {
            return 0;
        }
        pid = pid * 10 + (name[i] - '0');
    }
    return pid;
}

bool ProcessRuns(long pid) { return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

}  // namespace

fs::path TemporaryPathFor(const fs::path& path) {
    std::string name = ".";
    name.append(path.filename().string());
    name.append(".tmp");
    name.append(std::to_string(static_cast<long>(getpid())));
    return FolderOf(path) / name;
}

int RemoveStaleTemporaries(const fs::path& dir) noexcept {
    int removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const long pid = TemporaryPid(it->path().filename().string());
        if (pid > 0 && pid != static_cast<long>(getpid()) && !ProcessRuns(pid)) {
            std::error_code ignored;
            removed += fs::remove_all(it->path(), ignored) > 0 ? 1 : 0;
        }
    }
    return removed;
}

void CheckOutputPath(const fs::path& path, const std::string& field, bool create_parent) {
    std::error_code ec;
    if (path.empty() || fs::is_directory(path, ec)) {
        throw MakeInputError(path.string(), field, "",
                             path.empty() ? "needs a file name" : "is a folder, not a file");
    }
    const fs::path dir = FolderOf(path);
    std::error_code create_ec;
    if (create_parent && !fs::exists(dir, ec)) {
        fs::create_directories(dir, create_ec);
    }
    if (!fs::is_directory(dir, ec)) {
        // Say why: a file in the way, a folder that could not be made, or one that is missing.
        std::string why = "folder " + dir.string() + " does not exist";
        if (fs::exists(dir, ec)) {
            why = dir.string() + " is not a folder";
        } else if (create_ec) {
            why = "folder " + dir.string() + " cannot be created: " + create_ec.message();
        }
        throw MakeInputError(path.string(), field, "", why);
    }
    if (access(dir.c_str(), W_OK) != 0) {
        throw MakeInputError(path.string(), field, "",
                             "folder " + dir.string() + " is not writable");
    }
}

OutputSet::~OutputSet() {
    if (published_) {
        return;
    }
    for (const Entry& e : entries_) {
        std::error_code ignored;
        fs::remove_all(e.tmp_path, ignored);
    }
}

fs::path OutputSet::AddFile(const fs::path& path, const std::string& field, bool create_parent) {
    CheckOutputPath(path, field, create_parent);
    for (const Entry& e : entries_) {
        if (fs::weakly_canonical(e.final_path) == fs::weakly_canonical(path)) {
            throw MakeInputError(path.string(), field, "", "is also the output of " + e.field);
        }
    }
    RemoveStaleTemporaries(FolderOf(path));
    entries_.push_back({path, TemporaryPathFor(path), field, false});
    return entries_.back().tmp_path;
}

fs::path OutputSet::AddFolder(const fs::path& path, const std::string& field) {
    std::error_code ec;
    fs::path clean = path.lexically_normal();
    if (!clean.has_filename()) {
        clean = clean.parent_path();  // "out/" -> "out"
    }
    if (fs::exists(clean, ec) && !fs::is_directory(clean, ec)) {
        throw MakeInputError(path.string(), field, "", "exists and is not a folder");
    }
    const fs::path parent = FolderOf(clean);
    if (!fs::exists(parent, ec)) {
        fs::create_directories(parent, ec);
    }
    if (!fs::is_directory(parent, ec) || access(parent.c_str(), W_OK) != 0) {
        throw MakeInputError(path.string(), field, "",
                             "folder " + parent.string() + " is missing or not writable");
    }
    RemoveStaleTemporaries(parent);
    const fs::path tmp = TemporaryPathFor(clean);
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        throw MakeInputError(clean.string(), field, "", "cannot create " + tmp.string());
    }
    entries_.push_back({clean, tmp, field, true});
    return tmp;
}

void OutputSet::Publish() {
    for (const Entry& e : entries_) {
        std::error_code ec;
        fs::path old;
        if (e.folder && fs::exists(e.final_path, ec)) {
            // A folder cannot be renamed over a non-empty one: move the old one aside first
            // (under a temporary name, so a kill here leaves it to the stale-temporary sweep).
            old = TemporaryPathFor(e.final_path.parent_path() /
                                   (e.final_path.filename().string() + ".old"));
            fs::remove_all(old, ec);
            fs::rename(e.final_path, old, ec);
        }
        if (!ec) {
            fs::rename(e.tmp_path, e.final_path, ec);
        }
        if (ec) {
            throw MakeInputError(e.final_path.string(), e.field, "",
                                 "cannot be published: " + ec.message());
        }
        if (!old.empty()) {
            fs::remove_all(old, ec);
        }
    }
    published_ = true;
}

}  // namespace casmap::io
