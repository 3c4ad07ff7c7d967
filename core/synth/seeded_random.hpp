// SeededRandom: a small, portable random stream (SplitMix64) with our own distributions.
// std:: distributions differ between standard libraries; synthetic models must not.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace faultline::core {

class SeededRandom {
  public:
    explicit SeededRandom(std::uint64_t seed) : m_state(seed) {}

    std::uint64_t nextU64() {
        std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(nextU64() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

    // Standard normal by Box-Muller (one value per call; the pair's second half is dropped to
    // keep the stream position a simple function of the call count).
    double normal(double mean, double sd) {
        const double u1 = 1.0 - uniform(); // (0, 1]
        const double u2 = uniform();
        return mean + sd * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }

    // Weibull with shape k and scale lambda, by inverting its distribution function.
    double weibull(double shape, double scale) {
        const double u = 1.0 - uniform(); // (0, 1]
        return scale * std::pow(-std::log(u), 1.0 / shape);
    }

  private:
    std::uint64_t m_state;
};

} // namespace faultline::core
