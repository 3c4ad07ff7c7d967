// What the VTK legacy and XML readers share: VTK scalar types and their packed encodings, and
// the mapping of point arrays to a Frame (radius, ids, attribute columns named name_x/_y/_z).
#pragma once

#include "core/io/input_error.hpp"
#include "core/model/frame.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core::detail {

enum class VtkScalar {
    Bit,
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float32,
    Float64
};

// Bytes of one value (Bit: 0, see vtkPackedBytes).
std::size_t vtkScalarBytes(VtkScalar type);
bool vtkScalarIsIntegral(VtkScalar type);
// Bytes that `count` packed values take (bits are packed 8 to a byte).
std::uint64_t vtkPackedBytes(VtkScalar type, std::uint64_t count);

// Legacy names (float, double, int, unsigned_char, vtktypeint64, ...), case-insensitive.
std::optional<VtkScalar> vtkLegacyScalar(std::string_view name);
// XML names (Float32, Int64, UInt8, ...).
std::optional<VtkScalar> vtkXmlScalar(std::string_view name);

// Converts `count` packed values at `bytes` (which must hold vtkPackedBytes(type, count)).
void unpackVtkValues(const unsigned char* bytes, std::size_t count, VtkScalar type, bool bigEndian,
                     double* out);

// The index of the first value that is not finite once stored as float32, or `count`.
std::size_t firstNonFiniteAsFloat(const double* values, std::size_t count);

// One point array as read from the file, with where it was declared (for error messages).
struct VtkPointArray {
    std::string name;
    std::size_t components = 1;
    bool integralType = false;  // declared with an integer VTK type
    std::vector<double> values; // tuple-major: values[tuple * components + component]
    InputError::Where where = InputError::Where::File;
    std::uint64_t position = 0;
};

// Most components an array may have, and most attribute columns a frame may get (bounds
// against hostile headers: with zero points, arrays cost nothing else to declare).
inline constexpr std::size_t kMaxVtkComponents = 256;
inline constexpr std::size_t kMaxVtkColumns = 4096;

// Builds the frame: `points` holds x y z per point (already checked finite as float). Arrays
// named radius/radii/rad (or diameter) give the radius, id/ids/particle_id the ids; every
// other array becomes attribute columns: `name` (1 component), name_x/_y/_z (3 components)
// or name_0..name_{n-1}. Throws InputError on a bad radius or id, or a repeated column name.
Frame buildVtkFrame(const std::string& path, const std::vector<double>& points,
                    std::vector<VtkPointArray>& arrays);

} // namespace faultline::core::detail
