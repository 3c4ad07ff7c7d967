#include "core/model/frame.hpp"

#include "core/util/ascii.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace faultline::core {

namespace {
constexpr std::uint32_t kNoRow = std::numeric_limits<std::uint32_t>::max();

template <typename T> void rangeOf(const std::vector<T>& values, double& lo, double& hi) {
    double mn = std::numeric_limits<double>::infinity();
    double mx = -mn;
    for (T v : values) {
        const double d = static_cast<double>(v);
        if (d < mn)
            mn = d;
        if (d > mx)
            mx = d;
    }
    if (mn > mx)
        mn = mx = 0.0; // empty or all NaN
    lo = mn;
    hi = mx;
}
} // namespace

bool AttributeColumn::hasNoValue() const {
    if (!mayHaveNoValue())
        return false;
    return std::none_of(floats.begin(), floats.end(), [](float x) { return std::isfinite(x); });
}

const AttributeColumn* Frame::attribute(std::string_view name) const {
    for (const auto& c : attributes)
        if (c.name == name)
            return &c;
    return nullptr;
}

AttributeColumn* Frame::attribute(std::string_view name) {
    for (auto& c : attributes)
        if (c.name == name)
            return &c;
    return nullptr;
}

std::vector<std::string> Frame::attributeNames() const {
    std::vector<std::string> names;
    names.reserve(attributes.size());
    for (const auto& c : attributes)
        names.push_back(c.name);
    return names;
}

void Frame::finalize() {
    const std::size_t n = ids.size();
    if (n > kNoRow - 1)
        throw std::invalid_argument("frame has more than 4 billion particles");
    if (x.size() != n || y.size() != n || z.size() != n || radius.size() != n)
        throw std::invalid_argument("frame columns have different lengths");
    for (auto& c : attributes)
        if (c.size() != n)
            throw std::invalid_argument("attribute '" + c.name + "' has " +
                                        std::to_string(c.size()) + " values for " +
                                        std::to_string(n) + " particles");
    // Ranges of every column at once: each is a pass over memory, independent of the others.
    const std::size_t tasks = attributes.size() + 4;
    double axisRange[3][2] = {};
    double radiusSum = 0;
    std::size_t radiusCount = 0;
    double radiusLo = std::numeric_limits<double>::infinity(), radiusHi = -radiusLo;
    tbb::parallel_for(std::size_t(0), tasks, [&](std::size_t k) {
        if (k < attributes.size()) {
            auto& c = attributes[k];
            if (c.type == ColumnType::Float32)
                rangeOf(c.floats, c.min, c.max);
            else
                rangeOf(c.ints, c.min, c.max);
        } else if (k == attributes.size() + 3) {
            for (float r : radius)
                if (std::isfinite(r)) {
                    radiusLo = std::min(radiusLo, double(r));
                    radiusHi = std::max(radiusHi, double(r));
                    if (r > 0) {
                        radiusSum += r;
                        ++radiusCount;
                    }
                }
        } else {
            const std::vector<float>* axes[3] = {&x, &y, &z};
            const std::size_t a = k - attributes.size();
            rangeOf(*axes[a], axisRange[a][0], axisRange[a][1]);
        }
    });
    m_meanRadius = radiusCount ? radiusSum / double(radiusCount) : 0.0;
    m_radiusRange = {radiusLo, radiusHi};
    for (int a = 0; a < 3; ++a) {
        m_centreMin[a] = static_cast<float>(axisRange[a][0]);
        m_centreMax[a] = static_cast<float>(axisRange[a][1]);
    }
    if (!box.known) {
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = m_centreMin[a];
            box.hi[a] = m_centreMax[a];
        }
    }

    // id -> row: a direct table when ids are dense (4 bytes per id in range), else rows sorted
    // by id (4 bytes per particle) searched by bisection. Either way about 4 bytes a particle.
    m_rowById.clear();
    m_rowsSortedById.clear();
    m_idBase = 0;
    if (n == 0)
        return;
    auto [mnIt, mxIt] = std::minmax_element(ids.begin(), ids.end());
    const std::int64_t idMin = *mnIt, idMax = *mxIt;
    const auto span =
        static_cast<unsigned long long>(idMax) - static_cast<unsigned long long>(idMin);
    if (span <= 2ull * n + 1024ull) {
        m_idBase = idMin;
        m_rowById.assign(span + 1, kNoRow);
        for (std::size_t row = 0; row < n; ++row) {
            auto& slot = m_rowById[static_cast<std::size_t>(ids[row] - idMin)];
            if (slot != kNoRow)
                throw std::invalid_argument("particle id " + std::to_string(ids[row]) +
                                            " appears twice");
            slot = static_cast<std::uint32_t>(row);
        }
    } else {
        m_rowsSortedById.resize(n);
        for (std::size_t row = 0; row < n; ++row)
            m_rowsSortedById[row] = static_cast<std::uint32_t>(row);
        std::sort(m_rowsSortedById.begin(), m_rowsSortedById.end(),
                  [this](std::uint32_t a, std::uint32_t b) { return ids[a] < ids[b]; });
        for (std::size_t k = 1; k < n; ++k)
            if (ids[m_rowsSortedById[k]] == ids[m_rowsSortedById[k - 1]])
                throw std::invalid_argument(
                    "particle id " + std::to_string(ids[m_rowsSortedById[k]]) + " appears twice");
    }
}

AttributeColumn makeAttribute(std::string name, std::vector<float>&& values, bool integral) {
    AttributeColumn c;
    c.name = std::move(name);
    constexpr float kExactIntLimit = 16777216.0f; // 2^24: larger integers are not exact as float
    if (integral)
        for (float v : values)
            if (!(std::fabs(v) <= kExactIntLimit)) {
                integral = false;
                break;
            }
    if (integral) {
        c.type = ColumnType::Int32;
        c.ints.resize(values.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            c.ints[i] = static_cast<std::int32_t>(values[i]);
    } else {
        c.type = ColumnType::Float32;
        c.floats = std::move(values);
    }
    return c;
}

bool looksLikeIntegerColumn(std::string_view name, const std::vector<float>& values) {
    static constexpr std::string_view kCounting[] = {
        "type", "mol",     "molecule",     "proc",    "procp1",       "ix",
        "iy",   "iz",      "image",        "species", "speciestype",  "layer",
        "band", "cluster", "broken_bonds", "bonds",   "coordination", "contacts",
        "flag", "group",   "index",        "count"};
    const std::string lower = asciiLower(name);
    for (std::string_view known : kCounting)
        if (lower == known ||
            (lower.size() > known.size() &&
             lower.compare(lower.size() - known.size(), known.size(), known) == 0 &&
             (lower[lower.size() - known.size() - 1] == '_')))
            return true;
    for (float v : values)
        if (v != values.front())
            return true;
    return false;
}

namespace {
// The dense map's row of `id` (kNoRow: absent). Below the base, the unsigned offset wraps past
// the table's size.
inline std::uint32_t denseRow(const std::vector<std::uint32_t>& table, std::int64_t base,
                              std::int64_t id) {
    const auto offset = static_cast<unsigned long long>(id) - static_cast<unsigned long long>(base);
    return id >= base && offset < table.size() ? table[offset] : kNoRow;
}
} // namespace

void Frame::rowsOf(std::span<const std::int64_t> wanted, std::uint32_t* out) const {
    if (!m_rowById.empty()) {
        for (std::size_t k = 0; k < wanted.size(); ++k)
            out[k] = denseRow(m_rowById, m_idBase, wanted[k]);
        return;
    }
    for (std::size_t k = 0; k < wanted.size(); ++k) {
        const auto row = rowOf(wanted[k]);
        out[k] = row ? static_cast<std::uint32_t>(*row) : kNoRow;
    }
}

std::optional<std::size_t> Frame::rowOf(std::int64_t id) const {
    if (!m_rowById.empty()) {
        const std::uint32_t row = denseRow(m_rowById, m_idBase, id);
        if (row == kNoRow)
            return std::nullopt;
        return row;
    }
    auto it = std::lower_bound(m_rowsSortedById.begin(), m_rowsSortedById.end(), id,
                               [this](std::uint32_t row, std::int64_t v) { return ids[row] < v; });
    if (it == m_rowsSortedById.end() || ids[*it] != id)
        return std::nullopt;
    return *it;
}

std::size_t Frame::memoryBytes() const {
    std::size_t bytes =
        ids.capacity() * sizeof(std::int64_t) +
        (x.capacity() + y.capacity() + z.capacity() + radius.capacity()) * sizeof(float) +
        (m_rowById.capacity() + m_rowsSortedById.capacity()) * sizeof(std::uint32_t);
    for (const auto& c : attributes)
        bytes += c.floats.capacity() * sizeof(float) + c.ints.capacity() * sizeof(std::int32_t) +
                 c.name.capacity();
    return bytes;
}

} // namespace faultline::core
