// The virtual LMS 200's EEPROM: its configuration block in a small text file, so a restarted
// virtual scanner keeps what a 0x77 wrote (as the real unit keeps it over power cycles).
//
//   # casmap virtual LMS 200 EEPROM: configuration block (0x74 / 0x77), hex
//   config: 00 00 00 00 00 00 01 ...
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers {

ConfigBlock ReadEepromFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) {
        throw MakeInputError(path, "", "", "cannot be read");
    }
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (line.empty() || line[0] == '#') {
            continue;
        }
        const std::string where = path + ":" + std::to_string(line_no);
        if (line.rfind("config:", 0) != 0) {
            throw MakeInputError(where, "line", line.substr(0, 30), "expected 'config: HEX ...'");
        }
        std::istringstream hex(line.substr(7));
        ConfigBlock c;
        c.bytes.clear();
        std::string token;
        while (hex >> token) {
            if (token.size() != 2 ||
                token.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) {
                throw MakeInputError(where, "config", token.substr(0, 8),
                                     "two hex digits per byte");
            }
            if (c.bytes.size() >= ConfigBlock::kLongSize) {
                throw MakeInputError(where, "config", "more bytes", "34 or 32 bytes");
            }
            c.bytes.push_back(static_cast<std::uint8_t>(std::stoul(token, nullptr, 16)));
        }
        CheckConfigBlock(c, where);
        return c;
    }
    throw MakeInputError(path, "config", "", "missing ('config: HEX ...')");
}

void WriteEepromFile(const std::string& path, const ConfigBlock& config) {
    std::string text = "# casmap virtual LMS 200 EEPROM: configuration block (0x74 / 0x77), hex\n";
    text += "config:";
    for (const std::uint8_t b : config.bytes) {
        char buf[4];
        std::snprintf(buf, sizeof(buf), " %02X", b);
        text += buf;
    }
    text += "\n";
    const std::string tmp = path + ".tmp" + std::to_string(getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            std::remove(tmp.c_str());
            throw MakeInputError(path, "", "", "cannot be written (EEPROM file)");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw MakeInputError(path, "", "", "cannot be replaced (EEPROM file)");
    }
}

}  // namespace casmap::drivers
