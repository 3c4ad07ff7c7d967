// quantilePair: the two quantiles quantile() gives (numpy's type 7), by bins above 65,536 values.
#include "core/util/quantile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace faultline::core;

namespace {

// Both ways, each on its own copy (both reorder).
void expectSame(const std::vector<float>& values, double low, double high) {
    std::vector<float> a = values, b = values, c = values;
    const auto pair = quantilePair(a, low, high);
    EXPECT_EQ(pair.first, quantile(b, low)) << values.size() << " values, p" << low;
    EXPECT_EQ(pair.second, quantile(c, high)) << values.size() << " values, p" << high;
}

} // namespace

TEST(Quantile, PairAgreesWithSelectionOnEveryKindOfSample) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(-3.0f, 5.0f);
    std::exponential_distribution<float> tail(4.0f);
    for (std::size_t n : {1u, 2u, 100u, 65536u, 65537u, 200000u, 1000003u}) {
        std::vector<float> u(n), strain(n), few(n), same(n, 0.25f);
        for (std::size_t i = 0; i < n; ++i) {
            u[i] = uniform(rng);
            // Strain from motion: most values small, a few grains hundreds of times larger.
            strain[i] = i % 997 == 0 ? 500.0f + float(i % 7) : tail(rng) * 0.1f;
            few[i] = float(i % 5); // ties everywhere
        }
        for (const auto& [low, high] : {std::pair{0.01, 0.99}, std::pair{0.0, 1.0},
                                        std::pair{0.25, 0.75}, std::pair{0.5, 0.51}}) {
            expectSame(u, low, high);
            expectSame(strain, low, high);
            expectSame(few, low, high);
            expectSame(same, low, high);
        }
    }
    // A huge outlier puts nearly every value in the lowest bin: still exact.
    std::vector<float> outlier(300000);
    for (std::size_t i = 0; i < outlier.size(); ++i)
        outlier[i] = float(i % 1000) * 1e-3f;
    outlier[12345] = 3e38f;
    expectSame(outlier, 0.01, 0.99);
    // An infinity (maskedQuantiles keeps finite values only): the selection's answer.
    outlier[777] = INFINITY;
    expectSame(outlier, 0.25, 0.75);
}
