// LAMMPS dump text -> parseLammpsDumpFrame; anything but InputError is a bug.
#include "core/io/input_error.hpp"
#include "core/io/lammps_dump.hpp"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        faultline::core::parseLammpsDumpFrame("fuzz.dump", text);
    } catch (const faultline::core::InputError&) {
    }
    return 0;
}
