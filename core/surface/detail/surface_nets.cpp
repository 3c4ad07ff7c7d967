#include "core/surface/detail/surface_nets.hpp"

#include "core/surface/detail/field_level.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace faultline::core::detail {

namespace {

using FloatLeaf = openvdb::FloatTree::LeafNodeType;
using VecLeaf = openvdb::Vec3STree::LeafNodeType;
using Vec3f = std::array<float, 3>;

// A leaf's voxels with two voxels of its neighbours on every side (cells reach one voxel below
// the leaf, central differences at their corners one more): padded index p = local + kMargin.
constexpr int kMargin = 2;
constexpr int kPad = 8 + 2 * kMargin;
// Cells by their lowest corner, from one voxel below the leaf to its last voxel.
constexpr int kCells = 9;
constexpr int kNone = -1;
constexpr int kOwnedElsewhere = -2; // a foreign cell's entry is kOwnedElsewhere - (its slot)

inline int padOffset(int i, int j, int k) { return (i * kPad + j) * kPad + k; }
// One voxel along x, y, z in the padded arrays.
constexpr int kPadStep[3] = {kPad * kPad, kPad, 1};
inline int cellOffset(int i, int j, int k) { return (i * kCells + j) * kCells + k; }
inline int leafOffset(int i, int j, int k) { return (i * 8 + j) * 8 + k; }
// Which of the 3 x 3 x 3 leaves (0: below, 1: this one, 2: above) holds padded index p, and
// where in that leaf.
inline int sideOf(int p) { return p < kMargin ? 0 : p >= kMargin + 8 ? 2 : 1; }
inline int localOf(int p) {
    return p < kMargin ? p + 8 - kMargin : p >= kMargin + 8 ? p - kMargin - 8 : p - kMargin;
}
inline int neighbourIndex(int si, int sj, int sk) { return (si * 3 + sj) * 3 + sk; }

constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
constexpr int kCornerOffset[8] = {0, kPad* kPad,     kPad,     kPad* kPad + kPad,
                                  1, kPad* kPad + 1, kPad + 1, kPad* kPad + kPad + 1};
// Each corner's offset among a leaf's 8^3 voxels from the cell's lowest corner.
constexpr int kCornerLeafOffset[8] = {0, 64, 8, 72, 1, 65, 9, 73};
// Which leaves a cell's corners and their central differences (padded voxels [c, c + 3] along
// an axis, for cell index c) reach: 0, the one below as well; 2, the one above as well; 1, this
// leaf only.
inline int aroundCode(int c) { return c < kMargin ? 0 : c + 3 >= kMargin + 8 ? 2 : 1; }
constexpr int kEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                              {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// Each edge's axis (its corners differ along it only).
constexpr auto kEdgeAxis = [] {
    std::array<int, 12> axis{};
    for (int e = 0; e < 12; ++e)
        for (int k = 0; k < 3; ++k)
            if (kCorner[kEdge[e][0]][k] != kCorner[kEdge[e][1]][k])
                axis[e] = k;
    return axis;
}();
// Per pattern of inside corners (bit c: corner c), the edges whose ends differ, in kEdge's order.
struct CrossingEdges {
    int count = 0;
    std::array<std::uint8_t, 12> edge{};
};
constexpr auto kCrossingEdges = [] {
    std::array<CrossingEdges, 256> table{};
    for (int m = 0; m < 256; ++m)
        for (int e = 0; e < 12; ++e)
            if (((m >> kEdge[e][0]) ^ (m >> kEdge[e][1])) & 1)
                table[m].edge[table[m].count++] = std::uint8_t(e);
    return table;
}();

struct Foreign {
    std::uint32_t leaf; // the leaf that owns the cell's vertex
    std::int32_t cell;  // the cell's offset in that leaf's cell table
};

// A leaf's cells number kCells^3 = 729, and it owns at most as many vertices and foreign
// slots: 16 bits hold every entry and cell offset (half the memory of 32, which every build
// allocates and the kernel clears again).
using CellEntry = std::int16_t;
static_assert(kCells * kCells * kCells - 1 <= INT16_MAX &&
                  kOwnedElsewhere - kCells * kCells * kCells >= INT16_MIN,
              "cell entries and offsets fit in 16 bits");

struct LeafWork {
    std::vector<CellEntry> cells; // kCells^3: local vertex, kNone, or a foreign slot
    std::vector<Foreign> foreign;
    std::vector<Vec3f> positions, colors, gradients;
    std::vector<std::array<CellEntry, 4>> quads; // cell offsets, counter-clockwise outside
    std::uint32_t vertexBase = 0;
    std::size_t quadBase = 0;
    void clear() {
        cells.clear(), foreign.clear(), positions.clear(), colors.clear(), gradients.clear();
        quads.clear();
    }
    // Copies of `from`'s lists, each of exactly its size: a leaf holds about 30 vertices, and
    // lists grown in place would keep room for several times that in every leaf.
    void assignExact(const LeafWork& from) {
        cells.assign(from.cells.begin(), from.cells.end());
        foreign.assign(from.foreign.begin(), from.foreign.end());
        positions.assign(from.positions.begin(), from.positions.end());
        colors.assign(from.colors.begin(), from.colors.end());
        gradients.assign(from.gradients.begin(), from.gradients.end());
        quads.assign(from.quads.begin(), from.quads.end());
    }
};

} // namespace

void surfaceNets(const openvdb::FloatGrid& density, const openvdb::Vec3SGrid& color, bool normals,
                 float iso, float h, SurfaceMesh& mesh) {
    std::vector<const FloatLeaf*> leaves;
    for (auto it = density.tree().cbeginLeaf(); it; ++it)
        leaves.push_back(&*it);
    std::unordered_map<std::uint64_t, std::uint32_t> leafIndex;
    leafIndex.reserve(leaves.size() * 2);
    for (std::size_t n = 0; n < leaves.size(); ++n) {
        const auto o = leaves[n]->origin();
        leafIndex.emplace(packKey({o.x() >> 3, o.y() >> 3, o.z() >> 3}),
                          static_cast<std::uint32_t>(n));
    }
    // The colour leaf beside each density leaf (same topology), looked up once.
    std::vector<const VecLeaf*> colorOf(leaves.size(), nullptr);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const auto& range) {
        auto colorAcc = color.getConstAccessor();
        for (std::size_t n = range.begin(); n != range.end(); ++n)
            colorOf[n] = colorAcc.probeConstLeaf(leaves[n]->origin());
    });
    const openvdb::Vec3s background = color.background();
    std::vector<LeafWork> work(leaves.size());

    // Pass 1, per leaf: vertices of the cells it owns (a cell belongs to the leaf of its first
    // stored corner), and quads of the crossing edges that start in it.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const auto& range) {
        auto densityAcc = density.getConstAccessor();
        float value[kPad * kPad * kPad];
        bool stored[kPad * kPad * kPad];
        unsigned char in[kPad * kPad * kPad];
        LeafWork w; // this leaf's lists while they grow (kept by work[n] at their size)
        for (std::size_t n = range.begin(); n != range.end(); ++n) {
            const openvdb::Coord origin = leaves[n]->origin();
            const FloatLeaf* nd[27];
            const VecLeaf* nc[27];
            std::int64_t nleaf[27];
            float tile[27];
            for (int s = 0; s < 27; ++s) {
                const openvdb::Coord o =
                    origin.offsetBy(8 * (s / 9 - 1), 8 * ((s / 3) % 3 - 1), 8 * (s % 3 - 1));
                const auto it = leafIndex.find(packKey({o.x() >> 3, o.y() >> 3, o.z() >> 3}));
                const bool leaf = it != leafIndex.end();
                nd[s] = leaf ? leaves[it->second] : nullptr;
                nc[s] = leaf ? colorOf[it->second] : nullptr;
                nleaf[s] = leaf ? std::int64_t(it->second) : -1;
                tile[s] = leaf ? 0.0f : densityAcc.getValue(o);
            }
            const float* data[27];
            const openvdb::Vec3s* colorData[27];
            bool full[27]; // every voxel stored (the leaves buildSurface makes)
            for (int q = 0; q < 27; ++q) {
                data[q] = nd[q] ? nd[q]->buffer().data() : nullptr;
                colorData[q] = nc[q] ? nc[q]->buffer().data() : nullptr;
                full[q] = nd[q] && nd[q]->getValueMask().isOn();
            }
            // Per cell, whether every voxel its corners and their central differences read (a
            // 4^3 block of padded voxels from the cell's index) is stored, so that the corner
            // loops below need not ask: whether the leaves that block touches are full. Indexed
            // by aroundCode() of the cell's index along each axis.
            bool storedAround[3][3][3];
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    for (int c = 0; c < 3; ++c) {
                        bool all = true;
                        for (int si = std::min(a, 1); si <= std::max(a, 1); ++si)
                            for (int sj = std::min(b, 1); sj <= std::max(b, 1); ++sj)
                                for (int sk = std::min(c, 1); sk <= std::max(c, 1); ++sk)
                                    all = all && full[neighbourIndex(si, sj, sk)];
                        storedAround[a][b][c] = all;
                    }
            // Rows along z: kMargin voxels of the leaf below, 8 of the same leaf, kMargin of
            // the one above, each part copied with its size known here (no memcpy calls).
            auto part = [&]<int Count>(int s, int off, float* out, bool* on) {
                if (data[s]) {
                    std::memcpy(out, data[s] + off, Count * sizeof(float));
                    if (full[s]) {
                        std::memset(on, 1, Count);
                    } else {
                        const auto& mask = nd[s]->getValueMask();
                        for (int k = 0; k < Count; ++k)
                            on[k] = mask.isOn(off + k);
                    }
                } else {
                    for (int k = 0; k < Count; ++k) {
                        out[k] = tile[s];
                        on[k] = false;
                    }
                }
            };
            for (int i = 0; i < kPad; ++i)
                for (int j = 0; j < kPad; ++j) {
                    const int si = sideOf(i), sj = sideOf(j), li = localOf(i), lj = localOf(j);
                    float* out = &value[padOffset(i, j, 0)];
                    bool* on = &stored[padOffset(i, j, 0)];
                    part.template operator()<kMargin>(neighbourIndex(si, sj, 0),
                                                      leafOffset(li, lj, 8 - kMargin), out, on);
                    part.template operator()<8>(neighbourIndex(si, sj, 1), leafOffset(li, lj, 0),
                                                out + kMargin, on + kMargin);
                    part.template operator()<kMargin>(neighbourIndex(si, sj, 2),
                                                      leafOffset(li, lj, 0), out + kMargin + 8,
                                                      on + kMargin + 8);
                }
            // Which voxels are inside, once: the cells and the edges below only read these bits.
            int insideCount = 0;
            for (int p = 0; p < kPad * kPad * kPad; ++p) {
                in[p] = value[p] > iso ? 1 : 0;
                insideCount += in[p];
            }
            if (insideCount == 0 || insideCount == kPad * kPad * kPad)
                continue; // nothing crosses in or next to this leaf
            w.clear();
            w.cells.assign(kCells * kCells * kCells, kNone);
            for (int ci = 0; ci < kCells; ++ci)
                for (int cj = 0; cj < kCells; ++cj) {
                    // A row of cells along z whose corners (four rows of 10 flags) are all
                    // inside or all outside holds no vertex.
                    std::uint64_t any = 0, all = ~std::uint64_t{0};
                    std::uint16_t anyTail = 0, allTail = 0xFFFF;
                    for (int d = 0; d < 4; ++d) {
                        const int row = padOffset(ci + kMargin - 1 + (d & 1),
                                                  cj + kMargin - 1 + (d >> 1), kMargin - 1);
                        std::uint64_t head;
                        std::uint16_t tail;
                        std::memcpy(&head, &in[row], 8);
                        std::memcpy(&tail, &in[row + 8], 2);
                        any |= head, all &= head;
                        anyTail |= tail, allTail &= tail;
                    }
                    // Flags of the row's ten z positions (one per byte, 0 or 1); cell ck has
                    // its corners at positions ck and ck + 1: it is mixed when some corner is
                    // inside and not all are. Only the mixed cells are visited.
                    const unsigned __int128 anyRow = any | static_cast<unsigned __int128>(anyTail)
                                                               << 64;
                    const unsigned __int128 allRow = all | static_cast<unsigned __int128>(allTail)
                                                               << 64;
                    const unsigned __int128 nineCells =
                        (static_cast<unsigned __int128>(0x01) << 64) | 0x0101010101010101ull;
                    unsigned __int128 mixed =
                        (anyRow | anyRow >> 8) & ~(allRow & allRow >> 8) & nineCells;
                    while (mixed != 0) {
                        const std::uint64_t low = static_cast<std::uint64_t>(mixed);
                        const int ck = low != 0 ? std::countr_zero(low) / 8 : 8;
                        mixed &= mixed - 1; // one flag bit per byte: the lowest is this cell's
                        const int base =
                            padOffset(ci + kMargin - 1, cj + kMargin - 1, ck + kMargin - 1);
                        int inside = 0;
                        for (int c = 0; c < 8; ++c)
                            inside |= in[base + kCornerOffset[c]] << c;
                        float f[8];
                        for (int c = 0; c < 8; ++c)
                            f[c] = value[base + kCornerOffset[c]];
                        int first = -1;
                        for (int c = 0; c < 8 && first < 0; ++c)
                            if (stored[base + kCornerOffset[c]])
                                first = c;
                        if (first < 0)
                            continue;
                        const int q[3] = {ci + kMargin - 1 + kCorner[first][0],
                                          cj + kMargin - 1 + kCorner[first][1],
                                          ck + kMargin - 1 + kCorner[first][2]};
                        const int owner = neighbourIndex(sideOf(q[0]), sideOf(q[1]), sideOf(q[2]));
                        const int cell = cellOffset(ci, cj, ck);
                        if (owner != neighbourIndex(1, 1, 1)) {
                            if (nleaf[owner] < 0)
                                continue;
                            // The owner's cell table starts one voxel below its origin.
                            const int oi = ci - 8 * (sideOf(q[0]) - 1);
                            const int oj = cj - 8 * (sideOf(q[1]) - 1);
                            const int ok = ck - 8 * (sideOf(q[2]) - 1);
                            w.cells[cell] =
                                CellEntry(kOwnedElsewhere - static_cast<int>(w.foreign.size()));
                            w.foreign.push_back(
                                {static_cast<std::uint32_t>(nleaf[owner]), cellOffset(oi, oj, ok)});
                            continue;
                        }
                        // The vertex: mean of the edge crossings, in cell units.
                        float sum[3] = {0.0f, 0.0f, 0.0f};
                        // The crossing edges of this corner pattern, in kEdge's order: each one
                        // adds its first corner off its axis and the crossing's t along it.
                        const CrossingEdges& crossing = kCrossingEdges[inside];
                        for (int q = 0; q < crossing.count; ++q) {
                            const int e = crossing.edge[q];
                            const int a = kEdgeAxis[e];
                            const float fa = f[kEdge[e][0]], fb = f[kEdge[e][1]];
                            const float t = (iso - fa) / (fb - fa);
                            for (int k = 0; k < 3; ++k)
                                sum[k] += k == a ? t : float(kCorner[kEdge[e][0]][k]);
                        }
                        const int crossings = crossing.count;
                        const float t[3] = {sum[0] / float(crossings), sum[1] / float(crossings),
                                            sum[2] / float(crossings)};
                        // Colour and gradient: trilinear over the cell's stored corners; the
                        // gradient at a corner by central differences (one-sided next to a tile,
                        // whose value stands in for the field and is not it).
                        openvdb::Vec3s colorSum(0.0f), gradientSum(0.0f);
                        float weight = 0.0f;
                        // AllStored: every voxel the corners and their differences read is
                        // stored; InLeaf: the corners lie in this leaf.
                        auto corners = [&]<bool AllStored, bool InLeaf>() {
                            const openvdb::Vec3s* leaf = colorData[neighbourIndex(1, 1, 1)];
                            const openvdb::Vec3s* own =
                                InLeaf && leaf ? leaf + leafOffset(ci - 1, cj - 1, ck - 1)
                                               : nullptr;
                            for (int c = 0; c < 8; ++c) {
                                const int p[3] = {ci + kMargin - 1 + kCorner[c][0],
                                                  cj + kMargin - 1 + kCorner[c][1],
                                                  ck + kMargin - 1 + kCorner[c][2]};
                                const int at = padOffset(p[0], p[1], p[2]);
                                if (!AllStored && !stored[at])
                                    continue;
                                float wgt = 1.0f;
                                for (int k = 0; k < 3; ++k)
                                    wgt *= kCorner[c][k] ? t[k] : 1.0f - t[k];
                                if constexpr (InLeaf) {
                                    if (own)
                                        colorSum += wgt * own[kCornerLeafOffset[c]];
                                } else {
                                    const int s =
                                        neighbourIndex(sideOf(p[0]), sideOf(p[1]), sideOf(p[2]));
                                    if (colorData[s])
                                        colorSum +=
                                            wgt * colorData[s][leafOffset(
                                                      localOf(p[0]), localOf(p[1]), localOf(p[2]))];
                                }
                                if (normals) {
                                    // In value per voxel: only the direction is kept (normals).
                                    for (int a = 0; a < 3; ++a) {
                                        const int up = at + kPadStep[a], down = at - kPadStep[a];
                                        const float g = AllStored || (stored[up] && stored[down])
                                                            ? 0.5f * (value[up] - value[down])
                                                        : stored[up]   ? value[up] - value[at]
                                                        : stored[down] ? value[at] - value[down]
                                                                       : 0.0f;
                                        gradientSum[a] += wgt * g;
                                    }
                                }
                                weight += wgt;
                            }
                        };
                        if (!storedAround[aroundCode(ci)][aroundCode(cj)][aroundCode(ck)])
                            corners.template operator()<false, false>();
                        else if (ci >= 1 && ci <= 7 && cj >= 1 && cj <= 7 && ck >= 1 && ck <= 7)
                            corners.template operator()<true, true>();
                        else
                            corners.template operator()<true, false>();
                        const openvdb::Vec3s rgb = weight > 0.0f ? colorSum / weight : background;
                        w.cells[cell] = static_cast<CellEntry>(w.positions.size());
                        w.positions.push_back({(float(origin.x() - 1 + ci) + t[0]) * h,
                                               (float(origin.y() - 1 + cj) + t[1]) * h,
                                               (float(origin.z() - 1 + ck) + t[2]) * h});
                        w.colors.push_back({std::clamp(rgb[0], 0.0f, 1.0f),
                                            std::clamp(rgb[1], 0.0f, 1.0f),
                                            std::clamp(rgb[2], 0.0f, 1.0f)});
                        if (normals)
                            w.gradients.push_back(weight > 0.0f ? Vec3f{gradientSum[0] / weight,
                                                                        gradientSum[1] / weight,
                                                                        gradientSum[2] / weight}
                                                                : Vec3f{0.0f, 0.0f, 0.0f});
                    }
                }
            // Edges from this leaf's voxels towards +axis, a row of 8 along z at a time: the
            // bytes of (row XOR the row one step along the axis) that differ are the edges
            // the surface crosses (most rows have none).
            static_assert(sizeof(in[0]) == 1 && std::endian::native == std::endian::little,
                          "rows of 8 inside flags are read as 64 bits, first flag lowest");
            for (int i = kMargin; i < kMargin + 8; ++i)
                for (int j = kMargin; j < kMargin + 8; ++j) {
                    const int row = padOffset(i, j, kMargin);
                    std::uint64_t here, diff[3];
                    std::memcpy(&here, &in[row], 8);
                    for (int a = 0; a < 3; ++a) {
                        std::uint64_t next;
                        std::memcpy(&next, &in[row + kPadStep[a]], 8);
                        diff[a] = here ^ next;
                    }
                    std::uint64_t any = diff[0] | diff[1] | diff[2];
                    while (any != 0) {
                        const int byte = std::countr_zero(any) / 8;
                        any &= ~(std::uint64_t{0xFF} << (8 * byte));
                        const int k = kMargin + byte;
                        const int v[3] = {i, j, k};
                        const bool inHere = in[row + byte] != 0;
                        for (int a = 0; a < 3; ++a) {
                            if (((diff[a] >> (8 * byte)) & 0xFF) == 0)
                                continue;
                            const int b = (a + 1) % 3, c = (a + 2) % 3;
                            // Cells around the edge, counter-clockwise seen from +a.
                            std::array<CellEntry, 4> quad;
                            const int around[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
                            for (int m = 0; m < 4; ++m) {
                                int cc[3] = {v[0], v[1], v[2]};
                                cc[b] += around[m][0];
                                cc[c] += around[m][1];
                                quad[m] = CellEntry(cellOffset(
                                    cc[0] - kMargin + 1, cc[1] - kMargin + 1, cc[2] - kMargin + 1));
                            }
                            // Outward is from high density to low: +a when this end is inside.
                            if (!inHere)
                                std::swap(quad[1], quad[3]);
                            w.quads.push_back(quad);
                        }
                    }
                }
            work[n].assignExact(w);
        }
    });

    // Global numbering: a prefix sum over the leaves, so the mesh does not depend on threads.
    std::size_t vertices = 0, quads = 0;
    for (auto& w : work) {
        w.vertexBase = static_cast<std::uint32_t>(vertices);
        w.quadBase = quads;
        vertices += w.positions.size();
        quads += w.quads.size();
    }
    // Tens of megabytes that the kernel clears page by page as they are first written: both
    // cores at it.
    std::vector<char> keep;
    tbb::parallel_invoke(
        [&] { mesh.positions.resize(vertices); }, [&] { mesh.colors.resize(vertices); },
        [&] { mesh.normals.resize(normals ? vertices : 0); },
        [&] { mesh.indices.assign(6 * quads, 0); }, [&] { keep.assign(quads, 1); });
    tbb::parallel_for(std::size_t{0}, work.size(), [&](std::size_t n) {
        const LeafWork& w = work[n];
        std::copy(w.positions.begin(), w.positions.end(), mesh.positions.begin() + w.vertexBase);
        std::copy(w.colors.begin(), w.colors.end(), mesh.colors.begin() + w.vertexBase);
        if (normals)
            for (std::size_t v = 0; v < w.gradients.size(); ++v) {
                mesh.normals[w.vertexBase + v] = normalFromGradient(w.gradients[v]);
            }
        auto vertexOf = [&](std::int32_t cell) -> std::int64_t {
            const std::int32_t entry = w.cells[std::size_t(cell)];
            if (entry >= 0)
                return std::int64_t(w.vertexBase) + entry;
            if (entry == kNone)
                return -1;
            const Foreign& f = w.foreign[kOwnedElsewhere - entry];
            const LeafWork& owner = work[f.leaf];
            if (owner.cells.empty() || owner.cells[f.cell] < 0)
                return -1;
            return std::int64_t(owner.vertexBase) + owner.cells[f.cell];
        };
        for (std::size_t q = 0; q < w.quads.size(); ++q) {
            std::int64_t v[4];
            bool whole = true;
            for (int m = 0; m < 4; ++m) {
                v[m] = vertexOf(w.quads[q][m]);
                whole = whole && v[m] >= 0;
            }
            std::uint32_t* out = &mesh.indices[6 * (w.quadBase + q)];
            if (!whole) {
                keep[w.quadBase + q] = 0;
                continue;
            }
            const std::uint32_t a = std::uint32_t(v[0]), b = std::uint32_t(v[1]),
                                c = std::uint32_t(v[2]), d = std::uint32_t(v[3]);
            out[0] = a, out[1] = b, out[2] = c, out[3] = a, out[4] = c, out[5] = d;
        }
    });
    // Quads that lost a corner (only where the plan's tiles were wrong): dropped, not garbled.
    if (std::find(keep.begin(), keep.end(), 0) != keep.end()) {
        std::size_t to = 0;
        for (std::size_t q = 0; q < quads; ++q)
            if (keep[q]) {
                std::copy_n(&mesh.indices[6 * q], 6, &mesh.indices[6 * to]);
                ++to;
            }
        mesh.indices.resize(6 * to);
    }
    // Thousands of small lists, freed by both cores.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 256), [&](const auto& r) {
        for (std::size_t n = r.begin(); n != r.end(); ++n)
            work[n] = LeafWork{};
    });
}

} // namespace faultline::core::detail
