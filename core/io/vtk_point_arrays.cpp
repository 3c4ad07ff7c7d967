#include "core/io/vtk_point_arrays.hpp"

#include "core/util/ascii.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <unordered_set>

namespace faultline::core::detail {

namespace {

template <typename T>
void unpackAs(const unsigned char* p, std::size_t count, bool bigEndian, double* out) {
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    unsigned char buf[sizeof(T)];
    for (std::size_t i = 0; i < count; ++i, p += sizeof(T)) {
        if (swap)
            for (std::size_t b = 0; b < sizeof(T); ++b)
                buf[b] = p[sizeof(T) - 1 - b];
        else
            std::memcpy(buf, p, sizeof(T));
        T v;
        std::memcpy(&v, buf, sizeof(T));
        out[i] = static_cast<double>(v);
    }
}

bool isRadiusName(const std::string& n) { return n == "radius" || n == "radii" || n == "rad"; }
bool isDiameterName(const std::string& n) { return n == "diameter" || n == "diam"; }
bool isIdName(const std::string& n) {
    return n == "id" || n == "ids" || n == "particle_id" || n == "particleid";
}

bool allIntegral(const std::vector<double>& v) {
    for (double d : v)
        if (!(d == std::trunc(d) && std::fabs(d) <= 9.0e18))
            return false;
    return true;
}

[[noreturn]] void failAt(const std::string& path, const VtkPointArray& a, const std::string& msg) {
    throw InputError(path, a.where, a.position, msg);
}

} // namespace

std::size_t vtkScalarBytes(VtkScalar type) {
    switch (type) {
    case VtkScalar::Bit:
        return 0;
    case VtkScalar::Int8:
    case VtkScalar::UInt8:
        return 1;
    case VtkScalar::Int16:
    case VtkScalar::UInt16:
        return 2;
    case VtkScalar::Int32:
    case VtkScalar::UInt32:
    case VtkScalar::Float32:
        return 4;
    case VtkScalar::Int64:
    case VtkScalar::UInt64:
    case VtkScalar::Float64:
        return 8;
    }
    return 0;
}

bool vtkScalarIsIntegral(VtkScalar type) {
    return type != VtkScalar::Float32 && type != VtkScalar::Float64;
}

std::uint64_t vtkPackedBytes(VtkScalar type, std::uint64_t count) {
    if (type == VtkScalar::Bit)
        return count / 8 + (count % 8 != 0);
    return count * vtkScalarBytes(type); // callers bound count far below overflow
}

std::optional<VtkScalar> vtkLegacyScalar(std::string_view name) {
    const std::string n = asciiLower(name);
    if (n == "float" || n == "vtktypefloat32")
        return VtkScalar::Float32;
    if (n == "double" || n == "vtktypefloat64")
        return VtkScalar::Float64;
    if (n == "int" || n == "vtktypeint32" || n == "vtkidtype") // VTK writes vtkIdType as int
        return VtkScalar::Int32;
    if (n == "unsigned_int" || n == "vtktypeuint32")
        return VtkScalar::UInt32;
    if (n == "short" || n == "vtktypeint16")
        return VtkScalar::Int16;
    if (n == "unsigned_short" || n == "vtktypeuint16")
        return VtkScalar::UInt16;
    if (n == "char" || n == "signed_char" || n == "vtktypeint8")
        return VtkScalar::Int8;
    if (n == "unsigned_char" || n == "vtktypeuint8")
        return VtkScalar::UInt8;
    if (n == "long" || n == "vtktypeint64" || n == "long_long")
        return VtkScalar::Int64;
    if (n == "unsigned_long" || n == "vtktypeuint64" || n == "unsigned_long_long")
        return VtkScalar::UInt64;
    if (n == "bit")
        return VtkScalar::Bit;
    return std::nullopt;
}

std::optional<VtkScalar> vtkXmlScalar(std::string_view n) {
    static const std::pair<std::string_view, VtkScalar> kNames[] = {
        {"Float32", VtkScalar::Float32}, {"Float64", VtkScalar::Float64},
        {"Int8", VtkScalar::Int8},       {"UInt8", VtkScalar::UInt8},
        {"Int16", VtkScalar::Int16},     {"UInt16", VtkScalar::UInt16},
        {"Int32", VtkScalar::Int32},     {"UInt32", VtkScalar::UInt32},
        {"Int64", VtkScalar::Int64},     {"UInt64", VtkScalar::UInt64},
        {"Bit", VtkScalar::Bit}};
    for (const auto& [name, type] : kNames)
        if (n == name)
            return type;
    return std::nullopt;
}

void unpackVtkValues(const unsigned char* bytes, std::size_t count, VtkScalar type, bool bigEndian,
                     double* out) {
    switch (type) {
    case VtkScalar::Bit:
        for (std::size_t i = 0; i < count; ++i)
            out[i] = (bytes[i / 8] >> (7 - i % 8)) & 1; // most significant bit first
        return;
    case VtkScalar::Int8:
        return unpackAs<std::int8_t>(bytes, count, bigEndian, out);
    case VtkScalar::UInt8:
        return unpackAs<std::uint8_t>(bytes, count, bigEndian, out);
    case VtkScalar::Int16:
        return unpackAs<std::int16_t>(bytes, count, bigEndian, out);
    case VtkScalar::UInt16:
        return unpackAs<std::uint16_t>(bytes, count, bigEndian, out);
    case VtkScalar::Int32:
        return unpackAs<std::int32_t>(bytes, count, bigEndian, out);
    case VtkScalar::UInt32:
        return unpackAs<std::uint32_t>(bytes, count, bigEndian, out);
    case VtkScalar::Int64:
        return unpackAs<std::int64_t>(bytes, count, bigEndian, out);
    case VtkScalar::UInt64:
        return unpackAs<std::uint64_t>(bytes, count, bigEndian, out);
    case VtkScalar::Float32:
        return unpackAs<float>(bytes, count, bigEndian, out);
    case VtkScalar::Float64:
        return unpackAs<double>(bytes, count, bigEndian, out);
    }
}

std::size_t firstNonFiniteAsFloat(const double* values, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i)
        if (!std::isfinite(static_cast<float>(values[i])))
            return i;
    return count;
}

Frame buildVtkFrame(const std::string& path, const std::vector<double>& points,
                    std::vector<VtkPointArray>& arrays) {
    const std::size_t n = points.size() / 3;
    Frame frame;
    frame.x.resize(n);
    frame.y.resize(n);
    frame.z.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        frame.x[i] = static_cast<float>(points[3 * i]);
        frame.y[i] = static_cast<float>(points[3 * i + 1]);
        frame.z[i] = static_cast<float>(points[3 * i + 2]);
    }

    const VtkPointArray* idArray = nullptr;
    bool haveRadius = false;
    std::unordered_set<std::string> names; // attribute column names, to refuse repeats
    for (VtkPointArray& a : arrays) {
        if (a.values.size() != n * a.components)
            failAt(path, a,
                   "array '" + a.name + "' has " + std::to_string(a.values.size()) +
                       " values, expected " + std::to_string(n * a.components));
        const std::string key = asciiLower(a.name);
        if (a.components == 1 && !haveRadius && (isRadiusName(key) || isDiameterName(key))) {
            const std::size_t bad = firstNonFiniteAsFloat(a.values.data(), n);
            if (bad < n)
                failAt(path, a,
                       "radius array '" + a.name + "': value " + std::to_string(bad + 1) +
                           " is not a finite number (" + std::to_string(a.values[bad]) + ")");
            const double scale = isDiameterName(key) ? 0.5 : 1.0;
            frame.radius.resize(n);
            for (std::size_t i = 0; i < n; ++i)
                frame.radius[i] = static_cast<float>(a.values[i] * scale);
            haveRadius = true;
            continue;
        }
        if (a.components == 1 && !idArray && isIdName(key) && allIntegral(a.values)) {
            frame.ids.resize(n);
            for (std::size_t i = 0; i < n; ++i)
                frame.ids[i] = static_cast<std::int64_t>(a.values[i]);
            idArray = &a;
            continue;
        }
        static const char* kAxes[] = {"_x", "_y", "_z"};
        for (std::size_t c = 0; c < a.components; ++c) {
            std::string name = a.components == 1   ? a.name
                               : a.components == 3 ? a.name + kAxes[c]
                                                   : a.name + "_" + std::to_string(c);
            if (!names.insert(name).second)
                failAt(path, a, "column '" + name + "' appears twice");
            if (names.size() > kMaxVtkColumns)
                failAt(path, a,
                       "more than " + std::to_string(kMaxVtkColumns) + " attribute columns");
            std::vector<float> column(n);
            for (std::size_t i = 0; i < n; ++i)
                column[i] = static_cast<float>(a.values[i * a.components + c]);
            frame.attributes.push_back(
                makeAttribute(std::move(name), std::move(column), a.integralType));
        }
        std::vector<double>().swap(a.values); // release as we go
    }
    if (!idArray) {
        frame.idsAreRowNumbers = true;
        frame.ids.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            frame.ids[i] = static_cast<std::int64_t>(i);
    }
    if (!haveRadius) {
        frame.radiusIsDefault = true;
        frame.radius.assign(n, kDefaultRadius);
    }
    try {
        frame.finalize();
    } catch (const std::invalid_argument& e) {
        if (idArray)
            throw InputError(path, idArray->where, idArray->position,
                             "array '" + idArray->name + "': " + e.what());
        throw InputError(path, e.what());
    }
    return frame;
}

} // namespace faultline::core::detail
