#pragma once

// The start-up retry of `casmap record` (pipeline::Record): a scanner that is not there yet (a
// `casmap serve` that has not made its device link, a scanner powering up) is retried with
// back-off until timeout_s; a device that is there but unusable fails at once. The device's
// presence, the clock and the sleep are passed in, so a test can script the order of events.
// Private to the pipeline (not installed).

#include <functional>
#include <string>

#include "casmap/drivers/lms200_driver.hpp"

namespace casmap::pipeline {

/// One failed connection attempt: how it failed and whether the device path existed when it
/// began and once it had failed.
struct ConnectFailure {
    bool serial_error = false;  ///< drivers::SerialError: I/O failed or no LMS answered
    bool present_before = true;
    bool present_after = true;
};

/// True when the failure is worth another attempt: an I/O failure or silence, or a device path
/// absent before or after the attempt (not there yet, created while the attempt failed on its
/// absence, or gone). Any other failure on a path present throughout (not a terminal,
/// permission denied, a setting refused by the scanner) is final.
[[nodiscard]] bool RetryWorthy(const ConnectFailure& failure);

/// What ConnectWithRetry calls; all but stop_requested must be set.
struct ConnectSteps {
    std::function<void()> connect;         ///< one attempt; throws on failure
    std::function<bool()> device_present;  ///< does the device path exist now?
    std::function<bool()> stop_requested;  ///< empty: never
    std::function<double()> now_s;         ///< a monotonic clock, s
    std::function<void(double)> sleep_s;   ///< waits that many s
};

/// Calls steps.connect until it succeeds and returns the number of attempts. After a
/// RetryWorthy failure it sleeps 0.1 s (doubling to 1 s) and tries again, unless stop was
/// requested or the sleep would end past timeout_s after the first attempt began: then it throws
/// InputError(device, "device") "no LMS 200 ready within timeout_s ..." naming the attempts and
/// the last error. Any other failure is rethrown as it is.
int ConnectWithRetry(const std::string& device, double timeout_s, const ConnectSteps& steps);

/// The steps for `driver` on its device path `device`: driver.Connect(), std::filesystem::exists
/// (an error reading the path counts as absent), the steady clock, std::this_thread::sleep_for.
[[nodiscard]] ConnectSteps DeviceConnectSteps(drivers::Lms200Driver& driver,
                                              const std::string& device,
                                              std::function<bool()> stop_requested);

}  // namespace casmap::pipeline
