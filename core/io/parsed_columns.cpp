#include "core/io/parsed_columns.hpp"

#include "core/io/input_error.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace faultline::core {

void completeParsedFrame(Frame& frame, ParsedColumns&& parsed, const std::string& path,
                         std::uint64_t headerLine) {
    if (!parsed.hasIds) {
        frame.idsAreRowNumbers = true;
        for (std::size_t i = 0; i < frame.ids.size(); ++i)
            frame.ids[i] = static_cast<std::int64_t>(i);
    }
    if (parsed.radius == ParsedColumns::Radius::Missing) {
        frame.radiusIsDefault = true;
        std::fill(frame.radius.begin(), frame.radius.end(), kDefaultRadius);
    } else if (parsed.radius == ParsedColumns::Radius::Diameter) {
        for (float& r : frame.radius)
            r *= 0.5f;
    }
    std::vector<std::size_t> columns;
    for (std::size_t c = 0; c < parsed.names.size(); ++c)
        if (parsed.isAttribute[c])
            columns.push_back(c);
    frame.attributes.resize(columns.size());
    tbb::parallel_for(std::size_t(0), columns.size(), [&](std::size_t k) {
        const std::size_t c = columns[k];
        const bool integral = !parsed.targets[c].sawNonInteger &&
                              looksLikeIntegerColumn(parsed.names[c], parsed.values[c]);
        frame.attributes[k] = makeAttribute(parsed.names[c], std::move(parsed.values[c]), integral);
    });
    try {
        frame.finalize();
    } catch (const std::invalid_argument& e) {
        throw InputError(path, InputError::Where::Line, headerLine, e.what());
    }
}

} // namespace faultline::core
