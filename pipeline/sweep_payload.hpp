#pragma once

// The bytes of a sweep's payloads (what a rank sends for one training or held-out run) and of
// their broadcast to every rank: exact, doubles bit for bit. Internal to the sweep
// (sweep_train.cpp); not installed.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/distributed.hpp"

namespace casmap::pipeline::detail {

void PutU64(std::string& out, std::uint64_t v);
void PutF64(std::string& out, double v);
/// The size, then the bytes.
void PutStr(std::string& out, const std::string& s);

/// Reads what the Put functions wrote, in order, from `at`; throws std::runtime_error on a
/// truncated payload (a bug, not bad input).
struct Reader {
    const std::string& in;
    std::size_t at = 0;
    std::uint64_t U64();
    double F64();
    std::string Str();
};

/// The figures of a score a sweep keeps (PI, Table II shares, spikes, poles).
void PutScore(std::string& out, const CasScore& s);
[[nodiscard]] CasScore GetScore(Reader& r);

/// Rank 0's payloads (item order) on every rank; throws if any item failed ('E' + message).
[[nodiscard]] std::vector<std::string> Gather(const DistributedSession& session,
                                              const std::map<std::size_t, std::string>& payloads,
                                              std::size_t count);

}  // namespace casmap::pipeline::detail
