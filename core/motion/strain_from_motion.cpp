// Strain from motion: per sphere, the deformation gradient that best maps its neighbours'
// reference offsets onto their offsets now (least squares), its shear and volumetric strain,
// and the residual d2min (Falk & Langer), as OVITO's Atomic Strain computes them.
//
// Index of this file:
// [SECTION] Neighbour cells
// [SECTION] Sums over a sphere's neighbours
// [SECTION] Solving for the strain
// [SECTION] The columns

#include "core/motion/strain_from_motion.hpp"

#include "core/model/frame_difference.hpp"
#include "core/model/packing.hpp"
#include "core/model/periodic_cell.hpp"
#include "core/motion/strain_spec.hpp"
#include "core/util/lane_table.hpp"
#include "core/util/mat3.hpp"
#include "core/util/scratch_array.hpp"
#include "core/util/simd8.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FAULTLINE_STRAIN_AVX2 1
#define FAULTLINE_AVX2 __attribute__((target("avx2,fma")))
#include <immintrin.h>
#else
#define FAULTLINE_STRAIN_AVX2 0
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

namespace faultline::core {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

bool sameIdOrder(const Frame& a, const Frame& b) {
    return a.ids.size() == b.ids.size() &&
           (a.ids.empty() ||
            std::memcmp(a.ids.data(), b.ids.data(), a.ids.size() * sizeof(std::int64_t)) == 0);
}

constexpr std::uint32_t kNone = ~std::uint32_t(0);

// A reference centre (or a periodic image of one) with how far that sphere moved since (NaN:
// gone): worked out in double and taken to the current cell's minimum image, so a sphere that
// crossed a periodic face (or an image, whose reference is a cell edge away) keeps the
// precision of its small motion in float.
struct CellPoint {
    float x, y, z;    // reference
    float wx, wy, wz; // motion
};
constexpr float kFar = std::numeric_limits<float>::infinity();

// A row of the current frame: its centre and its sphere's slot in the cell list.
struct alignas(16) NowPoint {
    float x, y, z;
    std::uint32_t slot;
};

//-----------------------------------------------------------------------------
// [SECTION] Neighbour cells
//-----------------------------------------------------------------------------

// The reference centres and, on periodic axes, their images within `cutoff` of the centres'
// bounds, sorted into cubic cells of at least `cutoff`: neighbours of a sphere lie in its cell
// and the 26 around it, an image's vector is the minimum-image one, and a sphere's neighbours
// are read from memory in order (no lookups by id in the inner loop).
class NeighbourCells {
  public:
    NeighbourCells(const Frame& ref, const Frame& now, const std::uint32_t* nowRowOf, double cutoff)
        : m_nowCell(now.box) {
        const std::size_t n = ref.size();
        // The current centres as one record a row (one line read per sphere below, not three),
        // with the slot the row's sphere gets.
        m_now = makeScratchArray<NowPoint>(now.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, now.size(), 65536),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t i = r.begin(); i != r.end(); ++i)
                                  m_now[i] = {now.x[i], now.y[i], now.z[i], kNone};
                          });
        const auto& cmin = ref.centreMin();
        const auto& cmax = ref.centreMax();
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = double(cmin[a]) - cutoff;
            hi[a] = double(cmax[a]) + cutoff;
        }
        // The spheres are points 0..n-1, read from the frames; images (periodic axes) follow.
        std::vector<CellPoint> images;
        const PeriodicCell cell(ref.box);
        if (cell.any && n > 0) {
            const double edge[3][3] = {
                {cell.lx, 0, 0}, {cell.xy, cell.ly, 0}, {cell.xz, cell.yz, cell.lz}};
            std::vector<std::array<double, 3>> shifts;
            // Each shift's last axis whose cell edge moves it (c moves only z, b only y and x):
            // on that axis only centres within a slab by the opposite face can have an image in
            // bounds, a test on one coordinate that skips most spheres before the whole one.
            std::vector<int> slabAxis;
            for (int na = -1; na <= 1; ++na)
                for (int nb = -1; nb <= 1; ++nb)
                    for (int nc = -1; nc <= 1; ++nc) {
                        if ((na == 0 && nb == 0 && nc == 0) || (na && !cell.periodic[0]) ||
                            (nb && !cell.periodic[1]) || (nc && !cell.periodic[2]))
                            continue;
                        std::array<double, 3> s;
                        for (int a = 0; a < 3; ++a)
                            s[a] = na * edge[0][a] + nb * edge[1][a] + nc * edge[2][a];
                        shifts.push_back(s);
                        slabAxis.push_back(nc ? 2 : nb ? 1 : 0);
                    }
            // In parallel by blocks of spheres, then joined in order (shift, block, sphere): the
            // same list, so the same sums, as one pass would give.
            constexpr std::size_t kBlock = 16384;
            const std::size_t blocks = (n + kBlock - 1) / kBlock;
            std::vector<std::vector<CellPoint>> found(shifts.size() * blocks);
            tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t t) {
                const double* s = shifts[t / blocks].data();
                const int axis = slabAxis[t / blocks];
                const float* along = axis == 0   ? ref.x.data()
                                     : axis == 1 ? ref.y.data()
                                                 : ref.z.data();
                // The slab widened by far more than any rounding: the whole test decides.
                const double margin = 1e-5 * (std::fabs(lo[axis]) + std::fabs(hi[axis]) +
                                              std::fabs(s[axis]) + cutoff);
                const bool finite = std::isfinite(margin);
                const double slabLo = finite ? lo[axis] - s[axis] - margin : -HUGE_VAL;
                const double slabHi = finite ? hi[axis] - s[axis] + margin : HUGE_VAL;
                // The spheres in bounds first, then their motions (the current centres read
                // in no order, so fetched ahead).
                const std::size_t first = (t % blocks) * kBlock;
                std::vector<std::uint32_t> inside;
                for (std::size_t i = first; i < std::min(n, first + kBlock); ++i) {
                    if (!(along[i] >= slabLo && along[i] <= slabHi))
                        continue; // and a centre that is no number, whose image would be gone
                    const double q[3] = {ref.x[i] + s[0], ref.y[i] + s[1], ref.z[i] + s[2]};
                    if (q[0] < lo[0] || q[0] > hi[0] || q[1] < lo[1] || q[1] > hi[1] ||
                        q[2] < lo[2] || q[2] > hi[2])
                        continue;
                    inside.push_back(static_cast<std::uint32_t>(i));
                }
                found[t].reserve(inside.size());
                for (std::size_t h = 0; h < inside.size(); ++h) {
                    if (h + 8 < inside.size())
                        if (const std::uint32_t row = nowRowOf[inside[h + 8]]; row != kNone)
                            __builtin_prefetch(m_now.get() + row);
                    const std::size_t i = inside[h];
                    CellPoint p = pointOf(ref, nowRowOf, i, s);
                    p.x = static_cast<float>(ref.x[i] + s[0]);
                    p.y = static_cast<float>(ref.y[i] + s[1]);
                    p.z = static_cast<float>(ref.z[i] + s[2]);
                    found[t].push_back(p);
                }
            });
            std::size_t total = 0;
            for (const auto& f : found)
                total += f.size();
            images.reserve(total);
            for (const auto& f : found)
                images.insert(images.end(), f.begin(), f.end());
        }
        // Cells of at least `cutoff`, no more of them than ~4 per point (sparse or flat sets).
        const std::size_t count = n + images.size();
        if (count >= kNone) // slots are 32-bit, kNone the mark of none
            throw std::length_error("strain from motion: over 2^32 spheres and periodic images");
        // No axis gets more than 2^20 cells, whatever the cutoff (a tiny one is no neighbourhood).
        double extent = 0;
        for (int a = 0; a < 3; ++a)
            extent = std::max(extent, hi[a] - lo[a]);
        m_size = std::max(cutoff, extent / double(1 << 20));
        for (;;) {
            double cells = 1;
            for (int a = 0; a < 3; ++a) {
                // At most ~2^20 by m_size; NaN (a frame without a finite centre): one cell.
                const double span = (hi[a] - lo[a]) / m_size;
                m_dims[a] = span >= 1.0 ? static_cast<int>(std::min(span, 4.0e6)) + 1 : 1;
                cells *= m_dims[a];
            }
            if (cells <= 4.0 * double(count) + 64)
                break;
            m_size *= 1.25;
        }
        for (int a = 0; a < 3; ++a)
            m_lo[a] = lo[a];
        auto cellOf = makeScratchArray<std::uint32_t>(count);
        m_inverseSize = 1.0 / m_size;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              const std::size_t split = std::clamp(n, r.begin(), r.end());
                              for (std::size_t k = r.begin(); k < split; ++k)
                                  cellOf[k] = cellIndex(ref.x[k], ref.y[k], ref.z[k]);
                              for (std::size_t k = split; k < r.end(); ++k)
                                  cellOf[k] =
                                      cellIndex(images[k - n].x, images[k - n].y, images[k - n].z);
                          });
        // Each point's slot in cell order, the order within a cell being the points' (so the
        // spheres come before the images): a counting sort in parts (the spheres' two halves,
        // and the images if any), each part counted per cell, then its points given the slots
        // after those of the parts before it, the parts in parallel.
        const std::size_t cells = std::size_t(m_dims[0]) * m_dims[1] * m_dims[2];
        const std::size_t bounds[4] = {0, n / 2, n, count};
        const int parts = count > n ? 3 : 2;
        std::vector<std::uint32_t> next[3];
        tbb::parallel_for(0, parts, [&](int part) {
            next[part].assign(cells, 0);
            std::uint32_t* c = next[part].data();
            for (std::size_t k = bounds[part]; k < bounds[part + 1]; ++k)
                ++c[cellOf[k]];
        });
        m_start.resize(cells + 1);
        if (parts == 3)
            m_spheresEnd.resize(cells);
        std::uint32_t at = 0;
        for (std::size_t c = 0; c < cells; ++c) {
            m_start[c] = at;
            for (int part = 0; part < parts; ++part) {
                const std::uint32_t here = next[part][c];
                next[part][c] = at;
                at += here;
                if (part == 1 && parts == 3)
                    m_spheresEnd[c] = at;
            }
        }
        m_start[cells] = at;
        ScratchArray<std::uint32_t>& slot = cellOf; // cellOf[k] read once, then k's slot
        tbb::parallel_for(0, parts, [&](int part) {
            std::uint32_t* c = next[part].data();
            for (std::size_t k = bounds[part]; k < bounds[part + 1]; ++k)
                slot[k] = c[slot[k]]++;
        });
        for (auto& v : next)
            std::vector<std::uint32_t>().swap(v); // not held through the filling below
        // Reference positions as float arrays and whole points (reference and motion) in cell
        // order. Not zeroed first (every slot is written below, in parallel: a serial clearing
        // of these ~30 bytes a point cost as much as filling them).
        // Sixteen more, infinitely far: the AVX2 and AVX-512 sums read whole vectors past a
        // run's end.
        for (auto* v : {&m_x, &m_y, &m_z}) {
            *v = makeScratchArray<float>(count + 16);
            std::fill(v->get() + count, v->get() + count + 16, kFar);
        }
        m_points = makeScratchArray<float>(8 * count);
        m_count = count;
        std::atomic<std::uint32_t> widest[3] = {0, 0, 0}; // float bits: >= 0 orders as floats
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, count, 16384),
            [&](const tbb::blocked_range<std::size_t>& r) {
                const double noShift[3] = {0, 0, 0};
                float wide[3] = {0, 0, 0}; // NaN (gone) leaves it
                for (std::size_t k = r.begin(); k != r.end(); ++k) {
                    // The current frame's rows and the slots come in no order.
                    if (const std::size_t a = k + 16; a < std::min(r.end(), n)) {
                        if (const std::uint32_t row = nowRowOf[a]; row != kNone)
                            __builtin_prefetch(m_now.get() + row, 1);
                        const std::size_t to = slot[a];
                        __builtin_prefetch(m_points.get() + 8 * to, 1);
                        __builtin_prefetch(m_x.get() + to, 1);
                        __builtin_prefetch(m_y.get() + to, 1);
                        __builtin_prefetch(m_z.get() + to, 1);
                    }
                    const std::uint32_t at = slot[k];
                    const CellPoint p = k < n ? pointOf(ref, nowRowOf, k, noShift) : images[k - n];
                    // A sphere gone is never near: infinitely far.
                    const bool gone = std::isnan(p.wx);
                    m_x[at] = gone ? kFar : p.x;
                    m_y[at] = gone ? kFar : p.y;
                    m_z[at] = gone ? kFar : p.z;
                    float* q = m_points.get() + 8 * std::size_t(at);
                    q[0] = p.x, q[1] = p.y, q[2] = p.z;
                    q[3] = p.wx, q[4] = p.wy, q[5] = p.wz;
                    q[6] = q[7] = 0.0f;
                    if (k < n && nowRowOf[k] != kNone)
                        m_now[nowRowOf[k]].slot = at;
                    wide[0] = std::max(wide[0], std::fabs(p.wx));
                    wide[1] = std::max(wide[1], std::fabs(p.wy));
                    wide[2] = std::max(wide[2], std::fabs(p.wz));
                }
                for (int a = 0; a < 3; ++a) {
                    std::uint32_t bits;
                    std::memcpy(&bits, &wide[a], sizeof bits);
                    std::uint32_t seen = widest[a].load();
                    while (bits > seen && !widest[a].compare_exchange_weak(seen, bits)) {
                    }
                }
            });
        for (int a = 0; a < 3; ++a) {
            const std::uint32_t bits = widest[a].load();
            std::memcpy(&m_widestMotion[a], &bits, sizeof bits);
        }
    }

    std::size_t cellCount() const { return m_start.size() - 1; }
    std::size_t pointCount() const { return m_count; }
    std::size_t begin(std::size_t cell) const { return m_start[cell]; }
    // The end of the cell's spheres: its images (periodic axes) follow them.
    std::size_t spheresEnd(std::size_t cell) const {
        return m_spheresEnd.empty() ? m_start[cell + 1] : m_spheresEnd[cell];
    }
    // Each row of the current frame: its centre and where its sphere is in cell order (kNone:
    // not in the reference).
    const NowPoint* nowPoints() const { return m_now.get(); }
    // Reference positions in cell order (infinite: the sphere is gone).
    const float* xs() const { return m_x.get(); }
    const float* ys() const { return m_y.get(); }
    const float* zs() const { return m_z.get(); }
    // Each point as eight floats: reference x, y, z, motion wx, wy, wz (NaN: gone), 0, 0.
    const float* points() const { return m_points.get(); }
    const float* point(std::size_t k) const { return m_points.get() + 8 * k; }
    // The largest |motion| on each axis (of the points whose motion is a number).
    const float* widestMotion() const { return m_widestMotion; }

    // A cell and its coordinates, stepped through in order: the three 64-bit divisions that
    // find a cell's coordinates from its index, once per range of cells rather than per cell.
    struct At {
        std::size_t index;
        int x, y, z;
    };
    At at(std::size_t cell) const {
        return {cell, int(cell % m_dims[0]), int((cell / m_dims[0]) % m_dims[1]),
                int(cell / (std::size_t(m_dims[0]) * m_dims[1]))};
    }
    void next(At& c) const {
        ++c.index;
        if (++c.x < m_dims[0])
            return;
        c.x = 0;
        if (++c.y < m_dims[1])
            return;
        c.y = 0;
        ++c.z;
    }

    // fn(first, last) for each run of points in the 27 cells around `cell` (9 runs of up to
    // three cells that lie next to each other in memory).
    template <typename Fn> void around(const At& cell, Fn fn) const {
        const int cx = cell.x, cy = cell.y, cz = cell.z;
        for (int k = std::max(0, cz - 1); k <= std::min(m_dims[2] - 1, cz + 1); ++k)
            for (int j = std::max(0, cy - 1); j <= std::min(m_dims[1] - 1, cy + 1); ++j) {
                const std::size_t row = (std::size_t(k) * m_dims[1] + j) * m_dims[0];
                const std::size_t first = row + std::max(0, cx - 1);
                const std::size_t last = row + std::min(m_dims[0] - 1, cx + 1);
                fn(m_start[first], m_start[last + 1]);
            }
    }

  private:
    // Sphere i (its reference shifted by `shift` for an image) and its motion.
    CellPoint pointOf(const Frame& ref, const std::uint32_t* nowRowOf, std::size_t i,
                      const double shift[3]) const {
        const std::uint32_t k = nowRowOf[i];
        const float nan = std::numeric_limits<float>::quiet_NaN();
        CellPoint p{ref.x[i], ref.y[i], ref.z[i], nan, nan, nan};
        if (k != kNone) {
            const NowPoint& q = m_now[k];
            double w[3] = {double(q.x) - ref.x[i] - shift[0], double(q.y) - ref.y[i] - shift[1],
                           double(q.z) - ref.z[i] - shift[2]};
            // A centre that is no number (or infinite), then or now: the sphere counts as gone
            // (motion NaN on every axis, the one mark the sums test).
            if (!std::isfinite(w[0] + w[1] + w[2]))
                return p;
            m_nowCell.wrap(w[0], w[1], w[2]);
            p.wx = static_cast<float>(w[0]), p.wy = static_cast<float>(w[1]);
            p.wz = static_cast<float>(w[2]);
        }
        return p;
    }
    // Clamped before the conversion: a centre that is no number, or far beyond the int range
    // (a finite extreme a file may hold), is no undefined conversion.
    // Without branches (NaN fails the first test), so that a loop of them vectorises.
    int coord(double v, int axis) const {
        double c = (v - m_lo[axis]) * m_inverseSize;
        c = c > 0 ? c : 0.0;
        const double top = m_dims[axis] - 1;
        return static_cast<int>(c < top ? c : top);
    }
    std::uint32_t cellIndex(double px, double py, double pz) const {
        return static_cast<std::uint32_t>(
            (std::size_t(coord(pz, 2)) * m_dims[1] + coord(py, 1)) * m_dims[0] + coord(px, 0));
    }

    double m_lo[3] = {0, 0, 0};
    double m_size = 1, m_inverseSize = 1;
    int m_dims[3] = {1, 1, 1};
    std::vector<std::uint32_t> m_start;
    std::size_t m_count = 0;
    std::vector<std::uint32_t> m_spheresEnd; // empty: no images
    ScratchArray<NowPoint> m_now;
    ScratchArray<float> m_x, m_y, m_z, m_points;
    PeriodicCell m_nowCell;
    float m_widestMotion[3] = {0, 0, 0};
};

//-----------------------------------------------------------------------------
// [SECTION] Sums over a sphere's neighbours
//-----------------------------------------------------------------------------

// One sphere's sums over its neighbours within the cutoff, X being a neighbour's offset in the
// reference and U = Y - X how much further it moved than the sphere (Y its offset now, the
// minimum image on periodic axes): V = sum X X^T, A = sum U X^T and sum U_i^2 per axis. Summing
// U rather than Y keeps the residual's precision where the motion is small: with F = I + G,
// G = A V^-1, E = (G + G^T + G^T G) / 2 and d2min = sum |U - G X|^2 = sum U^2 - tr(G A^T).
struct NeighbourSums {
    double V[3][3] = {};
    double A[3][3] = {};
    double uu[3] = {};
    int count = 0;
};

// One sphere's sums as the AVX2 sums leave them, for the solve to read four spheres' at once:
// the sums of d * X_x, d * X_y, d * X_z and d * d over its neighbours, d = (X, U, 0, 0), and
// how many neighbours. Not initialised: each is written whole.
struct RawSums {
    alignas(32) float r[4][8];
    int count;
};

// Sums kept as a sphere's four vectors r (r[b][lane]: the sum of d * X_b for b < 3, of d * d for
// b = 3; d = (X, U, 0, 0)) as V, A and uu: V from lanes 0-2 of the first three (one sum for
// both halves), A from their lanes 3-5, uu from lanes 3-5 of the last. For one sphere's floats
// and for the AVX2 solve's vectors of four spheres alike (inlined there: its vectors need AVX).
template <typename R, typename T>
[[gnu::always_inline]] inline void unpackSums(const R& r, T (&V)[3][3], T (&A)[3][3], T (&uu)[3]) {
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            V[i][j] = r[std::max(i, j)][std::min(i, j)];
            A[i][j] = r[j][3 + i];
        }
        uu[i] = r[3][3 + i];
    }
}

NeighbourSums sumsOf(const RawSums& s) {
    NeighbourSums out;
    unpackSums(s.r, out.V, out.A, out.uu);
    out.count = s.count;
    return out;
}

// The points of the 27 cells around one cell, contiguous and padded to whole vectors with
// points that are never near, for the baseline sums: reference positions (x, y, z; infinite:
// gone) and how far each moved (w = now - reference; an image's reference is shifted by a cell
// edge). The AVX2 sums pack, per cell, the points near its spheres' box (Packed).
struct Candidates {
    std::vector<float> x, y, z, wx, wy, wz;
    std::size_t size = 0;
    void gather(const NeighbourCells& cells, const NeighbourCells::At& cell) {
        size = 0;
        cells.around(cell, [&](std::size_t first, std::size_t last) {
            const std::size_t n = last - first;
            if (x.size() < size + n + 8)
                for (auto* v : {&x, &y, &z, &wx, &wy, &wz})
                    v->resize(2 * (size + n + 8));
            const auto at = std::ptrdiff_t(size);
            std::copy(cells.xs() + first, cells.xs() + last, x.begin() + at);
            std::copy(cells.ys() + first, cells.ys() + last, y.begin() + at);
            std::copy(cells.zs() + first, cells.zs() + last, z.begin() + at);
            for (std::size_t k = 0; k < n; ++k) {
                const float* q = cells.point(first + k);
                wx[size + k] = q[3], wy[size + k] = q[4], wz[size + k] = q[5];
            }
            size += n;
        });
        for (std::size_t k = size; k < ((size + 7) & ~std::size_t(7)); ++k)
            x[k] = y[k] = z[k] = kFar, wx[k] = wy[k] = wz[k] = 0.0f;
    }
};

// The current frame's periodic cell as floats, for the minimum image eight offsets at a time.
struct CellF {
    bool periodic[3] = {false, false, false};
    float l[3] = {1, 1, 1}, inv[3] = {1, 1, 1}, xy = 0, xz = 0, yz = 0;
    explicit CellF(const PeriodicCell& c) {
        const double len[3] = {c.lx, c.ly, c.lz};
        for (int a = 0; a < 3; ++a) {
            periodic[a] = c.periodic[a];
            if (periodic[a]) {
                l[a] = static_cast<float>(len[a]);
                inv[a] = static_cast<float>(1.0 / len[a]);
            }
        }
        xy = static_cast<float>(c.xy), xz = static_cast<float>(c.xz);
        yz = static_cast<float>(c.yz);
    }
};

// U = w_j - w_i is Y - X (Y the offset now); on periodic axes it is taken to its minimum
// image, as Y would be (they differ by X, under the cutoff, far less than half a cell). The
// motions are minimum images already; this catches two neighbours whose motions straddle half a
// cell (a long cumulative interval in a flowing periodic box).
template <bool Wrap>
[[gnu::always_inline]] inline void sumNeighboursBody(const Candidates& c, const float* self,
                                                     float cutoff2, const CellF& cell,
                                                     NeighbourSums& out) {
    using namespace detail::simd8;
    const v8f px = splat(self[0]), py = splat(self[1]), pz = splat(self[2]);
    const v8f qx = splat(self[3]), qy = splat(self[4]), qz = splat(self[5]);
    const v8f c2 = splat(cutoff2), zero{}, one = splat(1.0f);
    const bool wrapX = cell.periodic[0], wrapY = cell.periodic[1], wrapZ = cell.periodic[2];
    const v8f lx = splat(cell.l[0]), ly = splat(cell.l[1]), lz = splat(cell.l[2]);
    const v8f ilx = splat(cell.inv[0]), ily = splat(cell.inv[1]), ilz = splat(cell.inv[2]);
    const v8f txy = splat(cell.xy), txz = splat(cell.xz), tyz = splat(cell.yz);
    // Round to nearest for |v| < 2^22 (offsets are a few cells at most).
    const v8f magic = splat(12582912.0f);
    v8f vxx{}, vxy{}, vxz{}, vyy{}, vyz{}, vzz{};
    v8f axx{}, axy{}, axz{}, ayx{}, ayy{}, ayz{}, azx{}, azy{}, azz{};
    v8f uxx{}, uyy{}, uzz{}, n{};
    for (std::size_t k = 0; k < c.size; k += 8) {
        v8f dx = load(c.x.data() + k) - px, dy = load(c.y.data() + k) - py,
            dz = load(c.z.data() + k) - pz;
        v8f ux = load(c.wx.data() + k) - qx, uy = load(c.wy.data() + k) - qy,
            uz = load(c.wz.data() + k) - qz;
        // Within the cutoff (a sphere gone is infinitely far; its NaN motion is left out below).
        const auto near = dx * dx + dy * dy + dz * dz <= c2;
        if constexpr (Wrap) { // z first since c carries x and y tilt, then y, then x
            if (wrapZ) {
                const v8f m = (uz * ilz + magic) - magic;
                uz -= m * lz, uy -= m * tyz, ux -= m * txz;
            }
            if (wrapY) {
                const v8f m = (uy * ily + magic) - magic;
                uy -= m * ly, ux -= m * txy;
            }
            if (wrapX)
                ux -= ((ux * ilx + magic) - magic) * lx;
        }
        dx = near ? dx : zero, dy = near ? dy : zero, dz = near ? dz : zero;
        ux = near ? ux : zero, uy = near ? uy : zero, uz = near ? uz : zero;
        n += near ? one : zero;
        vxx += dx * dx, vxy += dx * dy, vxz += dx * dz;
        vyy += dy * dy, vyz += dy * dz, vzz += dz * dz;
        axx += ux * dx, axy += ux * dy, axz += ux * dz;
        ayx += uy * dx, ayy += uy * dy, ayz += uy * dz;
        azx += uz * dx, azy += uz * dy, azz += uz * dz;
        uxx += ux * ux, uyy += uy * uy, uzz += uz * uz;
    }
    out.V[0][0] = sum(vxx), out.V[1][1] = sum(vyy), out.V[2][2] = sum(vzz);
    out.V[0][1] = out.V[1][0] = sum(vxy);
    out.V[0][2] = out.V[2][0] = sum(vxz);
    out.V[1][2] = out.V[2][1] = sum(vyz);
    out.A[0][0] = sum(axx), out.A[0][1] = sum(axy), out.A[0][2] = sum(axz);
    out.A[1][0] = sum(ayx), out.A[1][1] = sum(ayy), out.A[1][2] = sum(ayz);
    out.A[2][0] = sum(azx), out.A[2][1] = sum(azy), out.A[2][2] = sum(azz);
    out.uu[0] = sum(uxx), out.uu[1] = sum(uyy), out.uu[2] = sum(uzz);
    out.count = static_cast<int>(sum(n)) - 1; // the sphere itself (X = U = 0: no term)
}

// The sums of the spheres `selves` (rows in cell order) of one cell: the points around the
// cell gathered once, then each sphere against them. Spheres per call, not one: the loops are
// short (a dozen vectors), so a call per sphere cost as much as its sums.
FAULTLINE_HOT void cellSumsBaseline(const NeighbourCells& cells, const NeighbourCells::At& cell,
                                    const std::uint32_t* selves, std::size_t count, float cutoff2,
                                    const CellF& now, bool wrap, Candidates& candidates,
                                    NeighbourSums* out) {
    candidates.gather(cells, cell);
    for (std::size_t s = 0; s < count; ++s) {
        const float* sphere = cells.point(selves[s]);
        if (wrap)
            sumNeighboursBody<true>(candidates, sphere, cutoff2, now, out[s]);
        else
            sumNeighboursBody<false>(candidates, sphere, cutoff2, now, out[s]);
    }
}

#if FAULTLINE_STRAIN_AVX2
// The same sums with AVX2. Per cell, the points of the 27 cells within the cutoff of the box
// around its spheres, packed (about 65 of 130); then per sphere two passes: the packed points
// within the cutoff, eight distances at a time, their indices packed into a list (a table of
// the lanes each 8-bit mask keeps: no branch per neighbour), then each neighbour's terms as
// one vector of its offset and motion d = (X, U, 0, 0) times X's three components and itself:
//   s_j += d * X_j (j = x, y, z): lanes 0-2 sum X X^T, lanes 3-5 sum U X_j;  s_u += d * d.
// A sphere has about 20 neighbours, so this does a sixth of the products the eight-wide
// baseline does over every candidate, in 4 accumulators instead of 19; the terms come in the
// order of the points, so the sums are those of a pass over all 27 cells.
using detail::kLaneTable;

// The runs of points in the 27 cells around a cell (NeighbourCells::around), at most 9.
struct Runs {
    std::size_t first[9], last[9];
    int count = 0;
};

// The lanes whose squared distance is within c2, among the first `left` (the others lie past
// the end of what is read), as a mask; and the indices of a mask's lanes, packed to the front.
FAULTLINE_AVX2 inline unsigned lanesWithin(__m256 d2, __m256 c2, std::size_t left) {
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d2, c2, _CMP_LE_OQ))) &
           (left >= 8 ? 0xffu : (1u << left) - 1u);
}
FAULTLINE_AVX2 inline __m256i laneIndices(unsigned mask) {
    return _mm256_load_si256(reinterpret_cast<const __m256i*>(kLaneTable.lanes[mask]));
}

// The points of the runs around a cell that lie within the cutoff of the box around the cell's
// spheres (every neighbour of each of them does), packed in their order: reference x, y, z and
// the point's slot. A sphere's own pass then tests about half the points, with no runs' ends.
struct Packed {
    std::vector<float> x, y, z;
    std::vector<std::uint32_t> slot, near;
    std::size_t size = 0;
    void reserve(std::size_t total) {
        if (x.size() < total + 16)
            for (auto* v : {&x, &y, &z})
                v->resize(2 * total + 16);
        if (slot.size() < total + 16) {
            slot.resize(2 * total + 16);
            near.resize(2 * total + 16);
        }
    }
};

// The runs of points around a cell (room for them reserved in `packed`), and the box around the
// cell's spheres `selves` (lo, hi), for either packing of candidates.
inline Runs runsAround(const NeighbourCells& cells, const NeighbourCells::At& cell,
                       const std::uint32_t* selves, std::size_t count, Packed& packed, float* lo,
                       float* hi) {
    Runs runs;
    std::size_t total = 0;
    cells.around(cell, [&](std::size_t first, std::size_t last) {
        runs.first[runs.count] = first;
        runs.last[runs.count++] = last;
        total += last - first;
    });
    packed.reserve(total);
    for (int a = 0; a < 3; ++a)
        lo[a] = hi[a] = cells.point(selves[0])[a];
    for (std::size_t s = 1; s < count; ++s) {
        const float* p = cells.point(selves[s]);
        for (int a = 0; a < 3; ++a)
            lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    }
    return runs;
}

// Box distance per axis as the spheres' own test forms it (a - b, squared by multiply-adds in
// the same order): every rounding is monotonic, so a point within the cutoff of a sphere is
// within it of the box around the spheres in float too.
FAULTLINE_AVX2 void packCandidates(const NeighbourCells& cells, const Runs& runs, const float* lo,
                                   const float* hi, float cutoff2, Packed& out) {
    const __m256 lx = _mm256_set1_ps(lo[0]), ly = _mm256_set1_ps(lo[1]), lz = _mm256_set1_ps(lo[2]);
    const __m256 hx = _mm256_set1_ps(hi[0]), hy = _mm256_set1_ps(hi[1]), hz = _mm256_set1_ps(hi[2]);
    const __m256 c2 = _mm256_set1_ps(cutoff2), zero = _mm256_setzero_ps();
    const float *cx = cells.xs(), *cy = cells.ys(), *cz = cells.zs();
    float *ox = out.x.data(), *oy = out.y.data(), *oz = out.z.data();
    std::uint32_t* os = out.slot.data();
    std::size_t n = 0;
    for (int r = 0; r < runs.count; ++r) {
        const std::size_t last = runs.last[r];
        for (std::size_t k = runs.first[r]; k < last; k += 8) {
            const __m256 x = _mm256_loadu_ps(cx + k), y = _mm256_loadu_ps(cy + k),
                         z = _mm256_loadu_ps(cz + k);
            // Distance beyond the box on each axis (0 inside); infinite for a sphere gone.
            const __m256 dx =
                _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(lx, x), _mm256_sub_ps(x, hx)), zero);
            const __m256 dy =
                _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(ly, y), _mm256_sub_ps(y, hy)), zero);
            const __m256 dz =
                _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(lz, z), _mm256_sub_ps(z, hz)), zero);
            const __m256 d2 =
                _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx)));
            const unsigned mask = lanesWithin(d2, c2, last - k);
            const __m256i lanes = laneIndices(mask);
            _mm256_storeu_ps(ox + n, _mm256_permutevar8x32_ps(x, lanes));
            _mm256_storeu_ps(oy + n, _mm256_permutevar8x32_ps(y, lanes));
            _mm256_storeu_ps(oz + n, _mm256_permutevar8x32_ps(z, lanes));
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(os + n),
                                _mm256_add_epi32(lanes, _mm256_set1_epi32(static_cast<int>(k))));
            n += static_cast<std::size_t>(__builtin_popcount(mask));
        }
    }
    out.size = n;
}

template <bool Wrap>
FAULTLINE_AVX2 void sumNeighboursAvx2(const NeighbourCells& cells, Packed& packed,
                                      const float* self, float cutoff2, const CellF& cell,
                                      RawSums& out) {
    const __m256 px = _mm256_set1_ps(self[0]), py = _mm256_set1_ps(self[1]),
                 pz = _mm256_set1_ps(self[2]), c2 = _mm256_set1_ps(cutoff2);
    // Locals: the stores to `near` could otherwise alias the arrays' pointers.
    const float *cx = packed.x.data(), *cy = packed.y.data(), *cz = packed.z.data();
    const std::uint32_t* slots = packed.slot.data();
    std::uint32_t* near = packed.near.data();
    const float* cp = cells.points();
    const std::size_t last = packed.size;
    std::size_t n = 0;
    for (std::size_t k = 0; k < last; k += 8) {
        const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(cx + k), px);
        const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(cy + k), py);
        const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(cz + k), pz);
        const __m256 d2 = _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx)));
        // Lanes past the end hold what an earlier cell packed: left out.
        const unsigned mask = lanesWithin(d2, c2, last - k);
        const __m256i lanes = laneIndices(mask);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(near + n),
                            _mm256_add_epi32(lanes, _mm256_set1_epi32(static_cast<int>(k))));
        n += static_cast<std::size_t>(__builtin_popcount(mask));
    }
    const __m256 me = _mm256_loadu_ps(self);
    // The minimum image of U, as the baseline takes it (z first, then y, then x; lanes 3-5).
    const __m256 tz = _mm256_setr_ps(0, 0, 0, cell.xz, cell.yz, cell.l[2], 0, 0);
    const __m256 ty = _mm256_setr_ps(0, 0, 0, cell.xy, cell.l[1], 0, 0, 0);
    const __m256 tx = _mm256_setr_ps(0, 0, 0, cell.l[0], 0, 0, 0, 0);
    const __m256 ilx = _mm256_set1_ps(cell.inv[0]), ily = _mm256_set1_ps(cell.inv[1]),
                 ilz = _mm256_set1_ps(cell.inv[2]);
    const __m256i laneX = _mm256_set1_epi32(3), laneY = _mm256_set1_epi32(4),
                  laneZ = _mm256_set1_epi32(5);
    constexpr int kRound = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
    const bool wrapX = cell.periodic[0], wrapY = cell.periodic[1], wrapZ = cell.periodic[2];
    __m256 sx = _mm256_setzero_ps(), sy = sx, sz = sx, su = sx;
    for (std::size_t t = 0; t < n; ++t) {
        const std::size_t j = near[t];
        __m256 d = _mm256_sub_ps(_mm256_loadu_ps(cp + 8 * std::size_t(slots[j])), me);
        if constexpr (Wrap) {
            if (wrapZ)
                d = _mm256_fnmadd_ps(
                    _mm256_round_ps(_mm256_mul_ps(_mm256_permutevar8x32_ps(d, laneZ), ilz), kRound),
                    tz, d);
            if (wrapY)
                d = _mm256_fnmadd_ps(
                    _mm256_round_ps(_mm256_mul_ps(_mm256_permutevar8x32_ps(d, laneY), ily), kRound),
                    ty, d);
            if (wrapX)
                d = _mm256_fnmadd_ps(
                    _mm256_round_ps(_mm256_mul_ps(_mm256_permutevar8x32_ps(d, laneX), ilx), kRound),
                    tx, d);
        }
        sx = _mm256_fmadd_ps(d, _mm256_sub_ps(_mm256_broadcast_ss(cx + j), px), sx);
        sy = _mm256_fmadd_ps(d, _mm256_sub_ps(_mm256_broadcast_ss(cy + j), py), sy);
        sz = _mm256_fmadd_ps(d, _mm256_sub_ps(_mm256_broadcast_ss(cz + j), pz), sz);
        su = _mm256_fmadd_ps(d, d, su);
    }
    _mm256_store_ps(out.r[0], sx);
    _mm256_store_ps(out.r[1], sy);
    _mm256_store_ps(out.r[2], sz);
    _mm256_store_ps(out.r[3], su);
    out.count = static_cast<int>(n) - 1; // the sphere itself (X = U = 0: no term)
}

FAULTLINE_AVX2 void cellSumsAvx2(const NeighbourCells& cells, const NeighbourCells::At& cell,
                                 const std::uint32_t* selves, std::size_t count, float cutoff2,
                                 const CellF& now, bool wrap, Packed& packed, RawSums* out) {
    float lo[3], hi[3];
    const Runs runs = runsAround(cells, cell, selves, count, packed, lo, hi);
    packCandidates(cells, runs, lo, hi, cutoff2, packed);
    for (std::size_t s = 0; s < count; ++s) {
        const float* sphere = cells.point(selves[s]);
        if (wrap)
            sumNeighboursAvx2<true>(cells, packed, sphere, cutoff2, now, out[s]);
        else
            sumNeighboursAvx2<false>(cells, packed, sphere, cutoff2, now, out[s]);
    }
}

// The same sums with AVX-512 (where the CPU has F, DQ, BW and VL), to the last bit: the same
// points packed in the same order, the same neighbours found in the same order, and each lane
// of the sums the same multiply-adds in the same order as the AVX2 sums. Sixteen candidates a
// test instead of eight, packed by the CPU's compress rather than a table; and each neighbour's
// four products as two sixteen-wide multiply-adds, d = (X, U, 0, 0) in both halves times
// (X_x | X_y) and (X_z | d): the first half of each register one of the AVX2 sums, the second
// half the next.
#define FAULTLINE_AVX512 __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl,avx2,fma")))
// GCC 12's AVX-512 intrinsics start some results from a deliberately undefined vector
// (_mm512_undefined_ps), which its own warning then reports once they are inlined here.
#if !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

FAULTLINE_AVX512 inline unsigned lanesWithin16(__m512 d2, __m512 c2, std::size_t left) {
    return static_cast<unsigned>(_mm512_cmp_ps_mask(d2, c2, _CMP_LE_OQ)) &
           (left >= 16 ? 0xffffu : (1u << left) - 1u);
}

FAULTLINE_AVX512 void packCandidates512(const NeighbourCells& cells, const Runs& runs,
                                        const float* lo, const float* hi, float cutoff2,
                                        Packed& out) {
    const __m512 lx = _mm512_set1_ps(lo[0]), ly = _mm512_set1_ps(lo[1]), lz = _mm512_set1_ps(lo[2]);
    const __m512 hx = _mm512_set1_ps(hi[0]), hy = _mm512_set1_ps(hi[1]), hz = _mm512_set1_ps(hi[2]);
    const __m512 c2 = _mm512_set1_ps(cutoff2), zero = _mm512_setzero_ps();
    const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const float *cx = cells.xs(), *cy = cells.ys(), *cz = cells.zs();
    float *ox = out.x.data(), *oy = out.y.data(), *oz = out.z.data();
    std::uint32_t* os = out.slot.data();
    std::size_t n = 0;
    for (int r = 0; r < runs.count; ++r) {
        const std::size_t last = runs.last[r];
        for (std::size_t k = runs.first[r]; k < last; k += 16) {
            const __m512 x = _mm512_loadu_ps(cx + k), y = _mm512_loadu_ps(cy + k),
                         z = _mm512_loadu_ps(cz + k);
            // As packCandidates: the same operations, so the same points kept.
            const __m512 dx =
                _mm512_max_ps(_mm512_max_ps(_mm512_sub_ps(lx, x), _mm512_sub_ps(x, hx)), zero);
            const __m512 dy =
                _mm512_max_ps(_mm512_max_ps(_mm512_sub_ps(ly, y), _mm512_sub_ps(y, hy)), zero);
            const __m512 dz =
                _mm512_max_ps(_mm512_max_ps(_mm512_sub_ps(lz, z), _mm512_sub_ps(z, hz)), zero);
            const __m512 d2 =
                _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
            const auto mask = static_cast<__mmask16>(lanesWithin16(d2, c2, last - k));
            // Compressed in registers, then stored whole (a compressing store to memory is
            // slow on some CPUs).
            _mm512_storeu_ps(ox + n, _mm512_maskz_compress_ps(mask, x));
            _mm512_storeu_ps(oy + n, _mm512_maskz_compress_ps(mask, y));
            _mm512_storeu_ps(oz + n, _mm512_maskz_compress_ps(mask, z));
            _mm512_storeu_si512(
                os + n, _mm512_maskz_compress_epi32(
                            mask, _mm512_add_epi32(iota, _mm512_set1_epi32(static_cast<int>(k)))));
            n += static_cast<std::size_t>(__builtin_popcount(mask));
        }
    }
    out.size = n;
}

// The slots of the packed points within the cutoff of `self`, in the packed order, into `near`
// (room for the packed points and 16 more); how many (the sphere itself among them).
FAULTLINE_AVX512 inline std::size_t neighbours512(const Packed& packed, const float* self,
                                                  float cutoff2, std::uint32_t* near) {
    const __m512 px = _mm512_set1_ps(self[0]), py = _mm512_set1_ps(self[1]),
                 pz = _mm512_set1_ps(self[2]), c2 = _mm512_set1_ps(cutoff2);
    const float *cx = packed.x.data(), *cy = packed.y.data(), *cz = packed.z.data();
    const std::uint32_t* slots = packed.slot.data();
    const std::size_t last = packed.size;
    std::size_t n = 0;
    for (std::size_t k = 0; k < last; k += 16) {
        const __m512 dx = _mm512_sub_ps(_mm512_loadu_ps(cx + k), px);
        const __m512 dy = _mm512_sub_ps(_mm512_loadu_ps(cy + k), py);
        const __m512 dz = _mm512_sub_ps(_mm512_loadu_ps(cz + k), pz);
        const __m512 d2 = _mm512_fmadd_ps(dz, dz, _mm512_fmadd_ps(dy, dy, _mm512_mul_ps(dx, dx)));
        const auto mask = static_cast<__mmask16>(lanesWithin16(d2, c2, last - k));
        _mm512_storeu_si512(near + n,
                            _mm512_maskz_compress_epi32(mask, _mm512_loadu_si512(slots + k)));
        n += static_cast<std::size_t>(__builtin_popcount(mask));
    }
    return n;
}

// One sphere's sums over the points of the slots `near` (its neighbours and itself).
template <bool Wrap>
FAULTLINE_AVX512 inline void accumulate512(const NeighbourCells& cells, const std::uint32_t* near,
                                           std::size_t n, const float* self, const CellF& cell,
                                           RawSums& out) {
    const float* cp = cells.points();
    const __m512 me = _mm512_broadcast_f32x8(_mm256_loadu_ps(self));
    // X_x | X_y, and X_z | d.
    const __m512i firstIdx = _mm512_setr_epi32(0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1);
    const __m512i secondIdx =
        _mm512_setr_epi32(2, 2, 2, 2, 2, 2, 2, 2, 16, 17, 18, 19, 20, 21, 22, 23);
    __m512 s01 = _mm512_setzero_ps(), s23 = s01;
    if constexpr (!Wrap) {
        const __m512i ownIdx = _mm512_setr_epi32(2, 2, 2, 2, 2, 2, 2, 2, 0, 1, 2, 3, 4, 5, 6, 7);
        for (std::size_t t = 0; t < n; ++t) {
            const __m512 d = _mm512_sub_ps(
                _mm512_broadcast_f32x8(_mm256_loadu_ps(cp + 8 * std::size_t(near[t]))), me);
            s01 = _mm512_fmadd_ps(d, _mm512_permutexvar_ps(firstIdx, d), s01);
            s23 = _mm512_fmadd_ps(d, _mm512_permutexvar_ps(ownIdx, d), s23);
        }
    } else {
        const __m256 tz8 = _mm256_setr_ps(0, 0, 0, cell.xz, cell.yz, cell.l[2], 0, 0);
        const __m256 ty8 = _mm256_setr_ps(0, 0, 0, cell.xy, cell.l[1], 0, 0, 0);
        const __m256 tx8 = _mm256_setr_ps(0, 0, 0, cell.l[0], 0, 0, 0, 0);
        const __m512 tz = _mm512_broadcast_f32x8(tz8), ty = _mm512_broadcast_f32x8(ty8),
                     tx = _mm512_broadcast_f32x8(tx8);
        const __m512 ilx = _mm512_set1_ps(cell.inv[0]), ily = _mm512_set1_ps(cell.inv[1]),
                     ilz = _mm512_set1_ps(cell.inv[2]);
        const __m512i laneX = _mm512_set1_epi32(3), laneY = _mm512_set1_epi32(4),
                      laneZ = _mm512_set1_epi32(5);
        constexpr int kRound = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
        const bool wrapX = cell.periodic[0], wrapY = cell.periodic[1], wrapZ = cell.periodic[2];
        for (std::size_t t = 0; t < n; ++t) {
            const __m512 x = _mm512_sub_ps(
                _mm512_broadcast_f32x8(_mm256_loadu_ps(cp + 8 * std::size_t(near[t]))), me);
            __m512 d = x; // as the AVX2 sums, lane by lane
            if (wrapZ)
                d = _mm512_fnmadd_ps(
                    _mm512_roundscale_ps(_mm512_mul_ps(_mm512_permutexvar_ps(laneZ, d), ilz),
                                         kRound),
                    tz, d);
            if (wrapY)
                d = _mm512_fnmadd_ps(
                    _mm512_roundscale_ps(_mm512_mul_ps(_mm512_permutexvar_ps(laneY, d), ily),
                                         kRound),
                    ty, d);
            if (wrapX)
                d = _mm512_fnmadd_ps(
                    _mm512_roundscale_ps(_mm512_mul_ps(_mm512_permutexvar_ps(laneX, d), ilx),
                                         kRound),
                    tx, d);
            // X from the offset before the wrap (the AVX2 sums read it from the packed centres).
            s01 = _mm512_fmadd_ps(d, _mm512_permutexvar_ps(firstIdx, x), s01);
            s23 = _mm512_fmadd_ps(d, _mm512_permutex2var_ps(x, secondIdx, d), s23);
        }
    }
    _mm512_storeu_ps(out.r[0], s01);     // r[0], r[1]
    _mm512_storeu_ps(out.r[2], s23);     // r[2], r[3]
    out.count = static_cast<int>(n) - 1; // the sphere itself (X = U = 0: no term)
}

FAULTLINE_AVX512 void cellSums512(const NeighbourCells& cells, const NeighbourCells::At& cell,
                                  const std::uint32_t* selves, std::size_t count, float cutoff2,
                                  const CellF& now, bool wrap, Packed& packed, RawSums* out) {
    float lo[3], hi[3];
    const Runs runs = runsAround(cells, cell, selves, count, packed, lo, hi);
    packCandidates512(cells, runs, lo, hi, cutoff2, packed);
    // A sphere's neighbours found while the one before it sums its own: each list read well
    // after it was stored (a load of a few bytes right after a whole vector was stored there
    // waits for the store).
    const std::size_t stride = packed.size + 16;
    if (packed.near.size() < 2 * stride)
        packed.near.resize(2 * stride);
    std::uint32_t* lists[2] = {packed.near.data(), packed.near.data() + stride};
    std::size_t found[2] = {0, 0};
    for (std::size_t s = 0; s <= count; ++s) {
        if (s < count)
            found[s & 1] = neighbours512(packed, cells.point(selves[s]), cutoff2, lists[s & 1]);
        if (s == 0)
            continue;
        const std::size_t p = s - 1;
        if (wrap)
            accumulate512<true>(cells, lists[p & 1], found[p & 1], cells.point(selves[p]), now,
                                out[p]);
        else
            accumulate512<false>(cells, lists[p & 1], found[p & 1], cells.point(selves[p]), now,
                                 out[p]);
    }
}
#if !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

std::atomic<bool> g_baselineOnly{false};
std::atomic<bool> g_avx512Allowed{true};

bool useAvx2() {
#if FAULTLINE_STRAIN_AVX2
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return has && !g_baselineOnly.load(std::memory_order_relaxed);
#else
    return false;
#endif
}

bool useAvx512() {
#if FAULTLINE_STRAIN_AVX2
    static const bool has =
        __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
    return has && useAvx2() && g_avx512Allowed.load(std::memory_order_relaxed);
#else
    return false;
#endif
}

//-----------------------------------------------------------------------------
// [SECTION] Solving for the strain
//-----------------------------------------------------------------------------

struct StrainValues {
    float shear = kNaN, volumetric = kNaN, d2min = kNaN;
};

constexpr int kXYZ[3] = {0, 1, 2};

// G = A V^-1 and the invariants of E = (F^T F - I) / 2 = (G + G^T + G^T G) / 2 over the axes
// `axes` (2 or 3 of them; 3: x, y, z). The size a template argument: the loops unrolled (this
// was a third of the time of the sums themselves).
template <int dim> StrainValues solve(const NeighbourSums& s, const int* axes) {
    StrainValues out;
    if (s.count < 3)
        return out;
    if constexpr (dim == 3)
        axes = kXYZ;
    Mat3d V{}, A{};
    for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
            V[i][j] = s.V[axes[i]][axes[j]];
            A[i][j] = s.A[axes[i]][axes[j]];
        }
    Mat3d inv{};
    const double trace = dim == 3 ? V[0][0] + V[1][1] + V[2][2] : V[0][0] + V[1][1];
    if constexpr (dim == 3) {
        const double scale = trace / 3;
        if (!invert3(V, 1e-9 * scale * scale * scale, inv))
            return out;
    } else {
        const double det = V[0][0] * V[1][1] - V[0][1] * V[1][0];
        const double scale = trace / 2;
        if (!(std::fabs(det) > 1e-9 * scale * scale))
            return out;
        const double rdet = 1.0 / det;
        inv[0][0] = V[1][1] * rdet;
        inv[0][1] = -V[0][1] * rdet;
        inv[1][0] = -V[1][0] * rdet;
        inv[1][1] = V[0][0] * rdet;
    }
    double G[3][3] = {};
    for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
            for (int k = 0; k < dim; ++k)
                G[i][j] += A[i][k] * inv[k][j];
    double E[3][3] = {};
    for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
            double c = 0;
            for (int k = 0; k < dim; ++k)
                c += G[k][i] * G[k][j];
            E[i][j] = 0.5 * (G[i][j] + G[j][i] + c);
        }
    double uu = 0, ga = 0;
    for (int i = 0; i < dim; ++i) {
        uu += s.uu[axes[i]];
        for (int j = 0; j < dim; ++j)
            ga += G[i][j] * A[i][j];
    }
    // Rounding may leave a hair below zero; NaN (sums of absurd motions) stays NaN.
    const double residual = uu - ga;
    out.d2min = static_cast<float>(residual < 0 ? 0.0 : residual);
    if constexpr (dim == 3) {
        const double dxy = E[0][0] - E[1][1], dyz = E[1][1] - E[2][2], dzx = E[2][2] - E[0][0];
        out.shear =
            static_cast<float>(std::sqrt(E[0][1] * E[0][1] + E[1][2] * E[1][2] + E[0][2] * E[0][2] +
                                         (dxy * dxy + dyz * dyz + dzx * dzx) / 6.0));
        out.volumetric = static_cast<float>((E[0][0] + E[1][1] + E[2][2]) / 3.0);
    } else {
        const double d = E[0][0] - E[1][1];
        out.shear = static_cast<float>(std::sqrt(E[0][1] * E[0][1] + d * d / 2.0));
        out.volumetric = static_cast<float>((E[0][0] + E[1][1]) / 2.0);
    }
    return out;
}

#if FAULTLINE_STRAIN_AVX2
// solve<3> for four or eight spheres at once, one per lane of vectors of doubles: the same
// operations in the same order (sums start from zero as its loops do; no multiply-adds are
// fused in ISO C++ mode), so the same values to the last bit, whichever solves a sphere.
// `col`: the sums' vectors r[b] of the spheres widened to double, col[b][k] holding lane k of
// each; `count`: their neighbour counts. Inlined into the AVX2 and AVX-512 solves below.
template <typename VD, int N>
[[gnu::always_inline]] inline void solveLanes(const VD (&col)[4][6], const double* count,
                                              StrainValues* out) {
    VD V[3][3], A[3][3], uu[3];
    unpackSums(col, V, A, uu);
    // invert3's operations, lane by lane.
    VD det;
    determinant3(V, det);
    const VD scale = (V[0][0] + V[1][1] + V[2][2]) / 3.0;
    VD inv[3][3];
    scaledAdjugate3(V, 1.0 / det, inv);
    VD G[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            G[i][j] = VD{} + A[i][0] * inv[0][j] + A[i][1] * inv[1][j] + A[i][2] * inv[2][j];
    VD E[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            E[i][j] = 0.5 * (G[i][j] + G[j][i] +
                             (VD{} + G[0][i] * G[0][j] + G[1][i] * G[1][j] + G[2][i] * G[2][j]));
    VD ga = VD{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            ga += G[i][j] * A[i][j];
    const VD residual = (VD{} + uu[0] + uu[1] + uu[2]) - ga;
    const VD dxy = E[0][0] - E[1][1], dyz = E[1][1] - E[2][2], dzx = E[2][2] - E[0][0];
    const VD shear2 = E[0][1] * E[0][1] + E[1][2] * E[1][2] + E[0][2] * E[0][2] +
                      (dxy * dxy + dyz * dyz + dzx * dzx) / 6.0;
    const VD volumetric = (E[0][0] + E[1][1] + E[2][2]) / 3.0;
    for (int l = 0; l < N; ++l) {
        // As solve<3>: too few neighbours or a nearly singular sum (or NaN): no value.
        // (The square root per lane: correctly rounded, as the vector one.)
        if (count[l] < 3 || !(std::fabs(det[l]) > 1e-9 * scale[l] * scale[l] * scale[l])) {
            out[l] = StrainValues{};
            continue;
        }
        out[l].shear = static_cast<float>(std::sqrt(shear2[l]));
        out[l].volumetric = static_cast<float>(volumetric[l]);
        out[l].d2min = static_cast<float>(residual[l] < 0 ? 0.0 : residual[l]);
    }
}

// Four spheres' sums transposed (unpack, then shuffle: lane k of the four in the low half of
// u[k % 4], or the high half for k >= 4) and widened to double, which is exact: out[b][k] holds
// lane k of the four spheres' r[b].
FAULTLINE_AVX2 inline void widenSums4(const RawSums* s, __m256d (&out)[4][6]) {
    for (int b = 0; b < 4; ++b) {
        const __m256 r0 = _mm256_load_ps(s[0].r[b]), r1 = _mm256_load_ps(s[1].r[b]),
                     r2 = _mm256_load_ps(s[2].r[b]), r3 = _mm256_load_ps(s[3].r[b]);
        const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
        const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
        const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
        const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
        out[b][0] = _mm256_cvtps_pd(_mm256_castps256_ps128(u0));
        out[b][1] = _mm256_cvtps_pd(_mm256_castps256_ps128(u1));
        out[b][2] = _mm256_cvtps_pd(_mm256_castps256_ps128(u2));
        out[b][3] = _mm256_cvtps_pd(_mm256_castps256_ps128(u3));
        out[b][4] = _mm256_cvtps_pd(_mm256_extractf128_ps(u0, 1));
        out[b][5] = _mm256_cvtps_pd(_mm256_extractf128_ps(u1, 1));
    }
}

FAULTLINE_AVX2 void solve3x4(const RawSums* s, StrainValues* out) {
    typedef double v4d __attribute__((vector_size(32)));
    __m256d w[4][6];
    widenSums4(s, w);
    v4d col[4][6];
    for (int b = 0; b < 4; ++b)
        for (int k = 0; k < 6; ++k)
            col[b][k] = v4d(w[b][k]);
    const double count[4] = {double(s[0].count), double(s[1].count), double(s[2].count),
                             double(s[3].count)};
    solveLanes<v4d, 4>(col, count, out);
}

// The same for eight spheres, in AVX-512 doubles: half the instructions of two four-wide solves.
FAULTLINE_AVX512 void solve3x8(const RawSums* s, StrainValues* out) {
    typedef double v8d __attribute__((vector_size(64)));
    typedef double v4d __attribute__((vector_size(32)));
    __m256d lo[4][6], hi[4][6];
    widenSums4(s, lo);
    widenSums4(s + 4, hi);
    v8d col[4][6];
    for (int b = 0; b < 4; ++b)
        for (int k = 0; k < 6; ++k)
            col[b][k] =
                __builtin_shufflevector(v4d(lo[b][k]), v4d(hi[b][k]), 0, 1, 2, 3, 4, 5, 6, 7);
    double count[8];
    for (int l = 0; l < 8; ++l)
        count[l] = double(s[l].count);
    solveLanes<v8d, 8>(col, count, out);
}
#endif

//-----------------------------------------------------------------------------
// [SECTION] The columns
//-----------------------------------------------------------------------------

std::vector<AttributeColumn> namedColumns(std::size_t rows, const std::string& prefix) {
    std::vector<AttributeColumn> cols(kStrainVariables.size());
    // In parallel: filling the columns is their first touch (page faults, a millisecond each).
    tbb::parallel_for(std::size_t{0}, cols.size(), [&](std::size_t k) {
        cols[k].name = prefix + std::string(kStrainVariables[k]);
        cols[k].type = ColumnType::Float32;
        cols[k].floats.assign(rows, kNaN);
    });
    return cols;
}

} // namespace

double packingStrainCutoff(const Frame& ref) { return 1.5 * packingSpacing(ref); }

double defaultStrainCutoff(const Frame& ref) {
    if (ref.size() == 0)
        return 1.0;
    const double r = medianRadius(ref);
    return std::isnan(r) ? packingStrainCutoff(ref) : 1.5 * 2.0 * r;
}

double strainNeighboursWithin(const Frame& ref, double cutoff) {
    const std::size_t n = ref.size();
    const auto [volume, dims] = centreBounds(ref);
    if (n < 2)
        return 0;
    if (dims == 0 || !(volume > 0) || !std::isfinite(volume) || !std::isfinite(cutoff))
        return double(n - 1); // every centre at one point, or no bounds to measure: all of them
    const double density = double(n) / volume;
    const double reach = dims == 3   ? 4.0 / 3.0 * M_PI * cutoff * cutoff * cutoff
                         : dims == 2 ? M_PI * cutoff * cutoff
                                     : 2.0 * cutoff;
    return std::min(double(n - 1), density * reach);
}

std::vector<AttributeColumn> strainUnavailable(const Frame& now, const std::string& prefix) {
    auto cols = namedColumns(now.size(), prefix);
    for (auto& c : cols)
        c.min = c.max = 0.0;
    return cols;
}

std::vector<AttributeColumn> strainFromMotion(const Frame& now, const Frame& ref, double cutoff,
                                              const std::string& prefix) {
    if (!(cutoff > 0) || !std::isfinite(cutoff))
        cutoff = defaultStrainCutoff(ref);
    auto cols = namedColumns(now.size(), prefix);
    if (now.size() == 0 || ref.size() == 0) {
        for (auto& c : cols)
            cacheColumnRange(c);
        return cols;
    }
    if (ref.size() >= kNone || now.size() >= kNone) // rows are 32-bit, kNone the mark of none
        throw std::length_error("strain from motion: 2^32 spheres or more in one frame");
    // Where each reference sphere is in the current frame (rowsOf's "none" is kNone).
    auto nowRowOf = makeScratchArray<std::uint32_t>(ref.size());
    const bool aligned = sameIdOrder(now, ref);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ref.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          if (!aligned) {
                              now.rowsOf({ref.ids.data() + range.begin(), range.size()},
                                         nowRowOf.get() + range.begin());
                              return;
                          }
                          for (std::size_t r = range.begin(); r != range.end(); ++r)
                              nowRowOf[r] = static_cast<std::uint32_t>(r);
                      });
    const NeighbourCells cells(ref, now, nowRowOf.get(), cutoff);
    const PeriodicCell nowCell(now.box);
    const int flat = flatAxis(ref);
    int axes[3] = {0, 1, 2};
    int dim = 3;
    if (flat >= 0) {
        dim = 2;
        int k = 0;
        for (int a = 0; a < 3; ++a)
            if (a != flat)
                axes[k++] = a;
    }
    // At most the largest float: the padding lanes (infinitely far) must stay out of reach.
    const float cutoff2 =
        static_cast<float>(std::min(cutoff * cutoff, double(std::numeric_limits<float>::max())));
    static_assert(kStrainVariables.size() == 7);
    float* const columns[7] = {cols[0].floats.data(), cols[1].floats.data(), cols[2].floats.data(),
                               cols[3].floats.data(), cols[4].floats.data(), cols[5].floats.data(),
                               cols[6].floats.data()};
    const CellF nowCellF(nowCell);
    // U, the difference of two motions, is its own minimum image where no motion reaches an
    // eighth of the cell on a periodic axis (as in most increments): the sums skip the wrap.
    bool wrap = false;
    for (int a = 0; a < 3; ++a)
        wrap = wrap || (nowCellF.periodic[a] &&
                        !(double(cells.widestMotion()[a]) * nowCellF.inv[a] <= 0.125));
    // Cell by cell: the points around a cell gathered once for all the spheres in it. Each
    // sphere's values and motion are kept by slot, as the cells are summed (images' slots are
    // neither written nor read), and taken to the current frame's rows after: one record read
    // per row rather than seven writes scattered over the columns.
    // 24 bytes, not padded to 32: a quarter less of the memory written here and read back
    // (scattered) below, in a pass whose cost is that memory.
    struct SlotValues {
        float shear, volumetric, d2min;
        float w[3];
    };
    auto values = makeScratchArray<SlotValues>(cells.pointCount());
    const bool avx2 = useAvx2();
    const bool avx512 = useAvx512();
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, cells.cellCount(), 64),
        [&](const tbb::blocked_range<std::size_t>& range) {
            Candidates candidates;
#if FAULTLINE_STRAIN_AVX2
            Packed packed;
#endif
            // The spheres summed and not yet solved, solved four at a time across cells.
            std::vector<std::uint32_t> selves;
            std::vector<NeighbourSums> sums; // baseline
            std::unique_ptr<RawSums[]> raw;  // AVX2, one for each of `selves`
            std::size_t rawCapacity = 0;
            auto store = [&](std::size_t k, const StrainValues& v) {
                const float* q = cells.point(k);
                values[k] = {v.shear, v.volumetric, v.d2min, {q[3], q[4], q[5]}};
            };
            auto solveSummed = [&](bool all) {
                std::size_t s = 0;
#if FAULTLINE_STRAIN_AVX2
                if (avx2) {
                    if (dim == 3 && avx512)
                        for (; s + 8 <= selves.size(); s += 8) {
                            StrainValues v[8];
                            solve3x8(raw.get() + s, v);
                            for (int l = 0; l < 8; ++l)
                                store(selves[s + l], v[l]);
                        }
                    if (dim == 3)
                        for (; s + 4 <= selves.size(); s += 4) {
                            StrainValues v[4];
                            solve3x4(raw.get() + s, v);
                            for (int l = 0; l < 4; ++l)
                                store(selves[s + l], v[l]);
                        }
                    // The rest one by one: the last few, or every sphere of 2-D data (not held
                    // back, or each call would move all that were held).
                    if (all || dim != 3)
                        for (; s < selves.size(); ++s) {
                            const NeighbourSums one = sumsOf(raw[s]);
                            store(selves[s], dim == 3 ? solve<3>(one, axes) : solve<2>(one, axes));
                        }
                    std::copy(raw.get() + s, raw.get() + selves.size(), raw.get());
                } else
#endif
                {
                    for (; s < selves.size(); ++s)
                        store(selves[s],
                              dim == 3 ? solve<3>(sums[s], axes) : solve<2>(sums[s], axes));
                    sums.clear();
                }
                selves.erase(selves.begin(), selves.begin() + std::ptrdiff_t(s));
            };
            for (auto at = cells.at(range.begin()); at.index != range.end(); cells.next(at)) {
                const std::size_t cell = at.index;
                const std::size_t first = selves.size();
                for (std::size_t self = cells.begin(cell); self != cells.spheresEnd(cell); ++self) {
                    if (std::isnan(cells.point(self)[3])) // gone, or a centre that is no number
                        store(self, StrainValues{});
                    else
                        selves.push_back(static_cast<std::uint32_t>(self));
                }
                const std::size_t count = selves.size() - first;
                if (count == 0)
                    continue;
#if FAULTLINE_STRAIN_AVX2
                if (avx2) {
                    if (rawCapacity < selves.size()) {
                        rawCapacity = std::max<std::size_t>(2 * rawCapacity, selves.size());
                        std::unique_ptr<RawSums[]> more(new RawSums[rawCapacity]); // not zeroed
                        std::copy(raw.get(), raw.get() + first, more.get());
                        raw = std::move(more);
                    }
                    if (avx512)
                        cellSums512(cells, at, selves.data() + first, count, cutoff2, nowCellF,
                                    wrap, packed, raw.get() + first);
                    else
                        cellSumsAvx2(cells, at, selves.data() + first, count, cutoff2, nowCellF,
                                     wrap, packed, raw.get() + first);
                } else
#endif
                {
                    sums.resize(selves.size()); // each new one written whole by cellSums
                    cellSumsBaseline(cells, at, selves.data() + first, count, cutoff2, nowCellF,
                                     wrap, candidates, sums.data() + first);
                }
                if (selves.size() >= 64)
                    solveSummed(false);
            }
            solveSummed(true);
        });
    // Each current row's values and motion from its slot (prefetched: the slots come in no
    // order), and each column's range on the way (as cacheColumnRange gives it).
    const NowPoint* nowPoints = cells.nowPoints();
    constexpr int kColumns = 7;
    struct Ranges {
        float lo[kColumns], hi[kColumns];
        Ranges() {
            std::fill(lo, lo + kColumns, std::numeric_limits<float>::infinity());
            std::fill(hi, hi + kColumns, -std::numeric_limits<float>::infinity());
        }
    };
    const Ranges ranges = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, now.size(), 16384), Ranges{},
        [&](const tbb::blocked_range<std::size_t>& range, Ranges acc) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (i + 16 < range.end() && nowPoints[i + 16].slot != kNone) {
                    // Both ends: a 24-byte record may straddle two cache lines.
                    const char* at = reinterpret_cast<const char*>(&values[nowPoints[i + 16].slot]);
                    __builtin_prefetch(at);
                    __builtin_prefetch(at + sizeof(SlotValues) - 1);
                }
                const NowPoint& p = nowPoints[i];
                const std::uint32_t k = p.slot;
                if (k == kNone)
                    continue; // NaN already
                const SlotValues& v = values[k];
                const double w[3] = {v.w[0], v.w[1], v.w[2]};
                const float row[kColumns] = {
                    v.shear,
                    v.volumetric,
                    v.d2min,
                    static_cast<float>(std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])),
                    static_cast<float>(p.x - w[0]),
                    static_cast<float>(p.y - w[1]),
                    static_cast<float>(p.z - w[2])};
                for (int c = 0; c < kColumns; ++c) {
                    columns[c][i] = row[c];
                    if (row[c] < acc.lo[c]) // false for NaN
                        acc.lo[c] = row[c];
                    if (row[c] > acc.hi[c])
                        acc.hi[c] = row[c];
                }
            }
            return acc;
        },
        [](Ranges a, const Ranges& b) {
            for (int c = 0; c < kColumns; ++c) {
                a.lo[c] = std::min(a.lo[c], b.lo[c]);
                a.hi[c] = std::max(a.hi[c], b.hi[c]);
            }
            return a;
        });
    for (int c = 0; c < kColumns; ++c) {
        if (ranges.lo[c] > ranges.hi[c]) {
            cols[c].min = cols[c].max = 0.0; // empty or all NaN, as cacheColumnRange gives
        } else {
            cols[c].min = ranges.lo[c];
            cols[c].max = ranges.hi[c];
        }
    }
    return cols;
}

void detail::setStrainBaselineOnly(bool baselineOnly) { g_baselineOnly = baselineOnly; }

bool detail::strainUsesAvx2() { return useAvx2(); }

void detail::setStrainAvx512Allowed(bool allowed) { g_avx512Allowed = allowed; }

bool detail::strainUsesAvx512() { return useAvx512(); }

std::optional<std::size_t> StrainSpec::referenceFor(std::size_t frame, std::size_t count) const {
    const long long f = relative ? static_cast<long long>(frame) + reference : reference;
    if (f < 0 || f >= static_cast<long long>(count))
        return std::nullopt;
    return static_cast<std::size_t>(f);
}

} // namespace faultline::core
