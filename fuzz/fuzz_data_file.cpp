// Any bytes as a data file: format detection, gzip, frame indexing, every reader, every frame;
// then the frames again with strain from motion (incremental and cumulative) derived from
// whatever centres, boxes and radii the reader let through, where strain.add would take them.
#include "core/data/dataset.hpp"
#include "core/io/input_error.hpp"
#include "core/motion/strain_from_motion.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace faultline::core;
    faultline::fuzz::MemoryFile file(data, size);
    try {
        auto ds = Dataset::open({file.path()});
        const std::size_t frames = std::min<std::size_t>(ds->frameCount(), 4);
        for (std::size_t k = 0; k < frames; ++k)
            ds->frame(k);
        if (frames == 0)
            return 0;
        // As strain.add: not where the automatic cutoff takes in most of a large model.
        const auto first = ds->frame(0);
        if (strainNeighboursWithin(*first, defaultStrainCutoff(*first)) >
            kMaxAutomaticStrainNeighbours)
            return 0;
        ds->setStrains({StrainSpec{true, -1, 0, "inc_"}, StrainSpec{false, 0, 0, ""}});
        for (std::size_t k = 0; k < frames; ++k)
            ds->frame(k);
    } catch (const InputError&) {
    }
    return 0;
}
