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
#include "core/model/periodic_cell.hpp"
#include "core/motion/strain_spec.hpp"
#include "core/util/mat3.hpp"
#include "core/util/simd8.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

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
    float x, y, z;       // reference
    float wx, wy, wz;    // motion
    std::uint32_t owner; // reference row; the top bit marks an image
};
constexpr std::uint32_t kImage = 0x80000000u;

//-----------------------------------------------------------------------------
// [SECTION] Neighbour cells
//-----------------------------------------------------------------------------

// The reference centres and, on periodic axes, their images within `cutoff` of the centres'
// bounds, sorted into cubic cells of at least `cutoff`: neighbours of a sphere lie in its cell
// and the 26 around it, an image's vector is the minimum-image one, and a sphere's neighbours
// are read from memory in order (no lookups by id in the inner loop).
class NeighbourCells {
  public:
    NeighbourCells(const Frame& ref, const Frame& now, const std::vector<std::uint32_t>& nowRowOf,
                   double cutoff)
        : m_nowCell(now.box) {
        const std::size_t n = ref.size();
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
            for (int na = -1; na <= 1; ++na)
                for (int nb = -1; nb <= 1; ++nb)
                    for (int nc = -1; nc <= 1; ++nc) {
                        if ((na == 0 && nb == 0 && nc == 0) || (na && !cell.periodic[0]) ||
                            (nb && !cell.periodic[1]) || (nc && !cell.periodic[2]))
                            continue;
                        double s[3];
                        for (int a = 0; a < 3; ++a)
                            s[a] = na * edge[0][a] + nb * edge[1][a] + nc * edge[2][a];
                        for (std::size_t i = 0; i < n; ++i) {
                            const double q[3] = {ref.x[i] + s[0], ref.y[i] + s[1], ref.z[i] + s[2]};
                            if (q[0] < lo[0] || q[0] > hi[0] || q[1] < lo[1] || q[1] > hi[1] ||
                                q[2] < lo[2] || q[2] > hi[2])
                                continue;
                            CellPoint p = pointOf(ref, now, nowRowOf, i, s);
                            p.x = static_cast<float>(q[0]);
                            p.y = static_cast<float>(q[1]);
                            p.z = static_cast<float>(q[2]);
                            p.owner |= kImage;
                            images.push_back(p);
                        }
                    }
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
                m_dims[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / m_size) + 1);
                cells *= m_dims[a];
            }
            if (cells <= 4.0 * double(count) + 64)
                break;
            m_size *= 1.25;
        }
        for (int a = 0; a < 3; ++a)
            m_lo[a] = lo[a];
        std::vector<std::uint32_t> cellOf(count);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t k = r.begin(); k != r.end(); ++k)
                                  cellOf[k] = k < n ? cellIndex(ref.x[k], ref.y[k], ref.z[k])
                                                    : cellIndex(images[k - n].x, images[k - n].y,
                                                                images[k - n].z);
                          });
        const std::size_t cells = std::size_t(m_dims[0]) * m_dims[1] * m_dims[2];
        m_start.assign(cells + 1, 0);
        for (std::uint32_t c : cellOf)
            ++m_start[c + 1];
        for (std::size_t c = 0; c < cells; ++c)
            m_start[c + 1] += m_start[c];
        // Each point's slot in cell order (in turn: the order within a cell is the points'),
        // then the points written to their slots in parallel.
        std::vector<std::uint32_t> fill(m_start.begin(), m_start.end() - 1);
        std::vector<std::uint32_t>& slot = cellOf; // cellOf[k] read once, then k's slot
        for (std::size_t k = 0; k < count; ++k)
            slot[k] = fill[slot[k]]++;
        // Reference positions and motions as float arrays in cell order.
        // Not zeroed first (every slot is written below, in parallel: a serial clearing of
        // these ~30 bytes a point cost as much as filling them).
        for (auto* v : {&m_x, &m_y, &m_z, &m_wx, &m_wy, &m_wz})
            v->reset(new float[count]);
        m_owner.reset(new std::uint32_t[count]);
        m_count = count;
        m_slotOfNow.reset(new std::uint32_t[now.size()]);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, now.size(), 65536),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              std::fill(m_slotOfNow.get() + r.begin(), m_slotOfNow.get() + r.end(),
                                        kNone);
                          });
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16384),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              const double noShift[3] = {0, 0, 0};
                              for (std::size_t k = r.begin(); k != r.end(); ++k) {
                                  const std::uint32_t at = slot[k];
                                  const CellPoint p = k < n
                                                          ? pointOf(ref, now, nowRowOf, k, noShift)
                                                          : images[k - n];
                                  m_x[at] = p.x, m_y[at] = p.y, m_z[at] = p.z;
                                  m_wx[at] = p.wx, m_wy[at] = p.wy, m_wz[at] = p.wz;
                                  m_owner[at] = p.owner;
                                  if (k < n && nowRowOf[k] != kNone)
                                      m_slotOfNow[nowRowOf[k]] = at;
                              }
                          });
    }

    std::size_t cellCount() const { return m_start.size() - 1; }
    std::size_t pointCount() const { return m_count; }
    std::size_t begin(std::size_t cell) const { return m_start[cell]; }
    std::size_t end(std::size_t cell) const { return m_start[cell + 1]; }
    std::uint32_t owner(std::size_t k) const { return m_owner[k]; }
    // Where each row of the current frame is in cell order (kNone: not in the reference).
    const std::uint32_t* slotOfNow() const { return m_slotOfNow.get(); }
    // Reference positions (x, y, z) and motions (wx, wy, wz; NaN: gone) in cell order.
    const float* xs() const { return m_x.get(); }
    const float* ys() const { return m_y.get(); }
    const float* zs() const { return m_z.get(); }
    const float* wxs() const { return m_wx.get(); }
    const float* wys() const { return m_wy.get(); }
    const float* wzs() const { return m_wz.get(); }

    // fn(first, last) for each run of points in the 27 cells around `cell` (9 runs of up to
    // three cells that lie next to each other in memory).
    template <typename Fn> void around(std::size_t cell, Fn fn) const {
        const int cx = int(cell % m_dims[0]);
        const int cy = int((cell / m_dims[0]) % m_dims[1]);
        const int cz = int(cell / (std::size_t(m_dims[0]) * m_dims[1]));
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
    CellPoint pointOf(const Frame& ref, const Frame& now,
                      const std::vector<std::uint32_t>& nowRowOf, std::size_t i,
                      const double shift[3]) const {
        const std::uint32_t k = nowRowOf[i];
        const float nan = std::numeric_limits<float>::quiet_NaN();
        CellPoint p{ref.x[i], ref.y[i], ref.z[i], nan, nan, nan, static_cast<std::uint32_t>(i)};
        if (k != kNone) {
            double w[3] = {double(now.x[k]) - ref.x[i] - shift[0],
                           double(now.y[k]) - ref.y[i] - shift[1],
                           double(now.z[k]) - ref.z[i] - shift[2]};
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
    int coord(double v, int axis) const {
        return std::clamp(static_cast<int>((v - m_lo[axis]) / m_size), 0, m_dims[axis] - 1);
    }
    std::uint32_t cellIndex(double px, double py, double pz) const {
        return static_cast<std::uint32_t>(
            (std::size_t(coord(pz, 2)) * m_dims[1] + coord(py, 1)) * m_dims[0] + coord(px, 0));
    }

    double m_lo[3] = {0, 0, 0};
    double m_size = 1;
    int m_dims[3] = {1, 1, 1};
    std::vector<std::uint32_t> m_start;
    std::size_t m_count = 0;
    std::unique_ptr<std::uint32_t[]> m_owner, m_slotOfNow;
    std::unique_ptr<float[]> m_x, m_y, m_z, m_wx, m_wy, m_wz;
    PeriodicCell m_nowCell;
};

// The axis every centre of `f` shares (2-D data), or -1.
int flatAxis(const Frame& f) {
    if (f.size() < 2)
        return -1;
    for (int a = 0; a < 3; ++a)
        if (f.centreMin()[a] == f.centreMax()[a])
            return a;
    return -1;
}

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

// The points of the 27 cells around one cell, contiguous and padded to whole vectors with
// points that are never near: reference positions and how far each moved (w = now - reference;
// an image's reference is shifted by a cell edge; NaN: gone).
struct Candidates {
    std::vector<float> x, y, z, wx, wy, wz;
    std::size_t size = 0;
    [[gnu::always_inline]] inline void gather(const NeighbourCells& cells, std::size_t cell) {
        size = 0;
        cells.around(cell, [&](std::size_t first, std::size_t last) {
            const std::size_t n = last - first;
            if (x.size() < size + n + 8)
                for (auto* v : {&x, &y, &z, &wx, &wy, &wz})
                    v->resize(2 * (size + n + 8));
            for (auto [to, from] : {std::pair{&x, cells.xs()},
                                    {&y, cells.ys()},
                                    {&z, cells.zs()},
                                    {&wx, cells.wxs()},
                                    {&wy, cells.wys()},
                                    {&wz, cells.wzs()}})
                std::copy(from + first, from + last, to->begin() + std::ptrdiff_t(size));
            size += n;
        });
        const float far = std::numeric_limits<float>::infinity();
        for (std::size_t k = size; k < ((size + 7) & ~std::size_t(7)); ++k)
            x[k] = y[k] = z[k] = far, wx[k] = wy[k] = wz[k] = 0.0f;
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
        // Within the cutoff, and still there (a NaN motion is a sphere gone).
        const auto near = (dx * dx + dy * dy + dz * dz <= c2) & (ux == ux);
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
FAULTLINE_HOT void cellSums(const NeighbourCells& cells, std::size_t cell,
                            const std::uint32_t* selves, std::size_t count, float cutoff2,
                            const CellF& now, bool wrap, Candidates& candidates,
                            NeighbourSums* out) {
    candidates.gather(cells, cell);
    for (std::size_t s = 0; s < count; ++s) {
        const std::size_t k = selves[s];
        const float sphere[6] = {cells.xs()[k],  cells.ys()[k],  cells.zs()[k],
                                 cells.wxs()[k], cells.wys()[k], cells.wzs()[k]};
        if (wrap)
            sumNeighboursBody<true>(candidates, sphere, cutoff2, now, out[s]);
        else
            sumNeighboursBody<false>(candidates, sphere, cutoff2, now, out[s]);
    }
}

//-----------------------------------------------------------------------------
// [SECTION] Solving for the strain
//-----------------------------------------------------------------------------

struct StrainValues {
    float shear = kNaN, volumetric = kNaN, d2min = kNaN;
};

// G = A V^-1 and the invariants of E = (F^T F - I) / 2 = (G + G^T + G^T G) / 2 over the axes
// `axes` (2 or 3 of them).
StrainValues solve(const NeighbourSums& s, const int* axes, int dim) {
    StrainValues out;
    if (s.count < 3)
        return out;
    Mat3d V{}, A{};
    for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
            V[i][j] = s.V[axes[i]][axes[j]];
            A[i][j] = s.A[axes[i]][axes[j]];
        }
    Mat3d inv{};
    const double trace = dim == 3 ? V[0][0] + V[1][1] + V[2][2] : V[0][0] + V[1][1];
    if (dim == 3) {
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
    out.d2min = static_cast<float>(std::max(0.0, uu - ga));
    if (dim == 3) {
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

//-----------------------------------------------------------------------------
// [SECTION] The columns
//-----------------------------------------------------------------------------

std::vector<AttributeColumn> namedColumns(std::size_t rows, const std::string& prefix) {
    std::vector<AttributeColumn> cols(kStrainVariables.size());
    for (std::size_t k = 0; k < cols.size(); ++k) {
        cols[k].name = prefix + std::string(kStrainVariables[k]);
        cols[k].type = ColumnType::Float32;
        cols[k].floats.assign(rows, kNaN);
    }
    return cols;
}

} // namespace

double defaultStrainCutoff(const Frame& ref) {
    const std::size_t n = ref.size();
    if (n == 0)
        return 1.0;
    if (!ref.radiusIsDefault) {
        // The median of up to 65,536 evenly spaced radii.
        const std::size_t step = std::max<std::size_t>(1, n / 65536);
        std::vector<float> sample;
        sample.reserve(n / step + 1);
        for (std::size_t i = 0; i < n; i += step)
            sample.push_back(ref.radius[i]);
        std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
        const double r = sample[sample.size() / 2];
        if (r > 0 && std::isfinite(r))
            return 1.5 * 2.0 * r;
    }
    // No radii: a random close packing (0.64) of n spheres in the centres' bounds has diameter
    // d with n * pi d^3 / 6 = 0.64 V; in 2-D, n * pi d^2 / 4 = 0.84 A.
    const int flat = flatAxis(ref);
    double volume = 1;
    int dims = 0;
    for (int a = 0; a < 3; ++a) {
        const double l = double(ref.centreMax()[a]) - ref.centreMin()[a];
        if (a == flat || !(l > 0))
            continue;
        volume *= l;
        ++dims;
    }
    if (dims == 0)
        return 1.0;
    const double d = dims == 3   ? std::cbrt(0.64 * volume * 6.0 / (M_PI * double(n)))
                     : dims == 2 ? std::sqrt(0.84 * volume * 4.0 / (M_PI * double(n)))
                                 : volume / double(n);
    return 1.5 * d;
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
    if (ref.size() >= kImage)
        throw std::length_error("strain from motion: more than 2^31 spheres in one frame");
    // Where each reference sphere is in the current frame.
    std::vector<std::uint32_t> nowRowOf(ref.size());
    const bool aligned = sameIdOrder(now, ref);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ref.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t r = range.begin(); r != range.end(); ++r) {
                              if (aligned) {
                                  nowRowOf[r] = static_cast<std::uint32_t>(r);
                                  continue;
                              }
                              const auto k = now.rowOf(ref.ids[r]);
                              nowRowOf[r] = k ? static_cast<std::uint32_t>(*k) : kNone;
                          }
                      });
    const NeighbourCells cells(ref, now, nowRowOf, cutoff);
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
    float* shear = cols[0].floats.data();
    float* volumetric = cols[1].floats.data();
    float* d2min = cols[2].floats.data();
    float* displacement = cols[3].floats.data();
    float* refX = cols[4].floats.data();
    float* refY = cols[5].floats.data();
    float* refZ = cols[6].floats.data();
    const CellF nowCellF(nowCell);
    // Cell by cell: the points around a cell gathered once for all the spheres in it. The values
    // are kept in cell order, as the cells are summed, and taken to the current frame's rows
    // after: one read per row rather than seven writes scattered over the columns.
    struct SlotValues { // written for every slot of a sphere (not an image)
        float shear, volumetric, d2min;
    };
    // One per point of the cell list (images' slots are neither written nor read).
    std::unique_ptr<SlotValues[]> values(new SlotValues[cells.pointCount()]);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, cells.cellCount(), 64),
        [&](const tbb::blocked_range<std::size_t>& range) {
            Candidates candidates;
            std::vector<std::uint32_t> selves;
            std::vector<NeighbourSums> sums;
            for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
                selves.clear();
                for (std::size_t self = cells.begin(cell); self != cells.end(cell); ++self) {
                    if (cells.owner(self) & kImage)
                        continue;
                    if (std::isnan(cells.wxs()[self])) // gone, or a centre that is no number
                        values[self] = {kNaN, kNaN, kNaN};
                    else
                        selves.push_back(static_cast<std::uint32_t>(self));
                }
                if (selves.empty())
                    continue;
                sums.resize(selves.size()); // each one written whole by cellSums
                cellSums(cells, cell, selves.data(), selves.size(), cutoff2, nowCellF, nowCell.any,
                         candidates, sums.data());
                for (std::size_t s = 0; s < selves.size(); ++s) {
                    const std::size_t k = selves[s];
                    const StrainValues v = solve(sums[s], axes, dim);
                    values[k] = {v.shear, v.volumetric, v.d2min};
                }
            }
        });
    // Each current row's values and motion from its slot (prefetched: the slots come in no
    // order).
    const std::uint32_t* slotOfNow = cells.slotOfNow();
    const float *wx = cells.wxs(), *wy = cells.wys(), *wz = cells.wzs();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, now.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              if (i + 16 < range.end() && slotOfNow[i + 16] != kNone) {
                                  const std::uint32_t ahead = slotOfNow[i + 16];
                                  __builtin_prefetch(&values[ahead]);
                                  __builtin_prefetch(wx + ahead);
                                  __builtin_prefetch(wy + ahead);
                                  __builtin_prefetch(wz + ahead);
                              }
                              const std::uint32_t k = slotOfNow[i];
                              if (k == kNone)
                                  continue;
                              const SlotValues& v = values[k];
                              shear[i] = v.shear;
                              volumetric[i] = v.volumetric;
                              d2min[i] = v.d2min;
                              const double w[3] = {wx[k], wy[k], wz[k]};
                              displacement[i] = static_cast<float>(
                                  std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
                              refX[i] = static_cast<float>(now.x[i] - w[0]);
                              refY[i] = static_cast<float>(now.y[i] - w[1]);
                              refZ[i] = static_cast<float>(now.z[i] - w[2]);
                          }
                      });
    for (auto& c : cols)
        cacheColumnRange(c);
    return cols;
}

std::optional<std::size_t> StrainSpec::referenceFor(std::size_t frame, std::size_t count) const {
    const long long f = relative ? static_cast<long long>(frame) + reference : reference;
    if (f < 0 || f >= static_cast<long long>(count))
        return std::nullopt;
    return static_cast<std::size_t>(f);
}

} // namespace faultline::core
