#include "casmap/drivers/pose_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"

namespace casmap::drivers {

std::optional<core::TimedPose> ParsePoseLine(std::string line, const std::string& where) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) {
        line.resize(hash);
    }
    std::istringstream fields(line);
    std::vector<double> v;
    std::string token;
    while (fields >> token) {
        char* end = nullptr;
        const double x = std::strtod(token.c_str(), &end);
        if (end == nullptr || *end != '\0' || !std::isfinite(x)) {
            throw MakeInputError(where, "column " + std::to_string(v.size() + 1), token,
                                 "a finite number");
        }
        v.push_back(x);
    }
    if (v.empty()) {
        return std::nullopt;
    }
    if (v.size() != 8) {
        throw MakeInputError(where, "columns", std::to_string(v.size()),
                             "8: stamp_s x_m y_m z_m qx qy qz qw");
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3) {
        throw MakeInputError(where, "quaternion norm", std::to_string(q.norm()),
                             "unit length within 1e-3");
    }
    core::TimedPose p;
    p.stamp_s = v[0];
    p.world_T_sensor.translation = Eigen::Vector3d(v[1], v[2], v[3]);
    p.world_T_sensor.rotation = q.normalized();
    return p;
}

core::Trajectory ReadPoseFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw MakeInputError(path, "pose file", "", "is a folder, not a file");
    }
    std::ifstream in(path);
    if (!in) {
        throw MakeInputError(path, "pose file", "", "cannot be opened");
    }
    return ReadPoses(in, path);
}

core::Trajectory ReadPoses(std::istream& in, const std::string& name) {
    namespace limits = core::limits;
    std::vector<core::TimedPose> samples;
    std::vector<char> buffer(limits::kMaxPoseLineBytes + 1);
    int line_no = 0;
    // Bounded lines: an endless stream without newlines (/dev/zero) stops at the line limit,
    // one with newlines at the pose limit.
    while (in.getline(buffer.data(), static_cast<std::streamsize>(buffer.size())) ||
           in.gcount() > 0) {
        ++line_no;
        const std::string where = name + ":" + std::to_string(line_no);
        if (in.fail() && !in.eof()) {
            throw MakeInputError(where, "line", "",
                                 "longer than " + std::to_string(limits::kMaxPoseLineBytes) +
                                     " bytes, see docs/limits.md");
        }
        const std::optional<core::TimedPose> p = ParsePoseLine(buffer.data(), where);
        if (p) {
            if (!samples.empty() && !(p->stamp_s > samples.back().stamp_s)) {
                char stamp[64];
                std::snprintf(stamp, sizeof(stamp), "%.17g", p->stamp_s);
                throw MakeInputError(where, "stamp_s", stamp, "strictly increasing");
            }
            limits::CheckLimit(where, "poses", samples.size() + 1, limits::kMaxPoses, "pose");
            samples.push_back(*p);
        }
        if (in.eof()) {
            break;
        }
    }
    if (samples.empty()) {
        throw MakeInputError(name, "pose file", "", "holds no poses");
    }
    return core::Trajectory(std::move(samples));
}

std::string PoseFileText(const core::Trajectory& poses, double offset_s) {
    std::string text = "# casmap pose file: stamp_s x_m y_m z_m qx qy qz qw (world_T_sensor)\n";
    char buf[256];
    for (const core::TimedPose& p : poses.samples()) {
        const Eigen::Vector3d& t = p.world_T_sensor.translation;
        const Eigen::Quaterniond& q = p.world_T_sensor.rotation;
        std::snprintf(buf, sizeof(buf), "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                      p.stamp_s + offset_s, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
        text += buf;
    }
    return text;
}

}  // namespace casmap::drivers
