// Index of this file:
// [SECTION] Text helpers
// [SECTION] The reader: whole file
// [SECTION] Positions for errors
// [SECTION] Lines and tokens
// [SECTION] Values
// [SECTION] Sections: preamble, points, cells, fields, attributes
// [SECTION] Entry points

#include "core/io/vtk_legacy.hpp"

#include "core/io/input_error.hpp"
#include "core/io/vtk_point_arrays.hpp"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

namespace faultline::core {

using detail::VtkPointArray;
using detail::VtkScalar;

namespace {

constexpr std::uint64_t kMaxPoints = 0xFFFFFFFEull; // Frame rows are addressed by uint32

//-----------------------------------------------------------------------------
// [SECTION] Text helpers
//-----------------------------------------------------------------------------

std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
    if (s.size() < prefix.size())
        return false;
    for (std::size_t i = 0; i < prefix.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(s[i])) !=
            std::toupper(static_cast<unsigned char>(prefix[i])))
            return false;
    return true;
}

inline bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// Legacy writers encode blanks and other special characters in names as %XX.
std::string decodeName(std::string_view s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() &&
            std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
            out += static_cast<char>(std::stoi(std::string(s.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

//-----------------------------------------------------------------------------
// [SECTION] The reader: whole file
//-----------------------------------------------------------------------------

// One keyword line split into words, and where it starts.
struct HeaderLine {
    std::vector<std::string_view> words;
    std::uint64_t line = 0;
    std::uint64_t offset = 0;
};

class LegacyReader {
  public:
    LegacyReader(const std::string& path, std::string_view bytes) : m_path(path), m_data(bytes) {}

    Frame read() {
        readPreamble();
        HeaderLine h;
        bool havePoints = false;
        enum class Target { Dataset, PointData, CellData } target = Target::Dataset;
        std::uint64_t tuples = 0; // of the current POINT_DATA / CELL_DATA section
        while (nextHeaderLine(h)) {
            const std::string key = upper(h.words[0]);
            if (key == "POINTS") {
                if (havePoints)
                    fail(h, "a second POINTS section");
                readPoints(h);
                havePoints = true;
            } else if (key == "VERTICES" || key == "LINES" || key == "POLYGONS" ||
                       key == "TRIANGLE_STRIPS" || key == "CELLS") {
                skipCells(h);
            } else if (key == "CELL_TYPES") {
                expectWords(h, 2, "CELL_TYPES n");
                skipValues(count(h, 1, "cell count"), VtkScalar::Int32, "CELL_TYPES");
            } else if (key == "POINT_DATA") {
                expectWords(h, 2, "POINT_DATA n");
                if (!havePoints)
                    fail(h, "POINT_DATA before POINTS: expected the POINTS section first");
                tuples = count(h, 1, "point count");
                if (tuples != m_points.size() / 3)
                    fail(h, "POINT_DATA " + std::to_string(tuples) + " does not match POINTS " +
                                std::to_string(m_points.size() / 3));
                target = Target::PointData;
            } else if (key == "CELL_DATA") {
                expectWords(h, 2, "CELL_DATA n");
                tuples = count(h, 1, "cell count");
                target = Target::CellData;
            } else if (key == "FIELD") {
                // Dataset-level fields (TIME, CYCLE) have their own tuple counts: skip them.
                readField(h, target == Target::PointData, target == Target::Dataset ? 0 : tuples);
            } else if (key == "METADATA") {
                skipMetadata();
            } else if (target != Target::Dataset &&
                       readAttribute(h, key, target == Target::PointData, tuples)) {
                // handled
            } else {
                fail(h, "unknown keyword " + quoteForError(h.words[0]) +
                            (std::isdigit(static_cast<unsigned char>(h.words[0][0])) ||
                                     h.words[0][0] == '-'
                                 ? " (more values than the section declared?)"
                                 : "") +
                            ": expected POINTS, VERTICES, LINES, POLYGONS, TRIANGLE_STRIPS, "
                            "CELLS, CELL_TYPES, POINT_DATA, CELL_DATA" +
                            (target == Target::Dataset
                                 ? std::string()
                                 : ", SCALARS, VECTORS, NORMALS, FIELD or another attribute"));
            }
        }
        if (!havePoints)
            throw InputError(m_path, InputError::Where::Line, m_line,
                             "no POINTS section: expected 'POINTS n type' after DATASET");
        return detail::buildVtkFrame(m_path, m_points, m_arrays);
    }

  private:
    //-----------------------------------------------------------------------------
    // [SECTION] Positions for errors
    //-----------------------------------------------------------------------------

    [[noreturn]] void fail(const HeaderLine& h, const std::string& message) const {
        if (m_afterBinary)
            throw InputError(m_path, InputError::Where::Byte, h.offset, message);
        throw InputError(m_path, InputError::Where::Line, h.line, message);
    }
    [[noreturn]] void failHere(std::uint64_t line, const std::string& message) const {
        if (m_binary)
            throw InputError(m_path, InputError::Where::Byte, m_pos, message);
        throw InputError(m_path, InputError::Where::Line, line, message);
    }

    //-----------------------------------------------------------------------------
    // [SECTION] Lines and tokens
    //-----------------------------------------------------------------------------

    // The next raw line (without its end), false at the end of the data.
    bool nextLine(std::string_view& line, std::uint64_t& lineNo, std::uint64_t& offset) {
        if (m_pos >= m_data.size())
            return false;
        const void* nl = std::memchr(m_data.data() + m_pos, '\n', m_data.size() - m_pos);
        const std::size_t end =
            nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - m_data.data())
               : m_data.size();
        line = m_data.substr(m_pos, end - m_pos);
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        lineNo = m_line;
        offset = m_pos;
        m_pos = nl ? end + 1 : end;
        ++m_line;
        return true;
    }

    static std::vector<std::string_view> split(std::string_view line) {
        std::vector<std::string_view> words;
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && isSpace(line[i]))
                ++i;
            std::size_t j = i;
            while (j < line.size() && !isSpace(line[j]))
                ++j;
            if (j > i)
                words.push_back(line.substr(i, j - i));
            i = j;
            if (words.size() > 16) // no keyword line has this many words: binary garbage
                break;
        }
        return words;
    }

    // The next line holding a word (keyword lines); false at the end.
    bool nextHeaderLine(HeaderLine& h) {
        std::string_view line;
        while (nextLine(line, h.line, h.offset)) {
            h.words = split(line);
            if (!h.words.empty())
                return true;
        }
        return false;
    }

    // The next header line starts with `word` (case-insensitive). Only looks, never reads.
    // Right after a header line binary data may follow, and may begin with blank bytes: there
    // a binary file is looked at exactly at the next byte (`mayPrecedeData`).
    bool nextLineStartsWith(std::string_view word, bool mayPrecedeData) const {
        std::size_t p = m_pos;
        if (!(m_binary && mayPrecedeData))
            while (p < m_data.size() && isSpace(m_data[p]))
                ++p;
        return startsWithNoCase(m_data.substr(p), word) &&
               (p + word.size() == m_data.size() || isSpace(m_data[p + word.size()]));
    }

    void expectWords(const HeaderLine& h, std::size_t n, const char* form) const {
        if (h.words.size() != n)
            fail(h, std::string("expected '") + form + "', found " +
                        std::to_string(h.words.size()) + " words");
    }

    std::uint64_t count(const HeaderLine& h, std::size_t index, const char* what) const {
        const std::string_view w = h.words[index];
        std::uint64_t v = 0;
        auto r = std::from_chars(w.data(), w.data() + w.size(), v);
        if (r.ec != std::errc() || r.ptr != w.data() + w.size())
            fail(h, std::string("expected a ") + what + " (a non-negative integer), found " +
                        quoteForError(w));
        if (v > (1ull << 50))
            fail(h, std::string(what) + " " + std::string(w) + " is beyond what any file holds");
        return v;
    }

    VtkScalar scalarType(const HeaderLine& h, std::size_t index) const {
        auto t = detail::vtkLegacyScalar(h.words[index]);
        if (!t) {
            const std::string found = upper(h.words[index]);
            fail(h, "expected a data type (float, double, int, unsigned_char, vtktypeint64, ...), "
                    "found " +
                        quoteForError(h.words[index]) +
                        (found == "STRING" || found == "UTF8_STRING"
                             ? " (string arrays are not supported)"
                             : ""));
        }
        return *t;
    }

    //-----------------------------------------------------------------------------
    // [SECTION] Values
    //-----------------------------------------------------------------------------

    static std::uint64_t product(std::uint64_t a, std::uint64_t b) {
        std::uint64_t r;
        if (__builtin_mul_overflow(a, b, &r) || r > (1ull << 56))
            return 1ull << 56; // beyond any file: the room check then fails
        return r;
    }

    // Refuses counts the rest of the file cannot hold, before anything is allocated.
    void checkRoom(std::uint64_t values, VtkScalar type, const std::string& what,
                   std::uint64_t line) const {
        const std::uint64_t remaining = m_data.size() - m_pos;
        const std::uint64_t needed =
            m_binary ? detail::vtkPackedBytes(type, std::min<std::uint64_t>(values, 1ull << 56))
                     : (values == 0 ? 0 : 2 * values - 1);
        if (needed > remaining)
            failHere(line, what + ": " + std::to_string(values) + " values declared (" +
                               (m_binary ? std::to_string(needed) + " bytes"
                                         : "at least " + std::to_string(needed) + " characters") +
                               "), only " + std::to_string(remaining) +
                               " bytes remain (truncated file or wrong count)");
    }

    std::string_view nextToken(std::uint64_t& tokenLine) {
        while (m_pos < m_data.size() && isSpace(m_data[m_pos])) {
            if (m_data[m_pos] == '\n')
                ++m_line;
            ++m_pos;
        }
        tokenLine = m_line;
        const std::size_t start = m_pos;
        while (m_pos < m_data.size() && !isSpace(m_data[m_pos]))
            ++m_pos;
        return m_data.substr(start, m_pos - start);
    }

    [[noreturn]] void failValue(std::uint64_t line, const std::string& what, std::uint64_t index,
                                std::uint64_t total, std::string_view token,
                                const char* expected) const {
        std::string msg = what + ": value " + std::to_string(index + 1) + " of " +
                          std::to_string(total) + ": expected " + expected + ", found ";
        msg += token.empty() ? std::string("the end of the file") : quoteForError(token);
        throw InputError(m_path, InputError::Where::Line, line, msg);
    }

    // Reads `values` numbers into `out`, or skips them when out is null.
    void readValues(std::uint64_t values, VtkScalar type, double* out, const std::string& what,
                    bool requireFinite = false) {
        if (m_binary) {
            const std::uint64_t bytes = detail::vtkPackedBytes(type, values);
            if (bytes > m_data.size() - m_pos)
                failHere(0, what + ": " + std::to_string(values) + " values need " +
                                std::to_string(bytes) + " bytes, only " +
                                std::to_string(m_data.size() - m_pos) + " remain");
            const auto* p = reinterpret_cast<const unsigned char*>(m_data.data() + m_pos);
            if (out) {
                detail::unpackVtkValues(p, values, type, true, out);
                if (requireFinite) {
                    const std::size_t bad = detail::firstNonFiniteAsFloat(out, values);
                    if (bad < values)
                        throw InputError(m_path, InputError::Where::Byte,
                                         m_pos + bad * detail::vtkScalarBytes(type),
                                         what + ": value " + std::to_string(bad + 1) +
                                             " is not a finite number (" +
                                             std::to_string(out[bad]) + ")");
                }
            }
            m_pos += bytes;
            m_afterBinary = true;
            return;
        }
        const bool integral = detail::vtkScalarIsIntegral(type);
        for (std::uint64_t i = 0; i < values; ++i) {
            std::uint64_t line = 0;
            std::string_view tok = nextToken(line);
            if (tok.empty())
                failValue(line, what, i, values, tok, "a number");
            if (!out) { // skipping: only refuse what cannot be a number (a keyword: too few values)
                const char c = tok[0];
                if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' ||
                      c == '.' || c == 'n' || c == 'N' || c == 'i' || c == 'I'))
                    failValue(line, what, i, values, tok, "a number");
                continue;
            }
            const char* b = tok.data() + (tok[0] == '+');
            double v;
            auto r = fast_float::from_chars(b, tok.data() + tok.size(), v);
            if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
                failValue(line, what, i, values, tok, integral ? "an integer" : "a number");
            if (integral && v != std::trunc(v))
                failValue(line, what, i, values, tok, "an integer");
            if (requireFinite && !std::isfinite(static_cast<float>(v)))
                failValue(line, what, i, values, tok, "a finite number");
            out[i] = v;
        }
    }

    void skipValues(std::uint64_t values, VtkScalar type, const std::string& what) {
        checkRoom(values, type, what, m_line);
        readValues(values, type, nullptr, what);
    }

    //-----------------------------------------------------------------------------
    // [SECTION] Sections: preamble, points, cells, fields, attributes
    //-----------------------------------------------------------------------------

    void readPreamble() {
        HeaderLine h;
        std::string_view line;
        if (m_data.substr(0, 3) == "\xEF\xBB\xBF")
            m_pos = 3; // a UTF-8 byte order mark
        if (!nextLine(line, h.line, h.offset) || !startsWithNoCase(line, "# vtk DataFile Version"))
            throw InputError(m_path, InputError::Where::Line, 1,
                             "expected '# vtk DataFile Version x.y' on the first line");
        std::string_view version = line.substr(22);
        while (!version.empty() && isSpace(version.front()))
            version.remove_prefix(1);
        double v = 0;
        auto r = fast_float::from_chars(version.data(), version.data() + version.size(), v);
        if (r.ec != std::errc() || !(v >= 1.0 && v < 100.0))
            throw InputError(
                m_path, InputError::Where::Line, 1,
                "expected a version number such as 3.0 or 5.1 after 'Version', found " +
                    quoteForError(version));
        if (!nextLine(line, h.line, h.offset)) // title: anything
            throw InputError(m_path, InputError::Where::Line, 2,
                             "expected a title line, found the end of the file");
        if (!nextHeaderLine(h))
            throw InputError(m_path, InputError::Where::Line, 3,
                             "expected ASCII or BINARY, found the end of the file");
        const std::string mode = upper(h.words[0]);
        if (h.words.size() != 1 || (mode != "ASCII" && mode != "BINARY"))
            fail(h, "expected ASCII or BINARY, found " + quoteForError(h.words[0]));
        m_binary = mode == "BINARY";
        if (!nextHeaderLine(h))
            throw InputError(m_path, InputError::Where::Line, m_line,
                             "expected 'DATASET POLYDATA' or 'DATASET UNSTRUCTURED_GRID', found "
                             "the end of the file");
        if (upper(h.words[0]) != "DATASET" || h.words.size() != 2)
            fail(h, "expected 'DATASET POLYDATA' or 'DATASET UNSTRUCTURED_GRID', found " +
                        quoteForError(h.words[0]));
        const std::string type = upper(h.words[1]);
        if (type != "POLYDATA" && type != "UNSTRUCTURED_GRID")
            fail(h, "DATASET " + std::string(h.words[1]) +
                        " is not supported: expected POLYDATA or UNSTRUCTURED_GRID (particles as "
                        "points)");
    }

    void readPoints(const HeaderLine& h) {
        expectWords(h, 3, "POINTS n type");
        const std::uint64_t n = count(h, 1, "point count");
        if (n > kMaxPoints)
            fail(h, "POINTS " + std::to_string(n) +
                        " is more than the 4 billion points a frame can hold");
        const VtkScalar type = scalarType(h, 2);
        checkRoom(3 * n, type, "POINTS", h.line);
        m_points.resize(3 * n);
        readValues(3 * n, type, m_points.data(), "POINTS", true);
    }

    void skipCells(const HeaderLine& h) {
        const std::string kw(h.words[0]);
        expectWords(h, 3, (kw + " n size").c_str());
        const std::uint64_t a = count(h, 1, "cell count");
        const std::uint64_t b = count(h, 2, "size");
        if (nextLineStartsWith("OFFSETS", true)) { // the 5.x form: OFFSETS then CONNECTIVITY
            for (const char* part : {"OFFSETS", "CONNECTIVITY"}) {
                HeaderLine p;
                if (!nextHeaderLine(p) || upper(p.words[0]) != part || p.words.size() != 2)
                    fail(p.words.empty() ? h : p, kw + ": expected '" + part + " type'");
                skipValues(std::string_view(part) == "OFFSETS" ? a : b, scalarType(p, 1),
                           kw + " " + part);
            }
        } else {
            skipValues(b, VtkScalar::Int32, kw);
        }
    }

    void skipMetadata() {
        // Ends at a blank line (or the end of the file).
        std::string_view line;
        std::uint64_t lineNo, offset;
        while (nextLine(line, lineNo, offset))
            if (split(line).empty())
                return;
    }

    void keepOrSkip(bool keep, std::string name, std::uint64_t tuples, std::uint64_t components,
                    VtkScalar type, const HeaderLine& h) {
        const std::string what = std::string(h.words[0]) + " '" + name + "'";
        if (components == 0 || components > detail::kMaxVtkComponents)
            fail(h, what + ": expected 1 to " + std::to_string(detail::kMaxVtkComponents) +
                        " components, found " + std::to_string(components));
        const std::uint64_t values = product(tuples, components);
        if (!keep)
            return skipValues(values, type, what);
        checkRoom(values, type, what, h.line);
        if (m_arrays.size() >= detail::kMaxVtkColumns)
            fail(h, "more than " + std::to_string(detail::kMaxVtkColumns) + " point arrays");
        VtkPointArray a;
        a.name = std::move(name);
        a.components = components;
        a.integralType = detail::vtkScalarIsIntegral(type);
        a.where = m_binary ? InputError::Where::Byte : InputError::Where::Line;
        a.position = a.where == InputError::Where::Byte ? m_pos : h.line;
        a.values.resize(values);
        readValues(values, type, a.values.data(), what);
        m_arrays.push_back(std::move(a));
    }

    void readField(const HeaderLine& h, bool keep, std::uint64_t tuples) {
        expectWords(h, 3, "FIELD name count");
        const std::uint64_t arrays = count(h, 2, "array count");
        for (std::uint64_t k = 0; k < arrays; ++k) {
            HeaderLine a;
            if (!nextHeaderLine(a))
                throw InputError(m_path, InputError::Where::Line, m_line,
                                 "FIELD " + std::string(h.words[1]) + ": expected " +
                                     std::to_string(arrays) + " arrays, found " +
                                     std::to_string(k));
            if (upper(a.words[0]) == "NULL_ARRAY")
                continue;
            if (a.words.size() != 4)
                fail(a, "FIELD " + std::string(h.words[1]) + " array " + std::to_string(k + 1) +
                            ": expected 'name components tuples type'");
            const std::uint64_t components = count(a, 1, "component count");
            const std::uint64_t n = count(a, 2, "tuple count");
            const VtkScalar type = scalarType(a, 3);
            if (keep && n != tuples)
                fail(a, "FIELD array '" + std::string(a.words[0]) + "' has " + std::to_string(n) +
                            " tuples, expected one per point (" + std::to_string(tuples) + ")");
            keepOrSkip(keep, decodeName(a.words[0]), n, components, type, a);
            if (nextLineStartsWith("METADATA", false)) {
                HeaderLine m;
                nextHeaderLine(m);
                skipMetadata();
            }
        }
    }

    // An attribute of POINT_DATA (keep) or CELL_DATA (skip). False for an unknown keyword.
    bool readAttribute(const HeaderLine& h, const std::string& key, bool keep,
                       std::uint64_t tuples) {
        if (key == "SCALARS") {
            if (h.words.size() != 3 && h.words.size() != 4)
                fail(h, "expected 'SCALARS name type [components]'");
            const VtkScalar type = scalarType(h, 2);
            const std::uint64_t components =
                h.words.size() == 4 ? count(h, 3, "component count") : 1;
            if (nextLineStartsWith("LOOKUP_TABLE", true)) {
                HeaderLine lut;
                nextHeaderLine(lut);
                if (lut.words.size() != 2)
                    fail(lut, "expected 'LOOKUP_TABLE name' after SCALARS");
            }
            keepOrSkip(keep, decodeName(h.words[1]), tuples, components, type, h);
        } else if (key == "VECTORS" || key == "NORMALS") {
            expectWords(h, 3, (key + " name type").c_str());
            keepOrSkip(keep, decodeName(h.words[1]), tuples, 3, scalarType(h, 2), h);
        } else if (key == "TENSORS" || key == "TENSORS6") {
            expectWords(h, 3, (key + " name type").c_str());
            keepOrSkip(keep, decodeName(h.words[1]), tuples, key == "TENSORS" ? 9 : 6,
                       scalarType(h, 2), h);
        } else if (key == "GLOBAL_IDS" || key == "PEDIGREE_IDS") {
            expectWords(h, 3, (key + " name type").c_str());
            keepOrSkip(keep, decodeName(h.words[1]), tuples, 1, scalarType(h, 2), h);
        } else if (key == "EDGE_FLAGS") {
            expectWords(h, 3, "EDGE_FLAGS name type");
            keepOrSkip(false, decodeName(h.words[1]), tuples, 1, scalarType(h, 2), h);
        } else if (key == "TEXTURE_COORDINATES") { // not a physical variable: skipped
            expectWords(h, 4, "TEXTURE_COORDINATES name dim type");
            keepOrSkip(false, decodeName(h.words[1]), tuples, count(h, 2, "dimension"),
                       scalarType(h, 3), h);
        } else if (key == "COLOR_SCALARS") { // colours, not variables: skipped
            expectWords(h, 3, "COLOR_SCALARS name components");
            keepOrSkip(false, decodeName(h.words[1]), tuples, count(h, 2, "component count"),
                       m_binary ? VtkScalar::UInt8 : VtkScalar::Float32, h);
        } else if (key == "LOOKUP_TABLE") {
            expectWords(h, 3, "LOOKUP_TABLE name size");
            keepOrSkip(false, decodeName(h.words[1]), count(h, 2, "table size"), 4,
                       m_binary ? VtkScalar::UInt8 : VtkScalar::Float32, h);
        } else {
            return false;
        }
        return true;
    }

    const std::string& m_path;
    std::string_view m_data;
    std::size_t m_pos = 0;
    std::uint64_t m_line = 1; // line number of m_data[m_pos] (meaningless after binary data)
    bool m_binary = false;
    bool m_afterBinary = false; // binary data was read: positions are byte offsets from here on
    std::vector<double> m_points;
    std::vector<VtkPointArray> m_arrays;
};

} // namespace

//-----------------------------------------------------------------------------
// [SECTION] Entry points
//-----------------------------------------------------------------------------

bool looksLikeVtkLegacy(std::string_view head) {
    if (head.substr(0, 3) == "\xEF\xBB\xBF")
        head.remove_prefix(3);
    return startsWithNoCase(head, "# vtk DataFile");
}

Frame parseVtkLegacy(const std::string& path, std::string_view bytes) {
    LegacyReader reader(path, bytes);
    return reader.read();
}

} // namespace faultline::core
