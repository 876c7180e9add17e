#pragma once

// Test helpers for the InputError a call throws: its message, or the field it names (checking
// that a library error names no command-line flag).

#include <gtest/gtest.h>

#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::test {

/// The message of the InputError `call()` throws; "(no error)" when it throws none.
template <typename Call>
std::string ErrorOf(const Call& call) {
    try {
        call();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

/// The field of the InputError `call()` throws ("" when none), failing the test if the message
/// names a flag ("--"): libraries name the fields of their options structs.
template <typename Call>
std::string FieldOfError(const Call& call) {
    try {
        call();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
        return e.field();
    }
    return "";
}

}  // namespace casmap::test
