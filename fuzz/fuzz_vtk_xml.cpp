// VTK XML bytes (.vtu/.vtp, and .pvd collections) -> the XML readers; only InputError may escape.
#include "core/io/input_error.hpp"
#include "core/io/vtk_xml.hpp"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        faultline::core::parseVtkXml("fuzz.vtu", bytes);
    } catch (const faultline::core::InputError&) {
    }
    try {
        faultline::core::parseVtkCollection("fuzz.pvd", bytes);
    } catch (const faultline::core::InputError&) {
    }
    return 0;
}
