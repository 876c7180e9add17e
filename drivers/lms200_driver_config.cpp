// Changes to a connected LMS 200: variant, output mode, configuration (EEPROM), status, reset
// (reference sections 2 and 4; sicktoolbox's SetSick* sequences of section 6.4).
#include <chrono>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/lms200_driver.hpp"

namespace casmap::drivers {
namespace {

std::string VariantText(const Variant& v) {
    return std::to_string(v.angle_deg) + "," + std::to_string(v.resolution_cdeg);
}

}  // namespace

void Lms200Driver::SetVariant(const Variant& variant) {
    if (!variant.IsValid()) {
        throw MakeInputError("LMS 200 driver", "variant", VariantText(variant),
                             "180,100 180,50 100,100 100,50 or 100,25 (deg, 1/100 deg)");
    }
    RequireConnected("SetVariant");
    info_.output.Validate(variant);  // a sub-range must fit the new variant
    const bool was = StopOutput();
    const VariantReply r = ParseVariantReply(
        Require(MakeVariantRequest(variant), config_.reply_timeout_s, "variant 0x3B"));
    if (!r.accepted) {
        throw MakeInputError(
            config_.device, "variant", VariantText(variant),
            "refused by the scanner (BB result 0, keeps " + VariantText(r.variant) + ")");
    }
    info_.variant = r.variant;
    config_.variant = r.variant;  // kept over reconnects
    if (was) {
        StartOutput();
    }
}

void Lms200Driver::SetOutputMode(const OutputMode& mode) {
    RequireConnected("SetOutputMode");
    mode.Validate(info_.variant);
    (void)StopOutput();
    info_.output = mode;
    config_.output = mode;  // kept over reconnects
    StartOutput();
}

ConfigBlock Lms200Driver::ReadConfig() {
    RequireConnected("ReadConfig");
    const bool was = StopOutput();
    info_.config = ParseConfigReply(
        Require(MakeReadConfigRequest(), config_.reply_timeout_s, "configuration 0x74"));
    info_.format = FormatOf(info_.config);
    if (was) {
        StartOutput();
    }
    return info_.config;
}

void Lms200Driver::WriteConfig(const ConfigBlock& config) {
    CheckConfigBlock(config, "LMS 200 driver: WriteConfig");
    RequireConnected("WriteConfig");
    if (config.bytes.size() != info_.config.bytes.size()) {
        throw MakeInputError(
            config_.device, "configuration size", std::to_string(config.bytes.size()),
            "the scanner's block has " + std::to_string(info_.config.bytes.size()) + " bytes");
    }
    const bool was = StopOutput();
    const std::uint8_t login =
        ParseModeReply(Require(MakeInstallationRequest(config_.password), config_.mode_timeout_s,
                               "installation 0x20 0x00"));
    if (login != 0) {
        throw MakeInputError(config_.device, "password", "(8 characters)",
                             login == 1
                                 ? "refused by the scanner (A0 01: wrong password)"
                                 : "refused by the scanner (A0 " + std::to_string(login) + ")");
    }
    // The scanner writes its EEPROM before it answers: seconds (reference section 1).
    const WriteConfigReply w = ParseWriteConfigReply(
        Require(MakeWriteConfigRequest(config), config_.write_timeout_s, "configuration 0x77"));
    (void)ParseModeReply(
        Require(MakeModeRequest(mode::kRequest), config_.mode_timeout_s, "request mode 0x25"));
    if (!w.accepted) {
        throw MakeInputError(config_.device, "configuration", "(0x77)",
                             "refused by the scanner (F7 result 0)");
    }
    info_.config = ParseConfigReply(
        Require(MakeReadConfigRequest(), config_.reply_timeout_s, "configuration 0x74"));
    if (info_.config != config) {
        throw SerialError(config_.device + ": configuration read back after 0x77 differs");
    }
    info_.format = FormatOf(info_.config);
    if (was) {
        StartOutput();
    }
}

void Lms200Driver::ApplyConfigChanges(const ConfigChanges& changes) {
    const ConfigBlock current = ReadConfig();
    const ConfigBlock wanted = changes.ApplyTo(current);
    if (wanted != current) {
        WriteConfig(wanted);
    }
}

DeviceStatus Lms200Driver::ReadStatus() {
    RequireConnected("ReadStatus");
    const bool was = StopOutput();
    info_.status =
        ParseStatusReply(Require(MakeStatusRequest(), config_.reply_timeout_s, "status 0x31"));
    if (was) {
        StartOutput();
    }
    return info_.status;
}

std::string Lms200Driver::Reset() {
    RequireConnected("Reset");
    (void)StopOutput();
    (void)Require(MakeResetRequest(), config_.reply_timeout_s, "reset 0x10", cmd::kResetReply);
    // The scanner restarts at its power-on rate and announces itself with 0x90.
    port_->SetBaud(9600);
    parser_.Reset();
    awaited_.reset();
    awaited_cmd_ = cmd::kPowerOn;
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(config_.reset_timeout_s));
    while (!awaited_ && std::chrono::steady_clock::now() < deadline) {
        (void)ReadSome(config_.inter_byte_timeout_s);
    }
    awaited_cmd_ = 0;
    if (!awaited_ || awaited_->command != cmd::kPowerOn) {
        throw SerialError(config_.device + ": no power-on telegram 0x90 after reset");
    }
    const std::string text(awaited_->data.begin(), awaited_->data.end());
    Initialise();
    return text;
}

}  // namespace casmap::drivers
