// The texts a live session writes (pipeline/live.hpp): status.json and config.yaml.
#include <cstdio>
#include <string>

#include "casmap/io/yaml_emit.hpp"
#include "casmap/mapper/stage_params.hpp"
#include "casmap/pipeline/live.hpp"
#include "casmap/pipeline/stage_yaml.hpp"

namespace casmap::pipeline {

std::string LiveConfigYaml(const LiveConfig& c, const std::string& source) {
    const mapper::ActiveWindowConfig& w = c.window;
    YAML::Emitter out;
    out << YAML::Comment("casmap live: the effective configuration");
    out << YAML::BeginMap;
    out << YAML::Key << "source" << YAML::Value << YAML::DoubleQuoted << source;
    out << YAML::Key << "window" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "rows" << YAML::Value << w.rows << YAML::Key << "cols" << YAML::Value
        << w.cols << YAML::Key << "m" << YAML::Value << w.m;
    io::EmitNumber(out, "cell_m", w.cell_m);
    io::EmitNumber(out, "origin_x_m", w.origin_x_m);
    io::EmitNumber(out, "origin_y_m", w.origin_y_m);
    io::EmitNumber(out, "heading_step_rad", w.heading_step_rad);
    out << YAML::EndMap;
    out << YAML::Key << "mapper" << YAML::Value << YAML::Flow << YAML::BeginMap;
    const MapperMode mode = w.consensus ? MapperMode::kConsensus : MapperMode::kPaper;
    out << YAML::Key << "mode" << YAML::Value << std::string(ToString(mode));
    out << YAML::Key << "prefilter" << YAML::Value << std::string(ToString(c.prefilter));
    out << YAML::Key << "a" << YAML::Value << w.a;
    io::EmitNumber(out, "delta_l_m", w.delta_l_m);
    io::EmitNumber(out, "scan_period_s", w.scan_period_s);
    // The parameters of the stages run, as casmap map's map.yaml writes them.
    mapper::FilterParams params;
    params.sweep_jump = c.sweep_jump;
    params.consensus = w.consensus.value_or(mapper::ConsensusConfig{});
    for (const mapper::StageSection& section : mapper::StageSections(params)) {
        if (RunsStage(mode, c.prefilter, section.stage)) {
            detail::EmitStageSection(out, section);
        }
    }
    out << YAML::EndMap;
    out << YAML::Key << "cas" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "k" << YAML::Value << w.cas.k;
    io::EmitNumber(out, "speed_m_s", w.cas.speed_m_s);
    io::EmitNumber(out, "A", w.cas.EffectiveA());
    io::EmitNumber(out, "G", w.cas.EffectiveG());
    out << YAML::EndMap;
    io::EmitNumber(out, "obstacle_cell_m", w.obstacle_cell_m);
    io::EmitNumber(out, "pose_tolerance_s", c.pose_tolerance_s);
    io::EmitNumber(out, "pose_wait_s", c.pose_wait_s);
    out << YAML::EndMap;
    return io::EmittedText(out);
}

std::string StatusJson(const LiveStatus& s, const mapper::ActiveWindow& window) {
    const core::GridGeometry o = window.obstacles().Bounds();
    char buf[2048];
    std::snprintf(
        buf, sizeof(buf),
        "{\"elapsed_s\": %.3f, \"scans\": %llu, \"scans_mapped\": %llu, \"dropped\": %llu, "
        "\"poses\": %llu, \"rows_filtered\": %llu, \"beams_rejected\": %llu, "
        "\"scans_per_s\": %.2f, "
        "\"latency_p50_ms\": %.3f, \"latency_p99_ms\": %.3f, \"crc_errors\": %llu, "
        "\"resyncs\": %llu, \"reconnects\": %llu, \"finished\": %s,\n"
        " \"window\": {\"rows\": %d, \"cols\": %d, \"m\": %d, \"cell_m\": %s, \"heading_rad\": "
        "%.9g, \"first_row\": %lld, \"first_col\": %lld, \"origin_x_m\": %s, \"origin_y_m\": %s},\n"
        " \"obstacle_map\": {\"x0_m\": %.9g, \"y0_m\": %.9g, \"cell_m\": %s, \"rows\": %d, "
        "\"cols\": %d}}\n",
        s.elapsed_s, static_cast<unsigned long long>(s.scans),
        static_cast<unsigned long long>(s.scans_mapped), static_cast<unsigned long long>(s.dropped),
        static_cast<unsigned long long>(s.poses), static_cast<unsigned long long>(s.rows_filtered),
        static_cast<unsigned long long>(s.beams_rejected), s.scans_per_s, s.latency_p50_ms,
        s.latency_p99_ms, static_cast<unsigned long long>(s.source.crc_errors),
        static_cast<unsigned long long>(s.source.resyncs),
        static_cast<unsigned long long>(s.source.reconnects), s.finished ? "true" : "false",
        window.config().rows, window.config().cols, window.config().m,
        FormatNumber(window.config().cell_m).c_str(), window.heading_rad(),
        static_cast<long long>(window.first_row()), static_cast<long long>(window.first_col()),
        FormatNumber(window.config().origin_x_m).c_str(),
        FormatNumber(window.config().origin_y_m).c_str(), o.x0_m, o.y0_m,
        FormatNumber(o.cell_m).c_str(), o.rows, o.cols);
    return buf;
}

}  // namespace casmap::pipeline
