// VTK legacy bytes -> parseVtkLegacy; anything but InputError is a bug.
#include "core/io/input_error.hpp"
#include "core/io/vtk_legacy.hpp"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        faultline::core::parseVtkLegacy("fuzz.vtk", bytes);
    } catch (const faultline::core::InputError&) {
    }
    return 0;
}
