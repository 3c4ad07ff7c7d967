#include "core/view/framing.hpp"

#include "core/util/quantile.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace faultline::core {

namespace {

// The bulk along an axis: from this share of the centres to 1 minus it (strays on one side up to
// this share, falling grains, stay out of it). Beyond it by more than kMargin times its extent:
// a stray, if strays are at most kMostStrays of the centres. A uniform block reaches 0.06 of the
// bulk's extent beyond it, a cone's apex 0.6.
constexpr double kBulkShare = 0.05;
constexpr double kMargin = 1.0;
constexpr double kMostStrays = 0.05;

// Bounds of the finite centres within [limitLo, limitHi] on every axis, and how many finite
// centres lay outside.
struct Box {
    std::array<double, 3> lo{std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::infinity()};
    std::array<double, 3> hi{-std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
    std::size_t inside = 0, outside = 0;
    void join(const Box& o) {
        for (int a = 0; a < 3; ++a)
            lo[a] = std::min(lo[a], o.lo[a]), hi[a] = std::max(hi[a], o.hi[a]);
        inside += o.inside;
        outside += o.outside;
    }
};

Box boxWithin(const Frame& f, const std::array<double, 3>& limitLo,
              const std::array<double, 3>& limitHi) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, f.size(), 65536), Box{},
        [&](const tbb::blocked_range<std::size_t>& r, Box b) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const double p[3] = {f.x[i], f.y[i], f.z[i]};
                if (!std::isfinite(p[0] + p[1] + p[2]))
                    continue;
                bool in = true;
                for (int a = 0; a < 3; ++a)
                    in = in && p[a] >= limitLo[a] && p[a] <= limitHi[a];
                if (!in) {
                    ++b.outside;
                    continue;
                }
                ++b.inside;
                for (int a = 0; a < 3; ++a)
                    b.lo[a] = std::min(b.lo[a], p[a]), b.hi[a] = std::max(b.hi[a], p[a]);
            }
            return b;
        },
        [](Box a, const Box& b) {
            a.join(b);
            return a;
        });
}

} // namespace

Framing framingBounds(const Frame& frame) {
    Framing out;
    const std::size_t n = frame.size();
    if (n == 0)
        return out;
    // The bulk per axis from up to 65,536 evenly spaced centres.
    const std::size_t step = std::max<std::size_t>(1, n / 65536);
    std::array<double, 3> limitLo, limitHi;
    const std::vector<float>* axes[3] = {&frame.x, &frame.y, &frame.z};
    std::vector<float> sample;
    sample.reserve(n / step + 1);
    for (int a = 0; a < 3; ++a) {
        sample.clear();
        for (std::size_t i = 0; i < n; i += step)
            if (std::isfinite((*axes[a])[i]))
                sample.push_back((*axes[a])[i]);
        if (sample.empty())
            return out;
        const double low = quantile(sample, kBulkShare), high = quantile(sample, 1.0 - kBulkShare);
        const double margin = kMargin * (high - low);
        limitLo[a] = low - margin;
        limitHi[a] = high + margin;
    }
    const Box bulk = boxWithin(frame, limitLo, limitHi);
    if (bulk.inside == 0)
        return out;
    const std::size_t finite = bulk.inside + bulk.outside;
    if (bulk.outside == 0) { // no strays: every finite centre
        out.lo = bulk.lo, out.hi = bulk.hi;
        return out;
    }
    if (double(bulk.outside) > kMostStrays * double(finite)) { // a shape, not strays
        const double inf = std::numeric_limits<double>::infinity();
        const Box all = boxWithin(frame, {-inf, -inf, -inf}, {inf, inf, inf});
        out.lo = all.lo, out.hi = all.hi;
        return out;
    }
    out.lo = bulk.lo, out.hi = bulk.hi;
    out.strays = bulk.outside;
    return out;
}

} // namespace faultline::core
