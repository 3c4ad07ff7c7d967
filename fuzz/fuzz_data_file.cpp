// Any bytes as a data file: format detection, gzip, frame indexing, every reader, every frame.
#include "core/io/input_error.hpp"
#include "core/data/dataset.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    faultline::fuzz::MemoryFile file(data, size);
    try {
        auto ds = faultline::core::Dataset::open({file.path()});
        for (std::size_t k = 0; k < ds->frameCount() && k < 4; ++k)
            ds->frame(k);
    } catch (const faultline::core::InputError&) {
    }
    return 0;
}
