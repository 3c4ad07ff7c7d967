#include "core/model/frame_difference.hpp"

#include "core/model/periodic_cell.hpp"
#include "core/util/quantile.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace faultline::core {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr std::size_t kGrain = 16384;

// A column of a frame as doubles by row: an attribute or one of the fixed columns.
class ColumnReader {
  public:
    ColumnReader(const Frame& f, std::string_view name) {
        if (const AttributeColumn* c = f.attribute(name)) {
            if (c->type == ColumnType::Float32)
                m_floats = c->floats.data();
            else
                m_ints = c->ints.data();
        } else if (name == "x") {
            m_floats = f.x.data();
        } else if (name == "y") {
            m_floats = f.y.data();
        } else if (name == "z") {
            m_floats = f.z.data();
        } else if (name == "radius") {
            m_floats = f.radius.data();
        } else {
            m_missing = true;
        }
    }
    bool missing() const { return m_missing; }
    double operator()(std::size_t row) const {
        return m_floats ? static_cast<double>(m_floats[row]) : static_cast<double>(m_ints[row]);
    }

  private:
    const float* m_floats = nullptr;
    const std::int32_t* m_ints = nullptr;
    bool m_missing = false;
};

bool sameIdOrder(const Frame& a, const Frame& b) {
    return a.ids.size() == b.ids.size() &&
           (a.ids.empty() ||
            std::memcmp(a.ids.data(), b.ids.data(), a.ids.size() * sizeof(std::int64_t)) == 0);
}

// For each row of `now`, fn(row, referenceRow or -1).
template <typename Fn> void forMatchedRows(const Frame& now, const Frame& reference, Fn fn) {
    const bool aligned = sameIdOrder(now, reference);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, now.size(), kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t row = r.begin(); row != r.end(); ++row) {
                              if (aligned) {
                                  fn(row, static_cast<long long>(row));
                                  continue;
                              }
                              const auto ref = reference.rowOf(now.ids[row]);
                              fn(row, ref ? static_cast<long long>(*ref) : -1LL);
                          }
                      });
}

} // namespace

void cacheColumnRange(AttributeColumn& c) {
    using Range = std::pair<double, double>;
    const Range empty{std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
    const Range r = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, c.floats.size(), kGrain), empty,
        [&](const tbb::blocked_range<std::size_t>& b, Range acc) {
            for (std::size_t k = b.begin(); k != b.end(); ++k) {
                const double v = c.floats[k];
                if (v < acc.first) // false for NaN
                    acc.first = v;
                if (v > acc.second)
                    acc.second = v;
            }
            return acc;
        },
        [](Range a, Range b) {
            return Range{std::min(a.first, b.first), std::max(a.second, b.second)};
        });
    if (r.first > r.second) {
        c.min = c.max = 0.0; // empty or all NaN, as Frame::finalize does
    } else {
        c.min = r.first;
        c.max = r.second;
    }
}

AttributeColumn variableChange(const Frame& now, const Frame& reference,
                               std::string_view variable) {
    const ColumnReader current(now, variable);
    if (current.missing())
        throw std::invalid_argument("no variable '" + std::string(variable) + "' in this frame");
    const ColumnReader before(reference, variable);
    AttributeColumn out;
    out.name = std::string(variable) + " change";
    out.type = ColumnType::Float32;
    out.floats.assign(now.size(), kNaN);
    if (!before.missing())
        forMatchedRows(now, reference, [&](std::size_t row, long long ref) {
            if (ref >= 0)
                out.floats[row] =
                    static_cast<float>(current(row) - before(static_cast<std::size_t>(ref)));
        });
    cacheColumnRange(out);
    return out;
}

AttributeColumn displacementSince(const Frame& now, const Frame& reference) {
    const PeriodicCell cell(reference.box);
    AttributeColumn out;
    out.name = "displacement";
    out.type = ColumnType::Float32;
    out.floats.assign(now.size(), kNaN);
    forMatchedRows(now, reference, [&](std::size_t row, long long ref) {
        if (ref < 0)
            return;
        const auto r = static_cast<std::size_t>(ref);
        double dx = double(now.x[row]) - reference.x[r];
        double dy = double(now.y[row]) - reference.y[r];
        double dz = double(now.z[row]) - reference.z[r];
        if (cell.any)
            cell.wrap(dx, dy, dz);
        out.floats[row] = static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz));
    });
    cacheColumnRange(out);
    return out;
}

std::optional<std::pair<double, double>> maskedRange(const Frame& frame, std::string_view variable,
                                                     const std::vector<std::uint8_t>& mask) {
    const ColumnReader column(frame, variable);
    if (column.missing() || mask.size() != frame.size())
        return std::nullopt;
    using Range = std::pair<double, double>;
    constexpr Range kEmpty{std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
    const Range r = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, frame.size(), kGrain), kEmpty,
        [&](const tbb::blocked_range<std::size_t>& rows, Range acc) {
            for (std::size_t row = rows.begin(); row != rows.end(); ++row) {
                if (!mask[row])
                    continue;
                const double v = column(row);
                if (std::isfinite(v)) {
                    acc.first = std::min(acc.first, v);
                    acc.second = std::max(acc.second, v);
                }
            }
            return acc;
        },
        [](Range a, Range b) {
            return Range{std::min(a.first, b.first), std::max(a.second, b.second)};
        });
    if (r.first > r.second)
        return std::nullopt;
    return r;
}

std::optional<std::pair<double, double>> maskedQuantiles(const Frame& frame,
                                                         std::string_view variable,
                                                         const std::vector<std::uint8_t>& mask,
                                                         double low, double high) {
    const ColumnReader column(frame, variable);
    if (column.missing() || mask.size() != frame.size() || !(low >= 0 && low < high && high <= 1))
        return std::nullopt;
    // The finite values shown (the columns' values are floats or ints), gathered in parallel by
    // blocks: counted, then each block written at its place; without a branch per row (the
    // mask is as random as a threshold makes it: a mispredicted branch a row took 5 ms a
    // million rows).
    constexpr std::size_t kBlock = 65536;
    const std::size_t rows = frame.size(), blocks = (rows + kBlock - 1) / kBlock;
    std::vector<std::size_t> start(blocks + 1, 0);
    auto keep = [&](std::size_t row, float& v) {
        v = static_cast<float>(column(row));
        return (mask[row] != 0) & std::isfinite(v);
    };
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
        std::size_t n = 0;
        float v;
        for (std::size_t row = b * kBlock; row < std::min(rows, (b + 1) * kBlock); ++row)
            n += keep(row, v);
        start[b + 1] = n;
    });
    for (std::size_t b = 0; b < blocks; ++b)
        start[b + 1] += start[b];
    // Each row's value is written at the next free slot, then kept by moving past it or not;
    // past the block's last kept value the slot is the next block's, and nothing is written.
    std::vector<float> values(start[blocks]);
    tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
        float* out = values.data() + start[b];
        const float* end = values.data() + start[b + 1];
        for (std::size_t row = b * kBlock; row < std::min(rows, (b + 1) * kBlock) && out < end;
             ++row) {
            float v;
            const bool kept = keep(row, v);
            *out = v;
            out += kept;
        }
    });
    if (values.empty())
        return std::nullopt;
    return quantilePair(values, low, high);
}

} // namespace faultline::core
