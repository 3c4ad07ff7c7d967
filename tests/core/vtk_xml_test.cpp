#include "core/data/dataset.hpp"
#include "core/io/frame_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/vtk_xml.hpp"
#include "tests/common/sanitizers.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

using namespace faultline::core;

namespace {

const std::string kXmlPath = "synthetic.vtu";

// ---- building documents the way VTK writers do ------------------------------------------

std::string base64(const std::string& bytes) {
    static const char* kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (std::size_t k = 0; k < 3; ++k)
            v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += n > 1 ? kAlphabet[(v >> 6) & 63] : '=';
        out += n > 2 ? kAlphabet[v & 63] : '=';
    }
    return out;
}

template <typename T> std::string packed(T value, bool big) {
    std::string s(sizeof(T), '\0');
    std::memcpy(s.data(), &value, sizeof(T));
    if (big == (std::endian::native == std::endian::little))
        std::reverse(s.begin(), s.end());
    return s;
}

std::string encodeValues(const std::string& type, const std::vector<double>& values, bool big) {
    std::string out;
    for (double v : values) {
        if (type == "Float32")
            out += packed(static_cast<float>(v), big);
        else if (type == "Float64")
            out += packed(v, big);
        else if (type == "Int32")
            out += packed(static_cast<std::int32_t>(v), big);
        else if (type == "Int64")
            out += packed(static_cast<std::int64_t>(v), big);
        else if (type == "UInt8")
            out += packed(static_cast<std::uint8_t>(v), big);
        else
            throw std::logic_error("test encodes no " + type);
    }
    return out;
}

enum class Mode { Ascii, Inline, AppendedRaw, AppendedBase64 };

struct Options {
    Mode mode = Mode::Ascii;
    bool header64 = false;
    bool bigEndian = false;
    bool zlib = false;
    std::size_t blockSize = 16; // small: several blocks and a partial last one
    bool jointBase64 = false;   // header and data in one base64 stream (not VTK's way)
    std::string type = "UnstructuredGrid";
};

std::string word(std::uint64_t v, const Options& o) {
    return o.header64 ? packed<std::uint64_t>(v, o.bigEndian)
                      : packed<std::uint32_t>(static_cast<std::uint32_t>(v), o.bigEndian);
}

// The size header and the (possibly compressed) body of one array's bytes.
std::pair<std::string, std::string> framed(const std::string& raw, const Options& o) {
    if (!o.zlib)
        return {word(raw.size(), o), raw};
    const std::size_t blocks = (raw.size() + o.blockSize - 1) / o.blockSize;
    std::string header = word(blocks, o) + word(o.blockSize, o) + word(raw.size() % o.blockSize, o);
    std::string body;
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::string block = raw.substr(b * o.blockSize, o.blockSize);
        uLongf size = compressBound(block.size());
        std::string out(size, '\0');
        EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                            reinterpret_cast<const Bytef*>(block.data()), block.size(), 6),
                  Z_OK);
        out.resize(size);
        header += word(size, o);
        body += out;
    }
    return {header, body};
}

struct TestArray {
    std::string name, type;
    int components = 1;
    std::vector<double> values;
};

struct TestPiece {
    TestArray points;
    std::vector<TestArray> pointData;
};

std::string asciiValues(const std::vector<double>& values) {
    std::string s;
    char buf[40];
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.17g", values[i]);
        s += (i % 3 == 0 ? "\n          " : " ") + std::string(buf);
    }
    return s + "\n        ";
}

std::string makeDocument(const Options& o, const std::vector<TestPiece>& pieces) {
    std::string appended;
    auto dataArray = [&](const TestArray& a) {
        std::string tag = "<DataArray type=\"" + a.type + "\" Name=\"" + a.name +
                          "\" NumberOfComponents=\"" + std::to_string(a.components) + "\"";
        const std::string raw = encodeValues(a.type, a.values, o.bigEndian);
        const auto [header, body] = framed(raw, o);
        switch (o.mode) {
        case Mode::Ascii:
            return tag + " format=\"ascii\">" + asciiValues(a.values) + "</DataArray>\n";
        case Mode::Inline:
            return tag + " format=\"binary\">\n          " +
                   (o.jointBase64 ? base64(header + body) : base64(header) + base64(body)) +
                   "\n        </DataArray>\n";
        case Mode::AppendedRaw:
        case Mode::AppendedBase64: {
            tag += " format=\"appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
            appended += o.mode == Mode::AppendedRaw ? header + body : base64(header) + base64(body);
            return tag;
        }
        }
        return std::string();
    };
    std::string doc = "<!-- written by the test: no <?xml?> line -->\n<VTKFile type=\"" + o.type +
                      "\" version=\"1.0\" byte_order=\"" +
                      (o.bigEndian ? "BigEndian" : "LittleEndian") + "\" header_type=\"" +
                      (o.header64 ? "UInt64" : "UInt32") + "\"" +
                      (o.zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n  <" + o.type +
                      ">\n    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" "
                      "NumberOfTuples=\"1\" format=\"ascii\">0.5</DataArray>\n    </FieldData>\n";
    for (const TestPiece& p : pieces) {
        const std::size_t n = p.points.values.size() / 3;
        doc += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"0\">\n";
        doc += "      <PointData Scalars=\"radius\">\n";
        for (const TestArray& a : p.pointData)
            doc += "        " + dataArray(a);
        doc += "        <DataArray type=\"String\" Name=\"label\" format=\"ascii\">97 0 98 "
               "0</DataArray>\n";
        doc += "      </PointData>\n      <CellData>\n      </CellData>\n";
        doc += "      <Points>\n        " + dataArray(p.points) + "      </Points>\n";
        doc +=
            "      <Cells>\n        <DataArray type=\"Int64\" Name=\"connectivity\" "
            "format=\"ascii\">"
            "</DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n"
            "        </DataArray>\n      </Cells>\n    </Piece>\n";
    }
    doc += "  </" + o.type + ">\n";
    if (o.mode == Mode::AppendedRaw || o.mode == Mode::AppendedBase64)
        doc += std::string("  <AppendedData encoding=\"") +
               (o.mode == Mode::AppendedRaw ? "raw" : "base64") + "\">\n   _" + appended +
               "\n  </AppendedData>\n";
    return doc + "</VTKFile>\n";
}

TestPiece standardPiece() {
    TestPiece p;
    p.points = {"Points", "Float32", 3, {0.5, -1.25, 3, 2, 4, 8, -0.75, 1e3, 6.5}};
    p.pointData = {{"radius", "Float64", 1, {0.1, 0.2, 0.3}},
                   {"id", "Int64", 1, {7, 5, 9}},
                   {"velocity", "Float32", 3, {1, 2, 3, 4, 5, 6, 7, 8, 9}},
                   {"grain", "Int32", 1, {-1, 0, 2}},
                   {"q", "Float64", 2, {0.5, 1.5, 2.5, 3.5, 4.5, 5.5}},
                   {"flags", "UInt8", 1, {0, 255, 10}}};
    return p;
}

const AttributeColumn& xmlColumn(const Frame& f, const std::string& name) {
    const AttributeColumn* c = f.attribute(name);
    if (!c)
        throw std::runtime_error("no column " + name);
    return *c;
}

void expectStandardFrame(const Frame& f) {
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f.x, (std::vector<float>{0.5f, 2, -0.75f}));
    EXPECT_EQ(f.y, (std::vector<float>{-1.25f, 4, 1e3f}));
    EXPECT_EQ(f.z, (std::vector<float>{3, 8, 6.5f}));
    EXPECT_EQ(f.radius, (std::vector<float>{0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{7, 5, 9}));
    EXPECT_FALSE(f.idsAreRowNumbers);
    EXPECT_FALSE(f.radiusIsDefault);
    EXPECT_EQ(f.attributeNames(),
              (std::vector<std::string>{"velocity_x", "velocity_y", "velocity_z", "grain", "q_0",
                                        "q_1", "flags"}));
    EXPECT_EQ(xmlColumn(f, "velocity_z").floats, (std::vector<float>{3, 6, 9}));
    EXPECT_EQ(xmlColumn(f, "grain").ints, (std::vector<std::int32_t>{-1, 0, 2}));
    EXPECT_EQ(xmlColumn(f, "q_1").floats, (std::vector<float>{1.5f, 3.5f, 5.5f}));
    EXPECT_EQ(xmlColumn(f, "flags").ints, (std::vector<std::int32_t>{0, 255, 10}));
}

std::vector<Options> everyEncoding() {
    std::vector<Options> all{Options{}};
    for (Mode mode : {Mode::Inline, Mode::AppendedRaw, Mode::AppendedBase64})
        for (bool h64 : {false, true})
            for (bool big : {false, true})
                for (bool z : {false, true}) {
                    Options o;
                    o.mode = mode;
                    o.header64 = h64;
                    o.bigEndian = big;
                    o.zlib = z;
                    all.push_back(o);
                }
    Options joint;
    joint.mode = Mode::Inline;
    joint.jointBase64 = true;
    all.push_back(joint);
    joint.zlib = true;
    joint.header64 = true;
    all.push_back(joint);
    return all;
}

std::string describe(const Options& o) {
    static const char* kModes[] = {"ascii", "inline base64", "appended raw", "appended base64"};
    return std::string(kModes[static_cast<int>(o.mode)]) + (o.header64 ? " UInt64" : " UInt32") +
           (o.bigEndian ? " BigEndian" : " LittleEndian") + (o.zlib ? " zlib" : "") +
           (o.jointBase64 ? " joint" : "");
}

InputError xmlErrorOf(const std::string& doc) {
    try {
        parseVtkXml(kXmlPath, doc);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "expected an InputError for:\n" << doc.substr(0, 600);
    return InputError(kXmlPath, "none");
}

std::uint64_t lineOf(const std::string& doc, const std::string& what) {
    const std::size_t at = doc.find(what);
    EXPECT_NE(at, std::string::npos) << what;
    return 1 + static_cast<std::uint64_t>(
                   std::count(doc.begin(), doc.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

void expectXmlError(const std::string& doc, InputError::Where where, std::uint64_t position,
                    const std::string& needle) {
    const InputError e = xmlErrorOf(doc);
    EXPECT_EQ(e.path(), kXmlPath);
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_EQ(e.position(), position) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << needle;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
}

// A one-piece document whose Points array holds `payload` verbatim (inline binary).
std::string withPointsPayload(const std::string& payload, const std::string& attrs = "",
                              std::size_t points = 3) {
    return "<VTKFile type=\"UnstructuredGrid\" byte_order=\"LittleEndian\"" + attrs +
           ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(points) +
           "\">\n<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" "
           "format=\"binary\">" +
           payload + "</DataArray>\n</Points>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

std::string le32(std::uint32_t v) { return packed(v, false); }
std::string floats(std::initializer_list<float> v) {
    std::string s;
    for (float f : v)
        s += packed(f, false);
    return s;
}
std::string zlibOf(const std::string& raw) {
    uLongf size = compressBound(raw.size());
    std::string out(size, '\0');
    compress2(reinterpret_cast<Bytef*>(out.data()), &size,
              reinterpret_cast<const Bytef*>(raw.data()), raw.size(), 6);
    out.resize(size);
    return out;
}

} // namespace

TEST(VtkXml, DetectsByContent) {
    EXPECT_TRUE(looksLikeVtkXml("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\">"));
    EXPECT_TRUE(looksLikeVtkXml("<!-- c -->\n<VTKFile type=\"PolyData\" version=\"0.1\">"));
    EXPECT_FALSE(looksLikeVtkXml("<VTKFile type=\"Collection\">"));
    EXPECT_TRUE(looksLikeVtkCollection("<VTKFile type=\"Collection\" version=\"0.1\">"));
    EXPECT_FALSE(looksLikeVtkCollection("<VTKFile type=\"PolyData\">"));
    EXPECT_FALSE(looksLikeVtkXml("x,y,z\n1,2,3\n"));
}

TEST(VtkXml, EveryEncodingGivesTheSameFrame) {
    for (const Options& o : everyEncoding()) {
        SCOPED_TRACE(describe(o));
        const std::string doc = makeDocument(o, {standardPiece()});
        try {
            expectStandardFrame(parseVtkXml(kXmlPath, doc));
        } catch (const InputError& e) {
            ADD_FAILURE() << e.what();
        }
    }
}

TEST(VtkXml, PolyDataAndSeveralPiecesConcatenate) {
    Options o;
    o.type = "PolyData";
    o.mode = Mode::AppendedRaw;
    o.zlib = true;
    TestPiece a = standardPiece();
    TestPiece b;
    b.points = {"Points", "Float64", 3, {10, 11, 12}};
    b.pointData = {{"radius", "Float64", 1, {0.4}},          {"id", "Int64", 1, {100}},
                   {"velocity", "Float32", 3, {-1, -2, -3}}, {"grain", "Int32", 1, {5}},
                   {"q", "Float64", 2, {0.25, 0.75}},        {"flags", "UInt8", 1, {1}}};
    const Frame f = parseVtkXml(kXmlPath, makeDocument(o, {a, b}));
    ASSERT_EQ(f.size(), 4u);
    EXPECT_EQ(f.x, (std::vector<float>{0.5f, 2, -0.75f, 10}));
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{7, 5, 9, 100}));
    EXPECT_EQ(f.radius.back(), 0.4f);
    EXPECT_EQ(xmlColumn(f, "velocity_y").floats, (std::vector<float>{2, 5, 8, -2}));
    EXPECT_EQ(xmlColumn(f, "q_0").floats.back(), 0.25f);
    EXPECT_EQ(f.rowOf(100), 3u);
}

TEST(VtkXml, EmptyPieceAndDefaults) {
    const std::string empty =
        "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>"
        "<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\"><Points>"
        "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
        "</DataArray></Points></Piece></UnstructuredGrid></VTKFile>";
    EXPECT_EQ(parseVtkXml(kXmlPath, empty).size(), 0u);
    const std::string plain =
        "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"2\">"
        "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" "
        "format=\"ascii\">1 2 3 4 5 6</DataArray></Points>"
        "<PointData><DataArray type=\"Float32\" Name=\"Diameter\" format=\"ascii\">"
        "2 4</DataArray></PointData></Piece></PolyData></VTKFile>";
    const Frame f = parseVtkXml(kXmlPath, plain);
    EXPECT_EQ(f.radius, (std::vector<float>{1, 2}));
    EXPECT_TRUE(f.idsAreRowNumbers);
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{0, 1}));
    EXPECT_TRUE(f.attributes.empty());
}

TEST(VtkXml, BadBinaryDataNamesTheByteOffset) {
    using W = InputError::Where;
    const std::string data = floats({1, 2, 3, 4, 5, 6, 7, 8, 9});
    // A character that is not base64.
    std::string bad = withPointsPayload(base64(le32(36)) + "!" + base64(data).substr(1));
    expectXmlError(bad, W::Byte, bad.find('!'), "expected base64 data, found '!'");
    // A size header beyond the data, and one that does not match the points.
    const std::string shortData = withPointsPayload(base64(le32(36)) + base64(data.substr(0, 12)));
    expectXmlError(shortData, W::Byte, shortData.find("JAAAAA==") + 8,
                   "declares 36 bytes, only 12 remain");
    expectXmlError(withPointsPayload(base64(le32(1000000000)) + base64(data)), W::Byte,
                   withPointsPayload("").find("</DataArray>") + 8,
                   "size header declares 1000000000 bytes, expected 36");
    // Header and data encoded together, cut short: refused before reading the data.
    const std::string cut = withPointsPayload(base64(le32(36) + data).substr(0, 49));
    expectXmlError(cut, W::Byte, cut.find("format=\"binary\">") + 16 + 8,
                   "declares 36 bytes, only 32 remain");
    // Base64 that ends inside a group of four characters.
    const std::string whole = base64(le32(24)) + base64(data.substr(0, 24));
    const std::string group = withPointsPayload(whole.substr(0, whole.size() - 3) + "   ", "", 2);
    expectXmlError(group, W::Byte, group.find("</DataArray>"),
                   "ends inside a group of 4 characters");
}

TEST(VtkXml, LyingZlibBlocksAreRefusedBeforeAllocating) {
    using W = InputError::Where;
    const std::string zlib = " compressor=\"vtkZLibDataCompressor\"";
    const std::string data = floats({1, 2, 3, 4, 5, 6, 7, 8, 9});
    const std::string small = zlibOf(data.substr(0, 12));
    auto header = [](std::uint32_t blocks, std::uint32_t size, std::uint32_t last,
                     std::vector<std::uint32_t> sizes) {
        std::string h = le32(blocks) + le32(size) + le32(last);
        for (auto s : sizes)
            h += le32(s);
        return h;
    };
    // The block inflates to 12 bytes, its header says 36.
    const std::string lies = withPointsPayload(
        base64(header(1, 36, 0, {static_cast<std::uint32_t>(small.size())})) + base64(small), zlib);
    EXPECT_NE(std::string(xmlErrorOf(lies).what())
                  .find("does not decompress to the 36 bytes its header declares"),
              std::string::npos)
        << xmlErrorOf(lies).what();
    // 10^8 points claimed from a few compressed bytes: more than zlib can produce.
    const std::string huge = withPointsPayload(
        base64(header(1, 1200000000, 0, {static_cast<std::uint32_t>(small.size())})) +
            base64(small),
        zlib, 100000000);
    EXPECT_NE(std::string(xmlErrorOf(huge).what()).find("more than zlib can produce"),
              std::string::npos)
        << xmlErrorOf(huge).what();
    EXPECT_EQ(xmlErrorOf(huge).where(), W::Byte);
    // Compressed sizes beyond the data, and a block count the data cannot hold.
    const std::string beyond =
        withPointsPayload(base64(header(1, 36, 0, {1000000})) + base64(small), zlib);
    EXPECT_NE(std::string(xmlErrorOf(beyond).what())
                  .find("a compressed block of 1000000 bytes is declared"),
              std::string::npos)
        << xmlErrorOf(beyond).what();
    const std::string blocks = withPointsPayload(base64(header(0x7fffffff, 36, 0, {})), zlib);
    EXPECT_NE(std::string(xmlErrorOf(blocks).what()).find("more than the data can hold"),
              std::string::npos)
        << xmlErrorOf(blocks).what();
    // A total that does not match the points.
    const std::string total =
        withPointsPayload(base64(header(2, 36, 0, {4, 4})) + base64("abcdefgh"), zlib);
    EXPECT_NE(
        std::string(xmlErrorOf(total).what()).find("declares 72 uncompressed bytes, expected 36"),
        std::string::npos)
        << xmlErrorOf(total).what();
    // Garbage where zlib data should be.
    const std::string garbage =
        withPointsPayload(base64(header(1, 36, 0, {12})) + base64("not zlib at all"), zlib);
    EXPECT_NE(std::string(xmlErrorOf(garbage).what()).find("zlib block 0 is corrupt"),
              std::string::npos)
        << xmlErrorOf(garbage).what();
}

TEST(VtkXml, MalformedStructureNamesLineAndExpectation) {
    using W = InputError::Where;
    Options ascii;
    const std::string good = makeDocument(ascii, {standardPiece()});
    expectXmlError("", W::Line, 1, "no XML element found");
    expectXmlError("<!-- only a comment -->\n", W::Line, 2, "no XML element found");
    expectXmlError("<!-- unterminated\n<VTKFile>", W::Line, 1, "unterminated comment");
    expectXmlError("<Other type=\"PolyData\"/>", W::Line, 1,
                   "expected <VTKFile> as the root element");
    expectXmlError("<VTKFile type=\"ImageData\">\n</VTKFile>", W::Line, 1,
                   "VTKFile type 'ImageData' is not supported");
    expectXmlError(replaced(good, "header_type=\"UInt32\"", "header_type=\"UInt16\""), W::Line, 2,
                   "header_type: expected UInt32 or UInt64");
    expectXmlError(replaced(good, "byte_order=\"LittleEndian\"", "byte_order=\"Middle\""), W::Line,
                   2, "byte_order: expected LittleEndian or BigEndian");
    expectXmlError(replaced(good, "version=\"1.0\"", "compressor=\"vtkZstdDataCompressor\""),
                   W::Line, 2, "'vtkZstdDataCompressor' is not supported");
    // Deeply nested, unclosed and mismatched elements.
    std::string deep = "<VTKFile type=\"PolyData\">\n";
    for (int i = 0; i < 100; ++i)
        deep += "<a>";
    expectXmlError(deep, W::Line, 2, "nested deeper than 64 levels");
    const std::string unclosed = good.substr(0, good.find("  </UnstructuredGrid>"));
    expectXmlError(unclosed, W::Line, lineOf(good, "  </UnstructuredGrid>"),
                   "the file ends inside <UnstructuredGrid> opened at line 3");
    expectXmlError(replaced(good, "</Points>", "</Piece>"), W::Line, lineOf(good, "</Points>"),
                   "expected </Points>");
    expectXmlError(
        replaced(good, "<Piece NumberOfPoints=\"3\"", "<Piece NumberOfPoints=\"1000000000000\""),
        W::Line, lineOf(good, "<Piece"), "NumberOfPoints=\"1000000000000\" is more than");
    expectXmlError(
        replaced(good, "<Piece NumberOfPoints=\"3\"", "<Piece NumberOfPoints=\"100000000\""),
        W::Line, lineOf(good, "Name=\"Points\""), "expected 300000000 values, its text is only");
    expectXmlError(replaced(good, "<Piece NumberOfPoints=\"3\"", "<Piece NumberOfPoints=\"three\""),
                   W::Line, lineOf(good, "<Piece"),
                   "NumberOfPoints: expected a non-negative integer, found 'three'");
    expectXmlError(replaced(good, "<Piece NumberOfPoints=\"3\"", "<Piece"), W::Line,
                   lineOf(good, "<Piece"), "<Piece> has no NumberOfPoints attribute");
    expectXmlError(replaced(good, "Name=\"radius\"", "Name=\"radius\" Name=\"r\""), W::Line,
                   lineOf(good, "Name=\"radius\""), "attribute Name appears twice");
    expectXmlError(
        replaced(good, "type=\"Float64\" Name=\"radius\"", "type=\"Float16\" Name=\"radius\""),
        W::Line, lineOf(good, "Name=\"radius\""), "type 'Float16' is not supported");
    expectXmlError(replaced(good, "Name=\"Points\" NumberOfComponents=\"3\"",
                            "Name=\"Points\" NumberOfComponents=\"2\""),
                   W::Line, lineOf(good, "Name=\"Points\""),
                   "must have 3 numeric components, found 2");
    expectXmlError(replaced(good, "Name=\"grain\" NumberOfComponents=\"1\"",
                            "Name=\"grain\" NumberOfComponents=\"1\" NumberOfTuples=\"4\""),
                   W::Line, lineOf(good, "Name=\"grain\""), "NumberOfTuples=4 but the Piece");
    // Values: not a number, NaN positions, too many values.
    expectXmlError(replaced(good, "0.10000000000000001", "zero.one"), W::Line,
                   lineOf(good, "0.10000000000000001"),
                   "value 1 of 3: expected a number, found 'zero.one'");
    expectXmlError(replaced(good, "-0.75", "nan"), W::Line, lineOf(good, "-0.75"),
                   "value 7 of 9: expected a finite number, found 'nan'");
    expectXmlError(replaced(good, " 7 5 9", " 7 5 9 11"), W::Line, lineOf(good, " 7 5 9"),
                   "more values than the 3 expected, found '11'");
    expectXmlError(replaced(good, " 7 5 9", " 7 5 9.5"), W::Line, lineOf(good, " 7 5 9"),
                   "expected an integer, found '9.5'");
    expectXmlError(replaced(good, " 7 5 9", " 7 7 9"), W::Line, lineOf(good, "Name=\"id\""),
                   "particle id 7 appears twice");
    // Missing points, binary garbage in markup.
    const std::string noPoints = "<VTKFile type=\"PolyData\">\n<PolyData>\n<Piece "
                                 "NumberOfPoints=\"2\">\n</Piece>\n</PolyData>\n</VTKFile>";
    expectXmlError(noPoints, W::Line, 3, "Piece with 2 points has no <Points> DataArray");
    expectXmlError("<VTKFile type=\"PolyData\">\x01\x02\n<\x03\xff", W::Line, 2,
                   "expected a tag name after '<'");
    expectXmlError("<VTKFile type=\"PolyData\">\n<PolyData>\n</PolyData>\n</VTKFile>", W::File, 0,
                   "no <Piece> inside <PolyData>");
    expectXmlError("<VTKFile type=\"PolyData\"/> trailing", W::Line, 1,
                   "content after the root element");
}

TEST(VtkXml, ArraysWithoutDataAreStillBounded) {
    std::string doc =
        "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"0\"><PointData>\n";
    for (int i = 0; i < 5000; ++i)
        doc += "<DataArray type=\"Float32\" Name=\"a" + std::to_string(i) +
               "\" NumberOfComponents=\"256\" format=\"ascii\"/>\n";
    doc += "</PointData></Piece></PolyData></VTKFile>";
    expectXmlError(doc, InputError::Where::Line, 4098, "more than 4096 PointData arrays");
    const std::string twenty = doc.substr(0, doc.find("<DataArray type=\"Float32\" Name=\"a20\"")) +
                               "</PointData></Piece></PolyData></VTKFile>";
    expectXmlError(twenty, InputError::Where::Line, 18, "more than 4096 attribute columns");
}

TEST(VtkXml, AppendedDataErrors) {
    using W = InputError::Where;
    Options raw;
    raw.mode = Mode::AppendedRaw;
    const std::string good = makeDocument(raw, {standardPiece()});
    const std::string noAppended = good.substr(0, good.find("  <AppendedData")) + "</VTKFile>\n";
    expectXmlError(noAppended, W::Line, lineOf(good, "Name=\"Points\""),
                   "is appended, but the file has no <AppendedData>");
    expectXmlError(replaced(good, "offset=\"0\"", "offset=\"100000\""), W::Line,
                   lineOf(good, "Name=\"radius\""), "offset 100000 is beyond the");
    expectXmlError(replaced(good, "   _", "   x"), W::Line, lineOf(good, "<AppendedData"),
                   "expected the '_' marker");
    // An infinite coordinate in raw appended data: the byte offset of that array's data.
    TestPiece p = standardPiece();
    p.points.values[4] = std::numeric_limits<double>::infinity();
    const std::string inf = makeDocument(raw, {p});
    const std::size_t appendedStart = inf.find("   _") + 4;
    const std::string offsetAttr =
        "Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\"";
    const std::size_t at = inf.find(offsetAttr) + offsetAttr.size();
    const std::uint64_t offset = std::stoull(inf.substr(at, inf.find('"', at) - at));
    expectXmlError(inf, W::Byte, appendedStart + offset, "value 5 is not a finite number");
    // Appended data cut short.
    const std::string cut = good.substr(0, good.find("   _") + 4 + 190);
    EXPECT_NE(std::string(xmlErrorOf(cut).what()).find("declares 36 bytes, only 15 remain"),
              std::string::npos)
        << xmlErrorOf(cut).what();
    EXPECT_EQ(xmlErrorOf(cut).where(), W::Byte) << xmlErrorOf(cut).what();
}

TEST(VtkXml, TruncatedOrCorruptedFilesOnlyEverGiveInputErrors) {
    std::vector<Options> some(4);
    some[1].mode = Mode::Inline;
    some[1].zlib = some[1].header64 = true;
    some[2].mode = Mode::AppendedRaw;
    some[2].zlib = some[2].bigEndian = true;
    some[3].mode = Mode::AppendedBase64;
    for (const Options& o : some) {
        SCOPED_TRACE(describe(o));
        const std::string good = makeDocument(o, {standardPiece()});
        for (std::size_t n = 0; n < good.size(); ++n) {
            try {
                parseVtkXml(kXmlPath, good.substr(0, n));
            } catch (const InputError&) {
            }
        }
        for (std::size_t i = 0; i < good.size(); ++i)
            for (char c : {'<', '>', '"', '\0', '9', '\xff', '/', '='}) {
                std::string bad = good;
                bad[i] = c;
                try {
                    parseVtkXml(kXmlPath, bad);
                } catch (const InputError&) {
                }
            }
    }
}

TEST(VtkXml, CollectionSortsByTimestepKeepingFileOrder) {
    const std::string pvd =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
        "  <Collection>\n"
        "    <DataSet timestep=\"2\" group=\"\" part=\"0\" file=\"c.vtu\"/>\n"
        "    <DataSet timestep=\"0\" file=\"a.vtu\"/>\n"
        "    <DataSet timestep=\"0.5\" file=\"b.vtu\"/>\n"
        "    <DataSet timestep=\"5e-1\" file=\"sub/d.vtu\"/>\n"
        "  </Collection>\n</VTKFile>\n";
    const auto entries = parseVtkCollection("run.pvd", pvd);
    ASSERT_EQ(entries.size(), 4u);
    EXPECT_EQ(entries[0].file, "a.vtu");
    EXPECT_EQ(entries[1].file, "b.vtu");
    EXPECT_EQ(entries[2].file, "sub/d.vtu");
    EXPECT_EQ(entries[3].file, "c.vtu");
    EXPECT_EQ(entries[2].time, 0.5);
    EXPECT_EQ(entries[3].time, 2.0);

    auto err = [](const std::string& text) -> std::string {
        try {
            parseVtkCollection("run.pvd", text);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(err(replaced(pvd, " file=\"a.vtu\"", "")),
              "run.pvd:5: <DataSet> has no file attribute");
    EXPECT_EQ(err(replaced(pvd, "timestep=\"0\"", "timestep=\"soon\"")),
              "run.pvd:5: timestep: expected a finite number, found 'soon'");
    EXPECT_EQ(err(replaced(pvd, "\"Collection\"", "\"PolyData\"")),
              "run.pvd:2: expected <VTKFile type=\"Collection\"> as the root element");
    EXPECT_EQ(err(replaced(pvd, "</Collection>", "")),
              "run.pvd:9: expected </Collection> (opened at line 3), found </VTKFile>");
}

TEST(VtkXml, CollectionOpensAsATimeSeries) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "faultline_vtk_pvd";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / "sub");
    auto write = [&](const std::string& name, std::size_t points, Mode mode) {
        Options o;
        o.mode = mode;
        o.zlib = mode != Mode::Ascii;
        TestPiece p;
        for (std::size_t i = 0; i < points; ++i)
            p.points.values.insert(p.points.values.end(), {double(i), 0, 0});
        p.points.name = "Points";
        p.points.type = "Float32";
        p.points.components = 3;
        std::ofstream(dir / name, std::ios::binary) << makeDocument(o, {p});
    };
    write("a.vtu", 1, Mode::Ascii);
    write("b.vtu", 2, Mode::AppendedRaw);
    write("sub/d.vtu", 3, Mode::Inline);
    write("c.vtu", 4, Mode::AppendedBase64);
    std::ofstream(dir / "run.pvd") << "<VTKFile type=\"Collection\"><Collection>\n"
                                      "<DataSet timestep=\"2\" file=\"c.vtu\"/>\n"
                                      "<DataSet timestep=\"0\" file=\"a.vtu\"/>\n"
                                      "<DataSet timestep=\"0.5\" file=\"b.vtu\"/>\n"
                                      "<DataSet timestep=\"0.5\" file=\"sub/d.vtu\"/>\n"
                                      "</Collection></VTKFile>\n";
    auto ds = Dataset::open({(dir / "run.pvd").string()});
    ASSERT_EQ(ds->frameCount(), 4u);
    const double times[] = {0, 0.5, 0.5, 2};
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(ds->location(k).time, times[k]);
        EXPECT_EQ(ds->location(k).format, FileFormat::VtkXml);
        EXPECT_EQ(ds->frame(k)->size(), k + 1);
        EXPECT_TRUE(ds->frame(k)->radiusIsDefault);
    }
    std::filesystem::remove_all(dir);
}

#ifdef FAULTLINE_TEST_DATA
TEST(VtkXml, MercuryDpmAsciiWithCommentAndNoCells) {
    auto ds = Dataset::open(
        {std::string(FAULTLINE_TEST_DATA) + "/mercurydpm_particles_ascii_nocells.vtu"});
    ASSERT_EQ(ds->frameCount(), 1u);
    EXPECT_EQ(ds->location(0).format, FileFormat::VtkXml);
    const auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 66u);
    EXPECT_FALSE(f->idsAreRowNumbers);
    EXPECT_FALSE(f->radiusIsDefault);
    EXPECT_EQ(f->ids.front(), 0);
    EXPECT_EQ(f->ids.back(), 65);
    EXPECT_EQ(f->radius.front(), 0.05f);
    EXPECT_EQ(f->attributeNames(),
              (std::vector<std::string>{"Velocity_x", "Velocity_y", "Velocity_z", "speciesType"}));
    EXPECT_EQ(f->x.front(), -0.0606374f);
    EXPECT_EQ(f->z.front(), 0.0676553f);
    EXPECT_EQ(f->x.back(), 1.08858f);
    EXPECT_EQ(f->y.back(), -0.0335996f);
    EXPECT_EQ(xmlColumn(*f, "Velocity_z").floats.front(), 0.0483901f);
    EXPECT_EQ(xmlColumn(*f, "Velocity_x").floats.back(), 0.0804779f);
    EXPECT_FALSE(xmlColumn(*f, "speciesType").isInteger()); // declared Float32
}

TEST(VtkXml, CowHeadInlineBase64PolyData) {
    auto ds = Dataset::open(
        {std::string(FAULTLINE_TEST_DATA) + "/vtkdata_cowHead_inline_base64_uncompressed.vtp"});
    const auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 4074u);
    EXPECT_TRUE(f->idsAreRowNumbers);
    EXPECT_TRUE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(), (std::vector<std::string>{"Gauss_Curvature"}));
    EXPECT_EQ(f->x.front(), 3.238943099975586f);
    EXPECT_EQ(f->y.front(), 2.0651047229766846f);
    EXPECT_EQ(f->z.back(), 1.3911586999893188f);
    const AttributeColumn& g = xmlColumn(*f, "Gauss_Curvature");
    EXPECT_EQ(g.floats.front(), static_cast<float>(-0.8535541913109399));
    EXPECT_EQ(g.floats.back(), static_cast<float>(72.99596859623286));
    EXPECT_EQ(g.min, static_cast<double>(static_cast<float>(-219.99439028280585)));
    EXPECT_EQ(g.max, static_cast<double>(static_cast<float>(666.9499004962549)));
}

// VTK's other compressors, written by ParaView 5.11's own VTK (tests/data/scripts/
// paraview511_compressed_vtk_xml.py): LZ4 and LZMA, appended raw and inline base64, UInt32 and
// UInt64 headers, 64-byte blocks so each array spans several. 20 particles on a 5 x 4 grid.
TEST(VtkXml, ParaViewLz4AndLzmaCompressedFilesReadExactly) {
    for (const char* name :
         {"paraview511_lz4_appended.vtu", "paraview511_lzma_appended.vtu",
          "paraview511_lz4_inline_base64.vtp", "paraview511_lzma_inline_base64_uint64.vtp"}) {
        SCOPED_TRACE(name);
        auto ds = Dataset::open({std::string(FAULTLINE_TEST_DATA) + "/" + name});
        ASSERT_EQ(ds->frameCount(), 1u);
        const auto f = ds->frame(0);
        ASSERT_EQ(f->size(), 20u);
        EXPECT_FALSE(f->idsAreRowNumbers);
        EXPECT_FALSE(f->radiusIsDefault);
        EXPECT_EQ(f->attributeNames(), (std::vector<std::string>{"strain"}));
        const AttributeColumn& strain = xmlColumn(*f, "strain");
        for (std::size_t k = 0; k < 20; ++k) {
            const std::size_t i = k % 5, j = k / 5;
            EXPECT_EQ(f->ids[k], std::int64_t(1000 + k));
            EXPECT_EQ(f->x[k], float(0.5 * double(i)));
            EXPECT_EQ(f->y[k], float(0.25 * double(j)));
            EXPECT_EQ(f->z[k], float(0.125 * double(k)));
            EXPECT_EQ(f->radius[k], float(0.1 + 0.01 * double(k)));
            EXPECT_EQ(strain.floats[k], float(double(k) / 19.0));
        }
    }
}

// Hostile LZ4 and LZMA payloads: every truncation and byte change of the ParaView files gives an
// InputError (never a crash or an unbounded allocation); a flipped compressed byte is named as
// a corrupt block of that codec.
TEST(VtkXml, CorruptLz4AndLzmaBlocksAreInputErrors) {
    for (const char* name : {"paraview511_lz4_appended.vtu", "paraview511_lzma_appended.vtu"}) {
        SCOPED_TRACE(name);
        std::ifstream in(std::string(FAULTLINE_TEST_DATA) + "/" + name, std::ios::binary);
        const std::string good((std::istreambuf_iterator<char>(in)), {});
        const std::size_t data = good.find("_", good.find("<AppendedData")) + 1;
        ASSERT_NE(data, std::string::npos);
        for (std::size_t n = data; n < good.size(); n += 7)
            try {
                parseVtkXml(name, good.substr(0, n));
            } catch (const InputError&) {
            }
        // Every byte; under TSan every fifth (common/sanitizers.hpp).
        const std::size_t step = faultline::test::kUnderThreadSanitizer ? 5 : 1;
        for (std::size_t i = data; i < good.size(); i += step)
            for (char c : {'\0', '\xff', '\x7f'}) {
                std::string bad = good;
                bad[i] = c;
                try {
                    parseVtkXml(name, bad);
                } catch (const InputError&) {
                }
            }
        // The first array (20 Int64 = 160 bytes in 64-byte blocks) has a header of 6 UInt32s:
        // blocks, block size, last size, 3 sizes; its first block follows. LZ4 has no checksum,
        // so its first token is broken (a literal run past the block's end); xz checks a CRC.
        const bool lz4 = std::string(name).find("lz4") != std::string::npos;
        std::string bad = good;
        const std::size_t at = data + 24 + (lz4 ? 0 : 30);
        bad[at] = char(bad[at] ^ (lz4 ? 0xf0 : 0x5a));
        try {
            parseVtkXml(name, bad);
            ADD_FAILURE() << "a corrupted block was accepted";
        } catch (const InputError& e) {
            const std::string codec = lz4 ? "LZ4" : "LZMA";
            EXPECT_NE(std::string(e.what()).find(codec + " block"), std::string::npos) << e.what();
        }
    }
}
#endif
