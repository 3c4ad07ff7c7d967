// Frame: one timestep of a DEM model as columns (structure of arrays).
// Particle ids are the identity across frames; rowOf() maps an id to its row in this frame.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core {

enum class ColumnType { Float32, Int32 };

// A named per-particle variable. Exactly one of floats/ints holds the values, by type.
struct AttributeColumn {
    std::string name;
    ColumnType type = ColumnType::Float32;
    std::vector<float> floats;
    std::vector<std::int32_t> ints;
    double min = 0.0; // cached by Frame::finalize(); NaN values are ignored
    double max = 0.0;

    std::size_t size() const { return type == ColumnType::Float32 ? floats.size() : ints.size(); }
    double value(std::size_t row) const {
        return type == ColumnType::Float32 ? static_cast<double>(floats[row])
                                           : static_cast<double>(ints[row]);
    }
    bool isInteger() const { return type == ColumnType::Int32; }
    // A float column without one finite value (incremental strain on a frame before its
    // reference: every value NaN). Only a cached range of [0, 0], which such a column has,
    // leads to a scan; mayHaveNoValue is the test before it.
    bool hasNoValue() const;
    bool mayHaveNoValue() const {
        return !isInteger() && !floats.empty() && min == 0.0 && max == 0.0 &&
               !std::isfinite(floats.front());
    }
};

// The simulation box: orthogonal [lo, hi], or a LAMMPS triclinic box with tilts xy xz yz.
struct SimulationBox {
    std::array<double, 3> lo{0, 0, 0};
    std::array<double, 3> hi{0, 0, 0};
    bool triclinic = false;
    double xy = 0, xz = 0, yz = 0;
    std::array<bool, 3> periodic{false, false, false};
    bool known = false; // false when the file gives no box (the bounds of the spheres are used)
};

class Frame {
  public:
    std::int64_t timestep = 0;
    std::vector<std::int64_t> ids;
    std::vector<float> x, y, z;
    std::vector<float> radius;
    bool radiusIsDefault = false;  // the file had no radius or diameter column
    bool idsAreRowNumbers = false; // the file had no id column
    // The file named no columns and the reader assumed them (an old-style LAMMPS dump read as
    // LAMMPS' atom style: id type xs ys zs, then ix iy iz).
    bool columnsAssumed = false;
    SimulationBox box;
    std::vector<AttributeColumn> attributes;
    // The last `derivedColumns` attributes were derived (strain from motion), not read: the
    // dataset strips them before deriving again (core/data/dataset.hpp).
    std::size_t derivedColumns = 0;
    // Which strain list derived them, as a hash of the list and this frame's references; 0: none.
    // Frames whose derived columns hold other values differ in it (surface colours' cache keys).
    std::uint64_t derivation = 0;

    std::size_t size() const { return ids.size(); }

    const AttributeColumn* attribute(std::string_view name) const;
    AttributeColumn* attribute(std::string_view name);
    std::vector<std::string> attributeNames() const;

    // Must be called once all columns are filled: checks sizes, caches min/max, builds the
    // id -> row map, and computes the box from the spheres when the file gave none.
    // Throws std::invalid_argument when column sizes disagree or ids repeat.
    void finalize();

    std::optional<std::size_t> rowOf(std::int64_t id) const;
    // rowOf for many ids at once: out[k] is the row of wanted[k], or ~0u when this frame lacks
    // it. (A loop over the id map without a call per id: strain from motion maps every sphere.)
    void rowsOf(std::span<const std::int64_t> wanted, std::uint32_t* out) const;

    // Bounds of the sphere centres (not radii). Valid after finalize().
    const std::array<float, 3>& centreMin() const { return m_centreMin; }
    const std::array<float, 3>& centreMax() const { return m_centreMax; }
    // Mean of the finite positive radii (0 when none). Valid after finalize().
    double meanRadius() const { return m_meanRadius; }
    // Lowest and highest finite radius (low above high when there is none). After finalize().
    const std::array<double, 2>& radiusRange() const { return m_radiusRange; }

    // Heap bytes held by this frame (columns and the id map).
    std::size_t memoryBytes() const;

  private:
    // Dense ids (the common case): m_rowById[id - m_idBase]; sparse ids: rows sorted by id.
    std::int64_t m_idBase = 0;
    std::vector<std::uint32_t> m_rowById;        // dense map, kNoRow where absent
    std::vector<std::uint32_t> m_rowsSortedById; // sparse map
    std::array<float, 3> m_centreMin{0, 0, 0};
    std::array<float, 3> m_centreMax{0, 0, 0};
    double m_meanRadius = 0;
    std::array<double, 2> m_radiusRange{1, 0};
};

inline constexpr float kDefaultRadius = 0.5f;

// A column from parsed values: stored as Int32 when `integral` and every value fits exactly,
// else as Float32.
AttributeColumn makeAttribute(std::string name, std::vector<float>&& values, bool integral);

// Whether a text column whose tokens were all plain integers is an integer variable. Text does
// not say: "%g" prints a float column of zeros (strain before anything moves) as "0". So it
// takes a name known to count things (type, mol, ix, broken_bonds, layer, ...) or at least two
// distinct values; a constant column of another name stays float.
bool looksLikeIntegerColumn(std::string_view name, const std::vector<float>& values);

} // namespace faultline::core
