// Session file text -> parse and validate; anything but InputError is a bug.
#include "core/io/input_error.hpp"
#include "core/session/session_json.hpp"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const auto doc = faultline::core::parseJsonText(text, "fuzz.faultline.json");
        faultline::core::sessionFromJson(doc, "/nonexistent", "fuzz.faultline.json");
    } catch (const faultline::core::InputError&) {
    }
    return 0;
}
