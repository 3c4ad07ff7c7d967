#include "core/io/vtk_xml.hpp"

#include "core/io/input_error.hpp"
#include "core/io/vtk_point_arrays.hpp"
#include "core/io/vtk_xml_payload.hpp"
#include "core/io/xml_tokens.hpp"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace faultline::core {

using detail::VtkPointArray;
using detail::VtkScalar;
using detail::XmlArraySource;
using detail::XmlEncoding;

namespace {

constexpr std::uint64_t kMaxPoints = 0xFFFFFFFEull; // Frame rows are addressed by uint32

// A DataArray of a Piece's Points or PointData, as declared.
struct ArraySpec {
    XmlArraySource source;
    std::uint64_t components = 1;
    std::optional<std::uint64_t> tuples; // NumberOfTuples, when given
    bool skip = false;                   // a String array: not numbers
    std::string joinedText;              // owns the text when it came in several pieces
};

struct PieceSpec {
    std::uint64_t points = 0;
    std::uint64_t line = 0;
    std::vector<ArraySpec> pointsArrays;
    std::vector<ArraySpec> pointData;
};

enum class Context { VTKFile, Dataset, Piece, Points, PointData, DataArray, Other };

std::uint64_t parseCount(const XmlTokenizer& t, const char* attr, std::uint64_t max,
                         std::optional<std::uint64_t> fallback = std::nullopt) {
    const std::string* v = t.attribute(attr);
    if (!v) {
        if (fallback)
            return *fallback;
        t.fail("<" + std::string(t.name()) + "> has no " + attr + " attribute");
    }
    std::uint64_t n = 0;
    std::string_view s = *v;
    while (!s.empty() && s.front() == ' ')
        s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ')
        s.remove_suffix(1);
    auto r = std::from_chars(s.data(), s.data() + s.size(), n);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || s.empty())
        t.fail(std::string(attr) + ": expected a non-negative integer, found " + quoteForError(*v));
    if (n > max)
        t.fail(std::string(attr) + "=\"" + *v + "\" is more than the " + std::to_string(max) +
               " this reader accepts");
    return n;
}

struct Scan {
    XmlEncoding encoding;
    std::string datasetType;
    std::vector<PieceSpec> pieces;
};

void readVtkFileAttributes(const XmlTokenizer& t, Scan& scan) {
    const std::string* type = t.attribute("type");
    if (!type)
        t.fail("<VTKFile> has no type attribute");
    if (*type != "UnstructuredGrid" && *type != "PolyData")
        t.fail("VTKFile type '" + *type +
               "' is not supported: expected UnstructuredGrid or PolyData (particles as points)");
    scan.datasetType = *type;
    if (const std::string* order = t.attribute("byte_order")) {
        if (*order != "LittleEndian" && *order != "BigEndian")
            t.fail("byte_order: expected LittleEndian or BigEndian, found " +
                   quoteForError(*order));
        scan.encoding.bigEndian = *order == "BigEndian";
    }
    if (const std::string* header = t.attribute("header_type")) {
        if (*header != "UInt32" && *header != "UInt64")
            t.fail("header_type: expected UInt32 or UInt64, found " + quoteForError(*header));
        scan.encoding.headerBytes = *header == "UInt64" ? 8 : 4;
    }
    if (const std::string* c = t.attribute("compressor"); c && !c->empty()) {
        using C = XmlEncoding::Compressor;
        if (*c == "vtkZLibDataCompressor")
            scan.encoding.compressor = C::ZLib;
        else if (*c == "vtkLZ4DataCompressor")
            scan.encoding.compressor = C::LZ4;
        else if (*c == "vtkLZMADataCompressor")
            scan.encoding.compressor = C::LZMA;
        else
            t.fail("compressor " + quoteForError(*c) +
                   " is not supported: expected vtkZLibDataCompressor, vtkLZ4DataCompressor or "
                   "vtkLZMADataCompressor (or none)");
    }
}

ArraySpec readDataArrayTag(const XmlTokenizer& t, std::size_t index) {
    ArraySpec a;
    XmlArraySource& s = a.source;
    s.tagLine = t.line();
    const std::string* name = t.attribute("Name");
    s.name = name && !name->empty() ? *name : "array" + std::to_string(index);
    const std::string* type = t.attribute("type");
    if (!type)
        t.fail("DataArray '" + s.name + "' has no type attribute");
    if (*type == "String") {
        a.skip = true;
        return a;
    }
    auto scalar = detail::vtkXmlScalar(*type);
    if (!scalar)
        t.fail("DataArray '" + s.name + "': type " + quoteForError(*type) +
               " is not supported: expected Float32, Float64, Int8..Int64 or UInt8..UInt64");
    s.type = *scalar;
    a.components = parseCount(t, "NumberOfComponents", detail::kMaxVtkComponents, 1);
    if (a.components == 0)
        t.fail("DataArray '" + s.name + "': NumberOfComponents must be at least 1");
    if (t.attribute("NumberOfTuples"))
        a.tuples = parseCount(t, "NumberOfTuples", kMaxPoints);
    const std::string* format = t.attribute("format");
    if (!format)
        t.fail("DataArray '" + s.name + "' has no format attribute (ascii, binary or appended)");
    if (*format == "ascii") {
        s.format = XmlArraySource::Format::Ascii;
    } else if (*format == "binary") {
        s.format = XmlArraySource::Format::Binary;
    } else if (*format == "appended") {
        s.format = XmlArraySource::Format::Appended;
        s.appendedOffset = parseCount(t, "offset", ~0ull);
    } else {
        t.fail("DataArray '" + s.name + "': format " + quoteForError(*format) +
               " is not one of ascii, binary, appended");
    }
    return a;
}

// Reads the structure: pieces, their arrays and where their data lie. Stops at <AppendedData>.
Scan scanStructure(const std::string& path, std::string_view bytes) {
    Scan scan;
    XmlTokenizer t(path, bytes);
    std::vector<Context> stack;
    ArraySpec* current = nullptr;
    std::vector<std::pair<std::string_view, std::pair<std::size_t, std::uint64_t>>> segments;
    for (;;) {
        const XmlTokenizer::Kind kind = t.next();
        if (kind == XmlTokenizer::Kind::End)
            break;
        if (kind == XmlTokenizer::Kind::Text) {
            if (current && stack.size() == 5 && stack.back() == Context::DataArray)
                segments.push_back({t.text(), {t.offset(), t.line()}});
            continue;
        }
        if (kind == XmlTokenizer::Kind::EndTag) {
            if (stack.back() == Context::DataArray && current) {
                // Keep the content: one piece of text as it is, several (around a child
                // element such as <InformationKey>) joined.
                if (!segments.empty()) {
                    current->source.text = segments.front().first;
                    current->source.textOffset = segments.front().second.first;
                    current->source.textLine = segments.front().second.second;
                }
                if (segments.size() > 1) {
                    for (const auto& seg : segments)
                        current->joinedText += seg.first;
                    current->source.text = current->joinedText;
                }
                current = nullptr;
                segments.clear();
            }
            stack.pop_back();
            continue;
        }
        // A start or empty tag.
        const Context parent = stack.empty() ? Context::Other : stack.back();
        Context ctx = Context::Other;
        const std::string_view name = t.name();
        if (stack.empty()) {
            if (name != "VTKFile")
                t.fail("expected <VTKFile> as the root element, found <" + std::string(name) + ">");
            readVtkFileAttributes(t, scan);
            ctx = Context::VTKFile;
        } else if (parent == Context::VTKFile && name == "AppendedData") {
            const std::string* enc = t.attribute("encoding");
            if (!enc || (*enc != "raw" && *enc != "base64"))
                t.fail("<AppendedData>: expected encoding=\"raw\" or encoding=\"base64\"");
            scan.encoding.haveAppended = true;
            scan.encoding.appendedBase64 = *enc == "base64";
            if (kind == XmlTokenizer::Kind::StartTag) {
                std::size_t p = t.position();
                while (p < bytes.size() && (bytes[p] == ' ' || bytes[p] == '\t' ||
                                            bytes[p] == '\n' || bytes[p] == '\r'))
                    ++p;
                if (p >= bytes.size() || bytes[p] != '_')
                    t.fail("<AppendedData>: expected the '_' marker before the data");
                scan.encoding.appended = bytes.substr(p + 1);
                scan.encoding.appendedOffset = p + 1;
            }
            return scan; // VTK puts the appended data last; what follows is binary
        } else if (parent == Context::VTKFile && name == scan.datasetType) {
            ctx = Context::Dataset;
        } else if (parent == Context::Dataset && name == "Piece") {
            PieceSpec piece;
            piece.line = t.line();
            piece.points = parseCount(t, "NumberOfPoints", kMaxPoints);
            scan.pieces.push_back(std::move(piece));
            ctx = Context::Piece;
        } else if (parent == Context::Piece && name == "Points") {
            ctx = Context::Points;
        } else if (parent == Context::Piece && name == "PointData") {
            ctx = Context::PointData;
        } else if ((parent == Context::Points || parent == Context::PointData) &&
                   name == "DataArray") {
            PieceSpec& piece = scan.pieces.back();
            auto& list = parent == Context::Points ? piece.pointsArrays : piece.pointData;
            list.push_back(readDataArrayTag(t, list.size()));
            ctx = Context::DataArray;
            current = &list.back();
            segments.clear();
        }
        if (kind == XmlTokenizer::Kind::StartTag)
            stack.push_back(ctx);
        else
            current = nullptr; // an empty DataArray has no content
    }
    if (scan.datasetType.empty())
        throw InputError(path, "no <VTKFile> element");
    return scan;
}

// The values of one array of one piece.
std::vector<double> decode(const std::string& path, const Scan& scan, const PieceSpec& piece,
                           const ArraySpec& a, bool requireFinite) {
    if (a.tuples && *a.tuples != piece.points)
        throw InputError(path, InputError::Where::Line, a.source.tagLine,
                         "DataArray '" + a.source.name +
                             "': NumberOfTuples=" + std::to_string(*a.tuples) +
                             " but the Piece (line " + std::to_string(piece.line) + ") has " +
                             std::to_string(piece.points) + " points");
    std::vector<double> values;
    detail::decodeXmlArray(path, scan.encoding, a.source, piece.points * a.components,
                           requireFinite, values);
    return values;
}

} // namespace

bool looksLikeVtkXml(std::string_view head) {
    const std::size_t at = head.find("<VTKFile");
    if (at == std::string_view::npos)
        return false;
    const std::size_t end = head.find('>', at);
    const std::string_view tag =
        head.substr(at, end == std::string_view::npos ? head.size() - at : end - at);
    // Any VTKFile but a collection: parseVtkXml names the types it cannot read.
    return tag.find("\"Collection\"") == std::string_view::npos &&
           tag.find("'Collection'") == std::string_view::npos;
}

bool looksLikeVtkCollection(std::string_view head) {
    const std::size_t at = head.find("<VTKFile");
    if (at == std::string_view::npos)
        return false;
    return !looksLikeVtkXml(head);
}

Frame parseVtkXml(const std::string& path, std::string_view bytes) {
    const Scan scan = scanStructure(path, bytes);
    if (scan.pieces.empty())
        throw InputError(path, "no <Piece> inside <" + scan.datasetType + ">");

    std::vector<double> points;
    std::vector<VtkPointArray> arrays;
    std::unordered_map<std::string, std::size_t> arrayIndex; // name -> position in arrays
    std::uint64_t total = 0;
    for (std::size_t p = 0; p < scan.pieces.size(); ++p) {
        const PieceSpec& piece = scan.pieces[p];
        total += piece.points;
        if (total > kMaxPoints)
            throw InputError(path, InputError::Where::Line, piece.line,
                             "the pieces hold more than the 4 billion points a frame can hold");
        if (piece.pointsArrays.size() > 1)
            throw InputError(path, InputError::Where::Line, piece.pointsArrays[1].source.tagLine,
                             "<Points> holds more than one DataArray");
        if (piece.pointsArrays.empty()) {
            if (piece.points > 0)
                throw InputError(path, InputError::Where::Line, piece.line,
                                 "Piece with " + std::to_string(piece.points) +
                                     " points has no <Points> DataArray");
        } else {
            const ArraySpec& pa = piece.pointsArrays.front();
            if (pa.skip || pa.components != 3)
                throw InputError(path, InputError::Where::Line, pa.source.tagLine,
                                 "the <Points> DataArray must have 3 numeric components, found " +
                                     std::to_string(pa.components));
            std::vector<double> v = decode(path, scan, piece, pa, true);
            if (points.empty())
                points = std::move(v);
            else
                points.insert(points.end(), v.begin(), v.end());
        }

        // Point arrays: the first piece names them; every other piece must hold the same.
        std::size_t matched = 0;
        for (const ArraySpec& a : piece.pointData) {
            if (a.skip)
                continue;
            const auto found = arrayIndex.find(a.source.name);
            VtkPointArray* target = found == arrayIndex.end() ? nullptr : &arrays[found->second];
            if (p == 0) {
                if (target)
                    throw InputError(path, InputError::Where::Line, a.source.tagLine,
                                     "PointData array '" + a.source.name + "' appears twice");
                if (arrays.size() >= detail::kMaxVtkColumns)
                    throw InputError(path, InputError::Where::Line, a.source.tagLine,
                                     "more than " + std::to_string(detail::kMaxVtkColumns) +
                                         " PointData arrays");
                arrayIndex.emplace(a.source.name, arrays.size());
                VtkPointArray fresh;
                fresh.name = a.source.name;
                fresh.components = a.components;
                fresh.integralType = detail::vtkScalarIsIntegral(a.source.type);
                fresh.where = InputError::Where::Line;
                fresh.position = a.source.tagLine;
                arrays.push_back(std::move(fresh));
                target = &arrays.back();
            } else if (!target || target->components != a.components) {
                throw InputError(path, InputError::Where::Line, a.source.tagLine,
                                 "Piece " + std::to_string(p + 1) + ": PointData array '" +
                                     a.source.name +
                                     "' does not match the arrays of the first Piece");
            }
            ++matched;
            std::vector<double> v = decode(path, scan, piece, a, false);
            if (target->values.empty())
                target->values = std::move(v);
            else
                target->values.insert(target->values.end(), v.begin(), v.end());
            target->integralType =
                target->integralType && detail::vtkScalarIsIntegral(a.source.type);
        }
        if (matched != arrays.size())
            throw InputError(path, InputError::Where::Line, piece.line,
                             "Piece " + std::to_string(p + 1) + " has " + std::to_string(matched) +
                                 " PointData arrays, the first Piece has " +
                                 std::to_string(arrays.size()));
    }
    return detail::buildVtkFrame(path, points, arrays);
}

std::vector<CollectionEntry> parseVtkCollection(const std::string& path, std::string_view bytes) {
    XmlTokenizer t(path, bytes);
    std::vector<CollectionEntry> entries;
    std::vector<std::string_view> stack;
    for (;;) {
        const XmlTokenizer::Kind kind = t.next();
        if (kind == XmlTokenizer::Kind::End)
            break;
        if (kind == XmlTokenizer::Kind::EndTag) {
            stack.pop_back();
            continue;
        }
        if (kind == XmlTokenizer::Kind::Text)
            continue;
        const std::string_view name = t.name();
        if (stack.empty()) {
            const std::string* type = t.attribute("type");
            if (name != "VTKFile" || !type || *type != "Collection")
                t.fail("expected <VTKFile type=\"Collection\"> as the root element");
        } else if (stack.size() == 2 && stack[1] == "Collection" && name == "DataSet") {
            const std::string* file = t.attribute("file");
            if (!file || file->empty())
                t.fail("<DataSet> has no file attribute");
            const std::string* time = t.attribute("timestep");
            if (!time)
                t.fail("<DataSet file=\"" + *file + "\"> has no timestep attribute");
            std::string_view s = *time;
            while (!s.empty() && s.front() == ' ')
                s.remove_prefix(1);
            while (!s.empty() && s.back() == ' ')
                s.remove_suffix(1);
            if (!s.empty() && s.front() == '+')
                s.remove_prefix(1);
            double v = 0;
            auto r = fast_float::from_chars(s.data(), s.data() + s.size(), v);
            if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() ||
                !std::isfinite(v))
                t.fail("timestep: expected a finite number, found " + quoteForError(*time));
            entries.push_back({v, *file});
        }
        if (kind == XmlTokenizer::Kind::StartTag)
            stack.push_back(name);
    }
    std::stable_sort(
        entries.begin(), entries.end(),
        [](const CollectionEntry& a, const CollectionEntry& b) { return a.time < b.time; });
    return entries;
}

} // namespace faultline::core
