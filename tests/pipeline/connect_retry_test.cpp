// pipeline::ConnectWithRetry (the start-up retry of `casmap record`) fed scripted sequences of
// device presence and attempt results on a fake clock, so that every order of events, the race
// with `casmap serve` creating its link included, is tested without timing; then the same race
// against a real virtual LMS 200 whose link appears right after the first attempt failed.
#include "casmap/pipeline/connect_retry.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "../drivers/test_source.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/serial_port.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::pipeline {
namespace {

const std::string kDevice = "/tmp/ttyLMS";

[[noreturn]] void Absent() {
    throw MakeInputError(kDevice, "device", "", "cannot open: No such file or directory");
}
[[noreturn]] void NotATerminal() { throw MakeInputError(kDevice, "device", "", "not a terminal"); }
[[noreturn]] void Silent() { throw drivers::SerialError(kDevice + ": no reply to status"); }
void Answers() {}

/// One scripted attempt: is the device there when it begins, what it does, is it there after.
struct Attempt {
    bool present_before;
    std::function<void()> result;
    bool present_after;
};

/// Plays `attempts` in order through ConnectSteps on a clock that only sleeps advance.
class Script {
public:
    explicit Script(std::vector<Attempt> attempts) : attempts_(std::move(attempts)) {}

    ConnectSteps Steps() {
        ConnectSteps s;
        s.device_present = [this] {
            const Attempt& a = Current();
            return in_attempt_ ? a.present_after : a.present_before;
        };
        s.connect = [this] {
            in_attempt_ = true;
            Current().result();
            in_attempt_ = false;  // not reached when the attempt throws
        };
        s.now_s = [this] { return clock_s_; };
        s.sleep_s = [this](double dt_s) {
            sleeps_s.push_back(dt_s);
            clock_s_ += dt_s;
            in_attempt_ = false;
            ++next_;
        };
        return s;
    }
    std::vector<double> sleeps_s;

private:
    const Attempt& Current() const {
        if (next_ >= attempts_.size()) {
            throw std::logic_error("more attempts than scripted");
        }
        return attempts_[next_];
    }
    std::vector<Attempt> attempts_;
    std::size_t next_ = 0;
    bool in_attempt_ = false;
    double clock_s_ = 100.0;
};

std::string ErrorOf(const std::function<void()>& call) {
    try {
        call();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ConnectRetry, RetryWorthyIsAbsenceOnEitherSideOrSilence) {
    EXPECT_FALSE(RetryWorthy({false, true, true}));   // there throughout: a genuine error
    EXPECT_TRUE(RetryWorthy({true, true, true}));     // silent or I/O error
    EXPECT_TRUE(RetryWorthy({false, false, false}));  // not there yet
    EXPECT_TRUE(RetryWorthy({false, false, true}));   // appeared while the attempt failed
    EXPECT_TRUE(RetryWorthy({false, true, false}));   // gone during the attempt
}

TEST(ConnectRetry, LinkCreatedJustAfterTheFailedOpenIsRetried) {
    // The flaky case of Serve.AServedRunIsRecordedBackWithItsPoses: the open finds no device,
    // serve creates its link before the failure is judged; the path exists by then.
    Script script({{false, Absent, true}, {true, Answers, true}});
    EXPECT_EQ(ConnectWithRetry(kDevice, 20.0, script.Steps()), 2);
    EXPECT_EQ(script.sleeps_s, std::vector<double>{0.1});
}

TEST(ConnectRetry, AbsentDeviceIsRetriedWithBackOffUntilTheTimeout) {
    std::vector<Attempt> absent(10, Attempt{false, Absent, false});
    Script script(absent);
    const std::string error =
        ErrorOf([&] { static_cast<void>(ConnectWithRetry(kDevice, 2.0, script.Steps())); });
    // Sleeps 0.1 0.2 0.4 0.8 end at 1.5 s; another 1 s would end past 2 s: 5 attempts.
    EXPECT_EQ(script.sleeps_s, (std::vector<double>{0.1, 0.2, 0.4, 0.8}));
    EXPECT_NE(error.find("no LMS 200 ready within timeout_s 2 s (5 attempts; last: "),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("cannot open: No such file or directory"), std::string::npos) << error;
    EXPECT_EQ(error.rfind(kDevice, 0), 0U) << error;
}

TEST(ConnectRetry, AnErrorOnADevicePresentThroughoutIsFinal) {
    Script script({{true, NotATerminal, true}});
    const std::string error =
        ErrorOf([&] { static_cast<void>(ConnectWithRetry(kDevice, 20.0, script.Steps())); });
    EXPECT_NE(error.find("not a terminal"), std::string::npos) << error;
    EXPECT_EQ(error.find("attempts"), std::string::npos) << error;
    EXPECT_TRUE(script.sleeps_s.empty());
}

TEST(ConnectRetry, SilenceAndAVanishedDeviceAreRetried) {
    Script script({{true, Silent, true}, {true, NotATerminal, false}, {true, Answers, true}});
    EXPECT_EQ(ConnectWithRetry(kDevice, 20.0, script.Steps()), 3);
    EXPECT_EQ(script.sleeps_s, (std::vector<double>{0.1, 0.2}));
}

TEST(ConnectRetry, StopEndsTheRetriesWithTheTimeoutError) {
    Script script({{false, Absent, false}, {false, Absent, false}});
    ConnectSteps steps = script.Steps();
    steps.stop_requested = [] { return true; };
    const std::string error =
        ErrorOf([&] { static_cast<void>(ConnectWithRetry(kDevice, 20.0, steps)); });
    EXPECT_NE(error.find("(1 attempts; last: "), std::string::npos) << error;
    EXPECT_TRUE(script.sleeps_s.empty());
}

TEST(ConnectRetry, DeviceLinkCreatedRightAfterTheFirstAttemptFailed) {
    // The race on real files: the first attempt fails on the missing link, then the virtual
    // LMS 200 creates it before ConnectWithRetry looks at the path again.
    drivers::testing::NumberedSource source;
    drivers::VirtualLms200Config vc;
    vc.link_path = "/tmp/casmap_pipeline_connect_race_" + std::to_string(getpid());
    std::filesystem::remove(vc.link_path);
    drivers::VirtualLms200 scanner(vc, source);
    drivers::DriverConfig dc;
    dc.device = vc.link_path;
    drivers::Lms200Driver driver(dc);
    ConnectSteps steps = DeviceConnectSteps(driver, vc.link_path, {});
    int failures = 0;
    steps.connect = [&] {
        try {
            driver.Connect();
        } catch (const InputError&) {
            if (++failures == 1) {
                scanner.Start();
            }
            throw;
        }
    };
    EXPECT_EQ(ConnectWithRetry(vc.link_path, 20.0, steps), 2);
    EXPECT_EQ(failures, 1);
    driver.Close();
    scanner.Stop();
}

}  // namespace
}  // namespace casmap::pipeline
