#include "casmap/pipeline/dataset.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <fstream>
#include <sstream>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/dataset_spec_file.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/pipeline/data_dir.hpp"
#include "casmap/pipeline/dataset_card.hpp"
#include "casmap/pipeline/sha256.hpp"
#include "casmap/scenegen/random.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

std::optional<std::string> ReadFirstLine(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line) || line.empty()) {
        return std::nullopt;
    }
    return line;
}

// Every "<hex>  <name>" line of files.sha256 matches its file.
bool HashesVerify(const fs::path& dir) {
    std::ifstream in(dir / "files.sha256");
    if (!in) {
        return false;
    }
    bool any = false;
    for (std::string line; std::getline(in, line);) {
        if (line.size() < 67 || line.compare(64, 2, "  ") != 0) {
            return false;
        }
        const fs::path file = dir / line.substr(66);
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) {
            return false;
        }
        try {
            if (Sha256File(file) != line.substr(0, 64)) {
                return false;
            }
        } catch (const InputError&) {
            return false;
        }
        any = true;
    }
    return any;
}

std::string PendingLine(const scenegen::DatasetSpec& spec, std::size_t index) {
    const std::uint64_t seed = scenegen::SampleSeed(spec.seed, index);
    return "{\"index\":" + std::to_string(index) + ",\"seed\":" + std::to_string(seed) +
           ",\"split\":\"" + scenegen::SplitOf(spec, seed) + "\",\"status\":\"pending\"}";
}

// A record as a payload of DistributeWork: "ok reused\nline".
std::string EncodeRecord(const SampleRecord& r) {
    return std::string(r.ok ? "1" : "0") + (r.reused ? " 1\n" : " 0\n") + r.line;
}

SampleRecord DecodeRecord(std::size_t index, const std::string& payload) {
    return SampleRecord{index, payload.compare(0, 1, "1") == 0, payload.compare(2, 1, "1") == 0,
                        payload.substr(4)};
}

}  // namespace

std::vector<fs::path> FindRockMeshes(const std::string& dir_flag) {
    std::vector<fs::path> candidates;
    if (!dir_flag.empty()) {
        candidates.emplace_back(dir_flag);
    } else {
        candidates.emplace_back("scenes/meshes");
        if (const std::optional<fs::path> data = FindDataDir()) {
            candidates.push_back(*data / "scenes" / "meshes");  // installed or source tree
        }
    }
    for (const fs::path& dir : candidates) {
        std::error_code ec;
        std::vector<fs::path> rocks;
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
            const std::string name = e.path().filename().string();
            if (name.rfind("rock_", 0) == 0 && e.path().extension() == ".ply") {
                rocks.push_back(e.path());
            }
        }
        if (!rocks.empty()) {
            std::sort(rocks.begin(), rocks.end());
            return rocks;
        }
    }
    throw MakeInputError(dir_flag.empty() ? "scenes/meshes" : dir_flag, "meshes_dir", dir_flag,
                         "no rock_*.ply meshes found");
}

std::optional<SampleRecord> VerifiedSample(const fs::path& out_dir, std::size_t index) {
    const fs::path dir = SampleDir(out_dir, index);
    const std::optional<std::string> line = ReadFirstLine(dir / "sample.json");
    if (!line || !HashesVerify(dir)) {
        return std::nullopt;
    }
    return SampleRecord{index, true, true, *line};
}

SampleRecord ProduceSample(const scenegen::DatasetSpec& spec,
                           const DatasetContext& context,
                           std::size_t index) {
    if (std::optional<SampleRecord> done = VerifiedSample(context.out_dir, index)) {
        return *done;
    }
    return GenerateSample(spec, context, index);
}

std::vector<std::size_t> ShardIndices(std::size_t count, std::size_t shard, std::size_t shards) {
    std::vector<std::size_t> out;
    for (std::size_t i = shard; i < count; i += shards) {
        out.push_back(i);
    }
    return out;
}

void DatasetOptions::Validate() const {
    const core::Check check;
    check.That(threads >= 1, "threads", threads, "allowed: >= 1");
    check.That(shards >= 1, "shards", shards, "allowed: >= 1");
    check.That(shard < shards, "shard", shard, "allowed: 0 <= shard < shards");
}

void ParseShard(std::string_view text, DatasetOptions& options, const std::string& field) {
    const std::size_t slash = text.find('/');
    std::size_t i = 0;
    std::size_t k = 0;
    const char* end = text.data() + text.size();
    const bool ok =
        slash != std::string_view::npos &&
        std::from_chars(text.data(), text.data() + slash, i).ptr == text.data() + slash &&
        std::from_chars(text.data() + slash + 1, end, k).ptr == end && k > 0 && i < k;
    core::Check().That(ok, field, text, "expected I/K with 0 <= I < K");
    options.shard = i;
    options.shards = k;
}

DatasetSummary RunDataset(const scenegen::DatasetSpec& spec,
                          const DatasetContext& context,
                          const DatasetOptions& options,
                          const DistributedSession& session) {
    options.Validate();
    const auto start = std::chrono::steady_clock::now();
    if (session.rank() == 0) {
        io::EnsureDirectory(context.out_dir / "samples");
    }
    session.Barrier();  // the directory exists before any rank writes into it
    const std::vector<std::size_t> indices =
        ShardIndices(static_cast<std::size_t>(spec.count), options.shard, options.shards);
    std::map<std::size_t, SampleRecord> records;
    DatasetProgress progress{0, indices.size(), 0, 0.0};
    const auto work = [&](std::size_t i) { return EncodeRecord(ProduceSample(spec, context, i)); };
    const auto done = [&](std::size_t i, const std::string& payload) {
        SampleRecord r = DecodeRecord(i, payload);
        ++progress.done;
        progress.failed += r.ok ? 0 : 1;
        progress.elapsed_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        records[i] = std::move(r);
        if (options.progress) {
            options.progress(progress);
        }
    };
    (void)DistributeWork(session, indices, options.threads, work, done);
    DatasetSummary summary;
    if (session.rank() == 0) {
        summary = WriteDatasetIndex(spec, context.out_dir, records);
        summary.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    session.Barrier();
    return summary;
}

DatasetSummary RunDataset(const scenegen::DatasetSpec& spec,
                          const DatasetContext& context,
                          const DatasetOptions& options) {
    return RunDataset(spec, context, options, DistributedSession::Local());
}

DatasetSummary WriteDatasetIndex(const scenegen::DatasetSpec& spec,
                                 const fs::path& out_dir,
                                 const std::map<std::size_t, SampleRecord>& records) {
    DatasetSummary summary;
    std::string manifest;
    std::vector<SampleRecord> ok;
    for (std::size_t i = 0; i < static_cast<std::size_t>(spec.count); ++i) {
        const auto it = records.find(i);
        std::optional<SampleRecord> r;
        if (it != records.end()) {
            r = it->second;
            summary.generated += r->reused ? 0 : 1;
            summary.reused += r->reused ? 1 : 0;
            summary.failed += r->ok ? 0 : 1;
        } else if ((r = VerifiedSample(out_dir, i))) {
            r->reused = true;
        }
        if (!r) {
            ++summary.pending;
            manifest += PendingLine(spec, i) + "\n";
            continue;
        }
        manifest += r->line + "\n";
        if (r->ok) {
            ok.push_back(*r);
        }
    }
    summary.generated -= std::min(summary.generated, summary.failed);
    io::WriteTextAtomically(out_dir / "manifest.jsonl", manifest);
    YAML::Emitter yaml;
    yaml << YAML::Comment("casmap dataset: the effective spec and the counts");
    yaml << YAML::BeginMap;
    yaml << YAML::Key << "casmap_version" << YAML::Value << std::string(CASMAP_VERSION);
    yaml << YAML::Key << "counts" << YAML::Value << YAML::Flow << YAML::BeginMap;
    yaml << YAML::Key << "samples" << YAML::Value << spec.count;
    yaml << YAML::Key << "ok" << YAML::Value << ok.size();
    yaml << YAML::Key << "failed" << YAML::Value << spec.count - ok.size() - summary.pending;
    yaml << YAML::Key << "pending" << YAML::Value << summary.pending;
    yaml << YAML::EndMap;
    io::EmitDatasetSpec(yaml, spec);
    yaml << YAML::EndMap;
    io::WriteTextAtomically(out_dir / "dataset.yaml", io::EmittedText(yaml));
    WriteDatasetCard(spec, out_dir, ok);
    return summary;
}

}  // namespace casmap::pipeline
