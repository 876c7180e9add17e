// The command boundary's mapping of library field names to flags (apps/casmap/flag_names.hpp).
#include "apps/casmap/flag_names.hpp"

#include <gtest/gtest.h>

#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::app {
namespace {

std::string MessageOf(const std::function<void()>& body) {
    try {
        body();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

const FlagNames kNames = {{"run", "--run"},
                          {"scene", "--scene"},
                          {"motion", "--motion"},
                          {"baud", "--baud"},
                          {"poses_out", "--poses-out"}};

TEST(WithCommandLineFlags, MapsFieldsAndTheFieldNamesOfTheRule) {
    const auto both = [] {
        throw MakeInputError("", "run / scene", "", "give either run or scene and motion");
    };
    EXPECT_EQ(MessageOf([&] { WithCommandLineFlags(kNames, both); }),
              "command line: --run / --scene (give either --run or --scene and --motion)");
    // Its own field's name stays a word ("baud"), paths and flags keep theirs.
    const auto baud = [] {
        throw MakeInputError("", "baud", "7", "the LMS 200 has 9600 baud; see /data/run.h5");
    };
    EXPECT_EQ(MessageOf([&] { WithCommandLineFlags(kNames, baud); }),
              "command line: --baud = 7 (the LMS 200 has 9600 baud; see /data/run.h5)");
}

TEST(WithCommandLineFlags, FileErrorsPassUnlessTheyAreAboutTheGivenPath) {
    const auto in_file = [] { throw MakeInputError("rig.yaml:3:3", "motion", "Q", "allowed: T"); };
    EXPECT_EQ(MessageOf([&] { WithCommandLineFlags(kNames, in_file); }),
              "rig.yaml:3:3: motion = Q (allowed: T)");
    const auto path = [] {
        throw MakeInputError("/x/p.txt", "poses_out", "", "folder /x does not exist");
    };
    EXPECT_EQ(MessageOf([&] {
                  WithCommandLineFlags(kNames, path, {{"poses_out", "/x/p.txt"}});
              }),
              "/x/p.txt: --poses-out (folder /x does not exist)");
    EXPECT_EQ(MessageOf([&] {
                  WithCommandLineFlags(kNames, path, {{"poses_out", "/y.txt"}});
              }),
              "/x/p.txt: poses_out (folder /x does not exist)");
    const auto unmapped = [] { throw MakeInputError("", "run / window", "", "rule"); };
    EXPECT_EQ(MessageOf([&] { WithCommandLineFlags(kNames, unmapped); }), "run / window (rule)");
}

TEST(WithSetFlag, NamesTheFlagInsteadOfTheSettingsList) {
    const auto bad = [] { throw MakeInputError("filter parameters", "k", "9", "allowed: 1..7"); };
    EXPECT_EQ(MessageOf([&] { WithSetFlag(bad); }), "--set: k = 9 (allowed: 1..7)");
    const auto other = [] { throw MakeInputError("active window", "m", "500", "rule"); };
    EXPECT_EQ(MessageOf([&] { WithSetFlag(other); }), "active window: m = 500 (rule)");
}

}  // namespace
}  // namespace casmap::app
