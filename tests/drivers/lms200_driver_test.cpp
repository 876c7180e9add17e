// Bad input for the driver: missing device, not a terminal, wrong baud, a line of noise.
#include "casmap/drivers/lms200_driver.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <random>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pseudo_terminal.hpp"

namespace casmap::drivers {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string MessageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no InputError";
}

TEST(Lms200Driver, MissingDeviceIsAnInputErrorNamingThePath) {
    DriverConfig c;
    c.device = "/nonexistent/ttyCASMAP";
    Lms200Driver d(c);
    const std::string m = MessageOf([&] { d.Connect(); });
    EXPECT_NE(m.find("/nonexistent/ttyCASMAP"), std::string::npos) << m;
}

TEST(Lms200Driver, NonTerminalsAreInputErrors) {
    DriverConfig c;
    c.device = "/dev/null";  // a character device, but no terminal
    Lms200Driver d(c);
    EXPECT_NE(MessageOf([&] { d.Connect(); }).find("not a terminal"), std::string::npos);
    const std::string file = "/tmp/casmap_driver_test_" + std::to_string(getpid()) + ".txt";
    std::ofstream(file) << "hello";
    c.device = file;
    Lms200Driver f(c);
    EXPECT_NE(MessageOf([&] { f.Connect(); }).find("not a terminal"), std::string::npos);
    std::remove(file.c_str());
}

TEST(Lms200Driver, BaudRatesTheLmsDoesNotHaveAreRejected) {
    for (const int baud : {0, 57600, 115200, 250000}) {
        DriverConfig c;
        c.device = "/dev/ttyS0";
        c.baud = baud;
        const std::string m = MessageOf([&] { Lms200Driver d(c); });
        EXPECT_EQ(m, "baud = " + std::to_string(baud) +
                         " (the LMS 200 has 9600, 19200, 38400 or 500000 baud)");
    }
}

TEST(Lms200Driver, ALineOfNoiseIsCountedAndGivesUpInBoundedTime) {
    const std::string link = "/tmp/casmap_driver_noise_" + std::to_string(getpid());
    PseudoTerminal pty;
    pty.Open(link, 9600);
    std::atomic<bool> stop{false};
    std::thread noise([&] {
        const unsigned seed = 99;
        std::mt19937 rng(seed);
        std::uint8_t buf[16];
        while (!stop) {
            for (auto& b : buf) {
                b = static_cast<std::uint8_t>(rng());
            }
            (void)!write(pty.master_fd(), buf, sizeof(buf));
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    });
    DriverConfig c;
    c.device = link;
    c.tries = 1;
    c.autodetect = false;
    Lms200Driver d(c);
    const Clock::time_point t0 = Clock::now();
    EXPECT_THROW(d.Connect(), SerialError);
    EXPECT_LT(Since(t0), 2.0);
    const Clock::time_point t1 = Clock::now();
    EXPECT_FALSE(d.NextScan(0.5).has_value());  // keeps trying to reconnect, but returns
    EXPECT_LT(Since(t1), 2.5);
    const DriverCounters k = d.counters();
    EXPECT_GT(k.bytes, 0U);
    EXPECT_EQ(k.scans, 0U);
    EXPECT_EQ(k.telegrams, 0U);
    EXPECT_GT(k.dropped_bytes, 0U);
    stop = true;
    noise.join();
}

}  // namespace
}  // namespace casmap::drivers
