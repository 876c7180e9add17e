#include "casmap/pipeline/connect_retry.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/drivers/serial_port.hpp"

namespace casmap::pipeline {

bool RetryWorthy(const ConnectFailure& failure) {
    // Presence is sampled on both sides of the attempt: sampling only after it lost the race
    // with `casmap serve` creating its link just after the attempt found no device (judged
    // final although the device was absent when the attempt ran).
    return failure.serial_error || !failure.present_before || !failure.present_after;
}

int ConnectWithRetry(const std::string& device, double timeout_s, const ConnectSteps& steps) {
    const double start_s = steps.now_s();
    double backoff_s = 0.1;
    for (int attempt = 1;; ++attempt) {
        ConnectFailure failure;
        failure.present_before = steps.device_present();
        try {
            steps.connect();
            return attempt;
        } catch (const std::exception& e) {
            failure.serial_error = dynamic_cast<const drivers::SerialError*>(&e) != nullptr;
            failure.present_after = steps.device_present();
            if (!RetryWorthy(failure)) {
                throw;
            }
            const double elapsed_s = steps.now_s() - start_s;
            const bool stop = steps.stop_requested && steps.stop_requested();
            if (stop || elapsed_s + backoff_s > timeout_s) {
                throw MakeInputError(
                    device, "device", device,
                    "no LMS 200 ready within timeout_s " + core::FormatNumber(timeout_s) + " s (" +
                        std::to_string(attempt) + " attempts; last: " + e.what() + ")");
            }
        }
        steps.sleep_s(backoff_s);
        backoff_s = std::min(1.0, 2.0 * backoff_s);
    }
}

ConnectSteps DeviceConnectSteps(drivers::Lms200Driver& driver,
                                const std::string& device,
                                std::function<bool()> stop_requested) {
    ConnectSteps steps;
    steps.connect = [&driver] { driver.Connect(); };
    steps.device_present = [device] {
        std::error_code ec;
        return std::filesystem::exists(device, ec);
    };
    steps.stop_requested = std::move(stop_requested);
    steps.now_s = [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    };
    steps.sleep_s = [](double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); };
    return steps;
}

}  // namespace casmap::pipeline
