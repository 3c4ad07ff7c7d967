#include "core/view/triangle_depth_order.hpp"

#include <array>
#include <cassert>
#include <cstring>

namespace faultline::core {

namespace {

// Unsigned keys that sort like the floats they come from, largest float first.
std::uint32_t descendingKey(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const std::uint32_t ascending = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
    return ~ascending;
}

// Stable least-significant-digit radix sort of `order` by `keys` (both permuted together),
// eleven bits per pass; a pass where every key has the same digit is skipped.
void radixSort(std::vector<std::uint32_t>& keys, std::vector<std::uint32_t>& order,
               std::vector<std::uint32_t>& keysTmp, std::vector<std::uint32_t>& orderTmp) {
    constexpr int kBits = 11;
    constexpr std::uint32_t kBuckets = 1u << kBits;
    const std::size_t n = keys.size();
    keysTmp.resize(n);
    orderTmp.resize(n);
    std::array<std::uint32_t, kBuckets> count;
    for (int shift = 0; shift < 32; shift += kBits) {
        count.fill(0);
        for (std::uint32_t k : keys)
            ++count[(k >> shift) & (kBuckets - 1)];
        if (count[(keys[0] >> shift) & (kBuckets - 1)] == n)
            continue;
        std::uint32_t sum = 0;
        for (std::uint32_t& c : count) {
            const std::uint32_t here = c;
            c = sum;
            sum += here;
        }
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t slot = count[(keys[i] >> shift) & (kBuckets - 1)]++;
            keysTmp[slot] = keys[i];
            orderTmp[slot] = order[i];
        }
        keys.swap(keysTmp);
        order.swap(orderTmp);
    }
}

} // namespace

void TriangleDepthOrder::setTriangles(std::span<const float> positions,
                                      std::span<const std::uint32_t> indices) {
    assert(positions.size() % 3 == 0 && indices.size() % 3 == 0);
    const std::size_t vertices = positions.size() / 3;
    const std::size_t triangles = indices.size() / 3;
    m_indices.assign(indices.begin(), indices.end());
    m_sorted = m_indices;
    m_centroids.assign(triangles * 3, 0.0f);
    for (std::size_t t = 0; t < triangles; ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t v = indices[3 * t + corner];
            assert(v < vertices);
            if (v >= vertices)
                continue;
            for (int c = 0; c < 3; ++c)
                m_centroids[3 * t + c] += positions[3 * v + c] / 3.0f;
        }
    }
    m_valid = false;
}

bool TriangleDepthOrder::update(const glm::dvec3& eye, const glm::dvec3& forward,
                                bool perspective) {
    if (m_valid && perspective == m_perspective &&
        (perspective ? eye == m_eye : forward == m_forward))
        return false;
    m_valid = true;
    m_perspective = perspective;
    m_eye = eye;
    m_forward = forward;
    const std::size_t n = triangleCount();
    if (n < 2)
        return false;
    m_keys.resize(n);
    m_order.resize(n);
    // Relative to the eye in floats: centroids are floats, and the differences keep the digits.
    const glm::vec3 e(eye), f(forward);
    for (std::size_t t = 0; t < n; ++t) {
        const glm::vec3 d(m_centroids[3 * t] - e.x, m_centroids[3 * t + 1] - e.y,
                          m_centroids[3 * t + 2] - e.z);
        const float depth =
            perspective ? d.x * d.x + d.y * d.y + d.z * d.z : d.x * f.x + d.y * f.y + d.z * f.z;
        m_keys[t] = descendingKey(depth);
        m_order[t] = static_cast<std::uint32_t>(t);
    }
    radixSort(m_keys, m_order, m_keysTmp, m_orderTmp);
    m_sorted.resize(m_indices.size());
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t t = m_order[i];
        m_sorted[3 * i] = m_indices[3 * t];
        m_sorted[3 * i + 1] = m_indices[3 * t + 1];
        m_sorted[3 * i + 2] = m_indices[3 * t + 2];
    }
    ++m_sorts;
    return true;
}

} // namespace faultline::core
