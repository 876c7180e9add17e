#pragma once

// Timestamped pose files (docs/pose-file.md): one sensor pose world_T_sensor per line,
//   stamp_s x_m y_m z_m qx qy qz qw
// whitespace separated, '#' starts a comment, stamps strictly increasing.

#include <istream>
#include <optional>
#include <string>

#include "casmap/core/trajectory.hpp"

namespace casmap::drivers {

/// Reads a pose file. Throws InputError naming file:line, the field and the rule (missing
/// file, wrong column count, non-numbers, a quaternion far from unit length, stamps not
/// strictly increasing, no poses, a folder, a line or a pose count beyond core/limits.hpp).
[[nodiscard]] core::Trajectory ReadPoseFile(const std::string& path);

/// One line of a pose file: the pose, or nullopt for a blank or comment-only line. Throws
/// InputError naming `where` (e.g. "poses.txt:12"), the column and the rule. Does not check
/// the order of stamps (the caller knows the previous one).
[[nodiscard]] std::optional<core::TimedPose> ParsePoseLine(std::string line,
                                                           const std::string& where);

/// ReadPoseFile on a stream; `name` names it in messages.
[[nodiscard]] core::Trajectory ReadPoses(std::istream& in, const std::string& name);

/// The pose-file text of `poses` with every stamp shifted by `offset_s`.
[[nodiscard]] std::string PoseFileText(const core::Trajectory& poses, double offset_s = 0.0);

}  // namespace casmap::drivers
