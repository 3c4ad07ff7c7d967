// Decodes the values of one VTK XML DataArray: ascii text, inline base64, or appended data
// (raw or base64), optionally in zlib blocks. Never allocates more than the data present holds.
#pragma once

#include "core/io/vtk_point_arrays.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace faultline::core::detail {

// How the file encodes binary data (from <VTKFile> and <AppendedData>).
struct XmlEncoding {
    bool bigEndian = false;
    std::size_t headerBytes = 4; // UInt32 or UInt64 size headers
    // The VTKFile's compressor attribute: vtkZLibDataCompressor, vtkLZ4DataCompressor (raw LZ4
    // blocks) or vtkLZMADataCompressor (an .xz stream per block).
    enum class Compressor { None, ZLib, LZ4, LZMA };
    Compressor compressor = Compressor::None;
    bool haveAppended = false;
    bool appendedBase64 = false;
    std::string_view appended;      // everything after the '_' marker
    std::size_t appendedOffset = 0; // file offset of appended[0]
};

// One DataArray as declared.
struct XmlArraySource {
    enum class Format { Ascii, Binary, Appended };
    std::string name;
    VtkScalar type = VtkScalar::Float32;
    Format format = Format::Ascii;
    std::string_view text;            // inline content
    std::size_t textOffset = 0;       // file offset of text[0]
    std::uint64_t textLine = 0;       // line of text[0]
    std::uint64_t tagLine = 0;        // line of the <DataArray> tag
    std::uint64_t appendedOffset = 0; // its offset attribute
};

// zlib cannot inflate more than about 1032 bytes from one compressed byte.
inline constexpr std::uint64_t kMaxInflateRatio = 1032;

// Decodes exactly `count` values into `out`. With requireFinite every value must be finite
// once stored as float32. Throws InputError naming the line (ascii) or byte offset (binary).
void decodeXmlArray(const std::string& path, const XmlEncoding& encoding,
                    const XmlArraySource& source, std::uint64_t count, bool requireFinite,
                    std::vector<double>& out);

} // namespace faultline::core::detail
