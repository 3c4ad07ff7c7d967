#include "core/data/dataset.hpp"
#include "core/io/frame_source.hpp"
#include "core/io/input_error.hpp"
#include "core/io/vtk_legacy.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

using namespace faultline::core;

namespace {

const std::string kPath = "synthetic.vtk";

template <typename T> std::string bigEndian(T value) {
    std::string s(sizeof(T), '\0');
    std::memcpy(s.data(), &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::little)
        std::reverse(s.begin(), s.end());
    return s;
}
template <typename T> std::string bigEndian(std::initializer_list<T> values) {
    std::string s;
    for (T v : values)
        s += bigEndian(v);
    return s;
}

// Parses and returns the InputError it must throw.
InputError legacyErrorOf(const std::string& bytes) {
    try {
        parseVtkLegacy(kPath, bytes);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "expected an InputError for:\n" << bytes.substr(0, 300);
    return InputError(kPath, "none");
}

void expectError(const std::string& bytes, InputError::Where where, std::uint64_t position,
                 const std::string& needle) {
    const InputError e = legacyErrorOf(bytes);
    EXPECT_EQ(e.path(), kPath);
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_EQ(e.position(), position) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << needle;
}

const AttributeColumn& legacyColumn(const Frame& f, const std::string& name) {
    const AttributeColumn* c = f.attribute(name);
    if (!c)
        throw std::runtime_error("no column " + name);
    return *c;
}

// Every prefix and many one-byte corruptions must read or fail with an InputError, no other way.
void expectOnlyInputErrors(const std::string& good) {
    for (std::size_t n = 0; n < good.size(); ++n) {
        try {
            parseVtkLegacy(kPath, good.substr(0, n));
        } catch (const InputError&) {
        }
    }
    for (std::size_t i = 0; i < good.size(); ++i) {
        for (char c : {'x', '\0', '9', '\n', '-', '\xff'}) {
            std::string bad = good;
            bad[i] = c;
            try {
                parseVtkLegacy(kPath, bad);
            } catch (const InputError&) {
            }
        }
    }
}

const std::string kAsciiPolydata = "# vtk DataFile Version 3.0\n"
                                   "spheres written by hand\n"
                                   "ASCII\n"
                                   "DATASET POLYDATA\n"
                                   "FIELD FieldData 1\n"
                                   "TIME 1 1 double\n"
                                   "0.25\n"
                                   "POINTS 3 float\n"
                                   "0 0 0  1 2 3\n"
                                   "-1.5 2.5e1 7\n"
                                   "VERTICES 3 6\n"
                                   "1 0 1 1 1 2\n"
                                   "CELL_DATA 3\n"
                                   "SCALARS cellvalue float 1\n"
                                   "LOOKUP_TABLE default\n"
                                   "9 9 9\n"
                                   "POINT_DATA 3\n"
                                   "SCALARS radius double\n"
                                   "LOOKUP_TABLE default\n"
                                   "0.5 0.25 0.125\n"
                                   "SCALARS id int 1\n"
                                   "LOOKUP_TABLE default\n"
                                   "10 20 30\n"
                                   "VECTORS velocity float\n"
                                   "1 2 3 4 5 6 7 8 9\n"
                                   "LOOKUP_TABLE mytable 2\n"
                                   "0 0 0 1 1 1 1 1\n"
                                   "FIELD FieldData 2\n"
                                   "layer 1 3 int\n"
                                   "1 2 3\n"
                                   "stress%20xy 2 3 double\n"
                                   "0.1 0.2 0.3 0.4 0.5 0.6\n";

std::string binaryUnstructured() {
    std::string s = "# vtk DataFile Version 3.0\nbinary test\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
    s += "POINTS 3 double\n" + bigEndian<double>({1, 2, 3, -4, -5, -6, 0.5, 0.25, 1e6}) + "\n";
    s += "CELLS 3 6\n" + bigEndian<std::int32_t>({1, 0, 1, 1, 1, 2}) + "\n";
    s += "CELL_TYPES 3\n" + bigEndian<std::int32_t>({1, 1, 1}) + "\n";
    // Cell values that are blank bytes (newline, space) right after the header line.
    s += "CELL_DATA 3\nSCALARS c unsigned_char\nLOOKUP_TABLE default\n";
    s += std::string("\n \t", 3) + "\n";
    s += "POINT_DATA 3\nSCALARS radius float\nLOOKUP_TABLE default\n" +
         bigEndian<float>({0.5f, 1.5f, 2.5f}) + "\n";
    s += "FIELD FieldData 2\nid 1 3 vtktypeint64\n" +
         bigEndian<std::int64_t>({5000000000LL, 7, -3}) + "\n";
    s += "flag 1 3 unsigned_char\n" + std::string("\x01\x00\xff", 3) + "\n";
    s += "NORMALS n float\n" + bigEndian<float>({1, 0, 0, 0, 1, 0, 0, 0, -1}) + "\n";
    return s;
}

std::string binaryPolydata51() {
    std::string s = "# vtk DataFile Version 5.1\nvtk output\nBINARY\nDATASET POLYDATA\n";
    s += "POINTS 2 float\n" + bigEndian<float>({0.125f, 0.25f, 0.5f, 8, 16, 32}) + "\n";
    s += "VERTICES 3 2\nOFFSETS vtktypeint64\n" + bigEndian<std::int64_t>({0, 1, 2}) +
         "\nCONNECTIVITY vtktypeint64\n" + bigEndian<std::int64_t>({0, 1}) + "\n";
    s += "POINT_DATA 2\nSCALARS rad float 1\nLOOKUP_TABLE default\n" +
         bigEndian<float>({0.75f, 1.25f}) + "\n";
    s +=
        "SCALARS count short 1\nLOOKUP_TABLE default\n" + bigEndian<std::int16_t>({-2, 300}) + "\n";
    return s;
}

} // namespace

TEST(VtkLegacy, DetectsByContent) {
    EXPECT_TRUE(looksLikeVtkLegacy("# vtk DataFile Version 2.0\n"));
    EXPECT_TRUE(looksLikeVtkLegacy("\xEF\xBB\xBF# vtk DataFile Version 2.0\n"));
    EXPECT_FALSE(looksLikeVtkLegacy("ITEM: TIMESTEP\n"));
    EXPECT_FALSE(looksLikeVtkLegacy("<VTKFile"));
}

TEST(VtkLegacy, AsciiPolydataWithScalarsVectorsAndFields) {
    const Frame f = parseVtkLegacy(kPath, kAsciiPolydata);
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f.x, (std::vector<float>{0, 1, -1.5f}));
    EXPECT_EQ(f.y, (std::vector<float>{0, 2, 25}));
    EXPECT_EQ(f.z, (std::vector<float>{0, 3, 7}));
    EXPECT_EQ(f.radius, (std::vector<float>{0.5f, 0.25f, 0.125f}));
    EXPECT_FALSE(f.radiusIsDefault);
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{10, 20, 30}));
    EXPECT_FALSE(f.idsAreRowNumbers);
    EXPECT_EQ(f.attributeNames(),
              (std::vector<std::string>{"velocity_x", "velocity_y", "velocity_z", "layer",
                                        "stress xy_0", "stress xy_1"}));
    EXPECT_EQ(legacyColumn(f, "velocity_y").floats, (std::vector<float>{2, 5, 8}));
    EXPECT_FALSE(legacyColumn(f, "velocity_y").isInteger());
    EXPECT_TRUE(legacyColumn(f, "layer").isInteger());
    EXPECT_EQ(legacyColumn(f, "layer").ints, (std::vector<std::int32_t>{1, 2, 3}));
    EXPECT_EQ(legacyColumn(f, "stress xy_1").floats, (std::vector<float>{0.2f, 0.4f, 0.6f}));
    EXPECT_EQ(f.rowOf(20), 1u);
}

TEST(VtkLegacy, Version51CellsMetadataDiameterAndTensors) {
    const std::string text = "# vtk DataFile Version 5.1\n"
                             "vtk output\n"
                             "ASCII\n"
                             "DATASET UNSTRUCTURED_GRID\n"
                             "POINTS 2 double\n"
                             "0 0 0 1 1 1\n"
                             "METADATA\n"
                             "INFORMATION 1\n"
                             "NAME L2_NORM_RANGE LOCATION vtkDataArray\n"
                             "DATA 2 0 1.73205\n"
                             "\n"
                             "CELLS 3 2\n"
                             "OFFSETS vtktypeint64\n"
                             "0 1 2\n"
                             "CONNECTIVITY vtktypeint64\n"
                             "0 1\n"
                             "CELL_TYPES 2\n"
                             "1\n"
                             "1\n"
                             "\n"
                             "CELL_DATA 2\n"
                             "FIELD FieldData 1\n"
                             "cellid 1 2 vtktypeint64\n"
                             "0 1\n"
                             "POINT_DATA 2\n"
                             "SCALARS Diameter float\n"
                             "LOOKUP_TABLE default\n"
                             "1 3\n"
                             "TENSORS stress double\n"
                             "1 2 3 4 5 6 7 8 9\n"
                             "9 8 7 6 5 4 3 2 1\n"
                             "FIELD FieldData 1\n"
                             "mass 1 2 double\n"
                             "2.5 3.5\n"
                             "METADATA\n"
                             "INFORMATION 1\n"
                             "NAME L2_NORM_RANGE LOCATION vtkDataArray\n"
                             "DATA 2 2.5 3.5\n"
                             "\n";
    const Frame f = parseVtkLegacy(kPath, text);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.radius, (std::vector<float>{0.5f, 1.5f}));
    EXPECT_TRUE(f.idsAreRowNumbers);
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{0, 1}));
    ASSERT_EQ(f.attributes.size(), 10u);
    EXPECT_EQ(f.attributes[0].name, "stress_0");
    EXPECT_EQ(f.attributes[8].name, "stress_8");
    EXPECT_EQ(legacyColumn(f, "stress_8").floats, (std::vector<float>{9, 1}));
    EXPECT_EQ(legacyColumn(f, "mass").floats, (std::vector<float>{2.5f, 3.5f}));
}

TEST(VtkLegacy, NoRadiusNoIdGivesDefaultsAndFloatIdsAreIds) {
    const std::string plain = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET POLYDATA\n"
                              "POINTS 2 float\n1 2 3 4 5 6\n";
    const Frame f = parseVtkLegacy(kPath, plain);
    EXPECT_TRUE(f.radiusIsDefault);
    EXPECT_EQ(f.radius, (std::vector<float>{kDefaultRadius, kDefaultRadius}));
    EXPECT_TRUE(f.idsAreRowNumbers);
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{0, 1}));
    EXPECT_TRUE(f.attributes.empty());

    // Yade's VTKRecorder writes ids as doubles and the radius as "radii".
    const Frame g =
        parseVtkLegacy(kPath, plain + "POINT_DATA 2\nSCALARS id double 1\n"
                                      "LOOKUP_TABLE default\n4 9\n"
                                      "SCALARS radii double 1\nLOOKUP_TABLE default\n0.5 0.75\n");
    EXPECT_EQ(g.ids, (std::vector<std::int64_t>{4, 9}));
    EXPECT_EQ(g.radius, (std::vector<float>{0.5f, 0.75f}));
    EXPECT_TRUE(g.attributes.empty());
}

TEST(VtkLegacy, BinaryBigEndianUnstructuredGrid) {
    const Frame f = parseVtkLegacy(kPath, binaryUnstructured());
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f.x, (std::vector<float>{1, -4, 0.5f}));
    EXPECT_EQ(f.y, (std::vector<float>{2, -5, 0.25f}));
    EXPECT_EQ(f.z, (std::vector<float>{3, -6, 1e6f}));
    EXPECT_EQ(f.radius, (std::vector<float>{0.5f, 1.5f, 2.5f}));
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{5000000000LL, 7, -3}));
    EXPECT_EQ(f.attributeNames(), (std::vector<std::string>{"flag", "n_x", "n_y", "n_z"}));
    EXPECT_EQ(legacyColumn(f, "flag").ints, (std::vector<std::int32_t>{1, 0, 255}));
    EXPECT_EQ(legacyColumn(f, "n_z").floats, (std::vector<float>{0, 0, -1}));
}

TEST(VtkLegacy, BinaryVersion51OffsetsConnectivity) {
    const Frame f = parseVtkLegacy(kPath, binaryPolydata51());
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.x, (std::vector<float>{0.125f, 8}));
    EXPECT_EQ(f.z, (std::vector<float>{0.5f, 32}));
    EXPECT_EQ(f.radius, (std::vector<float>{0.75f, 1.25f}));
    EXPECT_EQ(legacyColumn(f, "count").ints, (std::vector<std::int32_t>{-2, 300}));
}

TEST(VtkLegacy, MalformedTextNamesLineAndExpectation) {
    using W = InputError::Where;
    const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n";
    expectError("", W::Line, 1, "# vtk DataFile Version");
    expectError("# vtk DataFile Version x\n", W::Line, 1, "version number");
    expectError("# vtk DataFile Version 3.0\nt\nTEXT\n", W::Line, 3, "expected ASCII or BINARY");
    expectError("# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n", W::Line, 4,
                "expected POLYDATA or UNSTRUCTURED_GRID");
    expectError(head, W::Line, 5, "no POINTS section");
    expectError(head + "POINTS 3 float\n0 0 0\n1 1 1\n", W::Line, 5, "9 values declared");
    expectError(head + "POINTS 3 float\n0 0 0\n1 1 1\n2 2 2 2 2 2\n", W::Line, 8,
                "unknown keyword '2' (more values than the section declared?)");
    expectError(head + "POINTS 2 float\n0 0 0\n1 oops 1\n", W::Line, 7,
                "POINTS: value 5 of 6: expected a number, found 'oops'");
    expectError(head + "POINTS 2 float\n0 0 0\n1 1 nan\n", W::Line, 7, "expected a finite number");
    expectError(head + "POINTS 2 double\n0 0 0\n1 1e300 1\n", W::Line, 7,
                "expected a finite number");
    expectError(head + "POINTS 2 float\n0 0 0\n\n\n1 1 inf\n", W::Line, 9, "found 'inf'");
    expectError(head + "POINTS 1000000000000 float\n0 0 0\n", W::Line, 5, "4 billion");
    expectError(head + "POINTS 100000000 float\n0 0 0\n", W::Line, 5,
                "300000000 values declared (at least 599999999 characters), only 6 bytes remain");
    expectError(head + "POINTS 1 float\n0 0 0\nPOINTS 1 float\n0 0 0\n", W::Line, 7,
                "a second POINTS section");
    expectError(head + "POINTS -1 float\n", W::Line, 5, "expected a point count");
    expectError(head + "POINTS 1 float3\n0 0 0\n", W::Line, 5, "expected a data type");
    expectError(head + "POINTS 1 float\n0 0 0\nPOINT_DATA 2\n", W::Line, 7,
                "POINT_DATA 2 does not match POINTS 1");
    expectError(head + "POINT_DATA 1\n", W::Line, 5, "POINT_DATA before POINTS");
    expectError(head + "POINTS 1 float\n0 0 0\nBANANAS 3\n", W::Line, 7,
                "unknown keyword 'BANANAS'");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS n int\n1 2.5\n", W::Line,
                9, "expected an integer, found '2.5'");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS n float 100000\n1 2\n",
                W::Line, 8, "expected 1 to 256 components");
    expectError(head +
                    "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nFIELD f 1\nname 1 3 float\n1 2 3\n",
                W::Line, 9, "has 3 tuples, expected one per point (2)");
    expectError(head +
                    "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nFIELD f 2\nname 1 2 float\n1 2\n",
                W::Line, 11, "expected 2 arrays, found 1");
    expectError(head +
                    "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nFIELD f 1\nname 1 2 string\na b\n",
                W::Line, 9, "string arrays are not supported");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nLINES 1 3\n2 0\nPOINT_DATA 2\n", W::Line, 9,
                "LINES: value 3 of 3: expected a number, found 'POINT_DATA'");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS id int\n4 4\n", W::Line,
                8, "particle id 4 appears twice");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS radius float\n1 nan\n",
                W::Line, 8, "radius array 'radius': value 2 is not a finite number");
    expectError(head + "POINTS 2 float\n0 0 0 1 1 1\nPOINT_DATA 2\nSCALARS a float\n1 2\nSCALARS a "
                       "float\n1 2\n",
                W::Line, 10, "column 'a' appears twice");
}

TEST(VtkLegacy, ArraysWithoutDataAreStillBounded) {
    // With zero points an array costs a line: the number of arrays is bounded instead.
    std::string text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n"
                       "POINT_DATA 0\n";
    for (int i = 0; i < 5000; ++i)
        text += "SCALARS a" + std::to_string(i) + " float 256\n";
    expectError(text, InputError::Where::Line, 4103, "more than 4096 point arrays");
    text.resize(text.find("SCALARS a20 "));
    expectError(text, InputError::Where::Line, 23, "more than 4096 attribute columns");
}

TEST(VtkLegacy, MalformedBinaryNamesByteOffset) {
    using W = InputError::Where;
    const std::string head =
        "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET POLYDATA\nPOINTS 2 float\n";
    const std::uint64_t data = head.size();
    // Truncated point data: refused before anything is read.
    expectError(head + bigEndian<float>({1, 2, 3}), W::Byte, data,
                "6 values declared (24 bytes), only 12 bytes remain");
    // An infinite coordinate: the offset of that value.
    expectError(head + bigEndian<float>({1, 2, 3, 4, std::numeric_limits<float>::infinity(), 6}) +
                    "\n",
                W::Byte, data + 16, "POINTS: value 5 is not a finite number");
    // Binary garbage where a keyword should be.
    const std::string points = head + bigEndian<float>({1, 2, 3, 4, 5, 6}) + "\n";
    expectError(points + std::string("\x01\x02\xfe\x00garbage", 11), W::Byte, points.size(),
                "unknown keyword");
    // A count of 10^12 cells.
    expectError(points + "LINES 1 1000000000000\n", W::Byte, points.size() + 22,
                "1000000000000 values declared");
    // Scalars cut short.
    expectError(points + "POINT_DATA 2\nSCALARS s double\nLOOKUP_TABLE default\n" +
                    bigEndian<double>(1.0),
                W::Byte, points.size() + 51, "2 values declared (16 bytes), only 8 bytes remain");
}

TEST(VtkLegacy, TruncatedOrCorruptedFilesOnlyEverGiveInputErrors) {
    expectOnlyInputErrors(kAsciiPolydata);
    expectOnlyInputErrors(binaryUnstructured());
    expectOnlyInputErrors(binaryPolydata51());
}

TEST(VtkLegacy, OpensThroughDatasetByContent) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "faultline_vtk_legacy_dataset";
    std::filesystem::create_directories(dir);
    const auto file = dir / "spheres.data"; // the extension says nothing: content decides
    std::ofstream(file, std::ios::binary) << binaryUnstructured();
    auto ds = Dataset::open({file.string()});
    ASSERT_EQ(ds->frameCount(), 1u);
    EXPECT_EQ(ds->location(0).format, FileFormat::VtkLegacy);
    EXPECT_EQ(ds->frame(0)->size(), 3u);
    std::filesystem::remove_all(dir);
}

#ifdef FAULTLINE_TEST_DATA
TEST(VtkLegacy, LiggghtsCustomVtk51FieldData) {
    const std::string path =
        std::string(FAULTLINE_TEST_DATA) + "/liggghts_customvtk_v51_fielddata_cohesion_49600.vtk";
    auto ds = Dataset::open({path});
    ASSERT_EQ(ds->frameCount(), 1u);
    const auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 1000u);
    EXPECT_FALSE(f->idsAreRowNumbers);
    EXPECT_FALSE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(),
              (std::vector<std::string>{"type", "i_x", "i_y", "i_z", "v_x", "v_y", "v_z", "f_x",
                                        "f_y", "f_z", "omega_x", "omega_y", "omega_z"}));
    // First and last values as written in the file.
    EXPECT_EQ(f->ids.front(), 83);
    EXPECT_EQ(f->ids.back(), 864);
    EXPECT_EQ(f->x.front(), -0.012093f);
    EXPECT_EQ(f->y.front(), -0.0166414f);
    EXPECT_EQ(f->z.front(), 0.00149437f);
    EXPECT_EQ(f->z.back(), 0.0161207f);
    EXPECT_EQ(f->radius.front(), 0.0015f);
    EXPECT_EQ(f->radius.back(), 0.0015f);
    EXPECT_TRUE(legacyColumn(*f, "type").isInteger());
    EXPECT_EQ(legacyColumn(*f, "type").min, 1.0);
    EXPECT_EQ(legacyColumn(*f, "v_x").floats.front(), -0.0072785979766f);
    EXPECT_EQ(legacyColumn(*f, "omega_z").floats.back(), 0.41025595512f);
    EXPECT_EQ(f->rowOf(83), 0u);
}

TEST(VtkLegacy, BinaryBigEndianTrackWithCellDataBeforePointData) {
    const std::string path =
        std::string(FAULTLINE_TEST_DATA) + "/vtkdata_track1_binary_BE_polydata.vtk";
    auto ds = Dataset::open({path});
    const auto f = ds->frame(0);
    ASSERT_EQ(f->size(), 16267u);
    EXPECT_TRUE(f->idsAreRowNumbers);
    EXPECT_TRUE(f->radiusIsDefault);
    EXPECT_EQ(f->attributeNames(), (std::vector<std::string>{"scalars"}));
    EXPECT_EQ(f->x[0], 0.01f);
    EXPECT_EQ(f->y[0], 0.07f);
    EXPECT_EQ(f->z[0], 1470.0f);
    EXPECT_EQ(f->z[1], 1470.5f);
    EXPECT_EQ(f->x.back(), -1890.31f);
    EXPECT_EQ(f->z.back(), 9602.97f);
    const AttributeColumn& s = legacyColumn(*f, "scalars");
    EXPECT_EQ(s.floats[0], 0.3f);
    EXPECT_EQ(s.floats[3], 2.0f);
    EXPECT_EQ(s.floats.back(), 2.4f);
    EXPECT_EQ(s.min, static_cast<double>(0.1f));
    EXPECT_EQ(s.max, static_cast<double>(36.1f));
}
#endif

// Issue 37: LIGGGHTS' dump custom/vtk writes run_boundingBox_N.vtk (a RECTILINEAR_GRID) beside
// each run_N.vtk; the pattern run_*.vtk is the frames alone, and files holding no time take the
// number in their names as their timesteps.
TEST(VtkLegacy, ASeriesSkipsBoundingBoxesAndTakesTimestepsFromNames) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("faultline-vtk-series-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string frame = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET POLYDATA\n"
                              "POINTS 2 float\n1 2 3 4 5 6\n";
    // Each step's box a little wider (the walls of a LIGGGHTS run move); the box of step 2000
    // is missing.
    auto box = [](int step) {
        const std::string hi = std::to_string(10 + step / 500);
        return "# vtk DataFile Version 2.0\nGenerated by LIGGGHTS\nASCII\n"
               "DATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\n"
               "X_COORDINATES 2 float\n-1 +" +
               hi + "\nY_COORDINATES 2 float\n-2 " + hi + "\nZ_COORDINATES 2 float\n-3\n" + hi +
               "\n";
    };
    for (int step : {1000, 2000, 500}) {
        std::ofstream(dir / ("run_" + std::to_string(step) + ".vtk")) << frame;
        if (step != 2000)
            std::ofstream(dir / ("run_boundingBox_" + std::to_string(step) + ".vtk")) << box(step);
    }
    auto ds = Dataset::open({(dir / "run_*.vtk").string()});
    ASSERT_EQ(ds->frameCount(), 3u);
    EXPECT_EQ(ds->location(0).timestep, 500);
    EXPECT_EQ(ds->location(1).timestep, 1000);
    EXPECT_EQ(ds->location(2).timestep, 2000);
    EXPECT_EQ(ds->frame(2)->size(), 2u);
    // Each frame's box is its bounding box file's; without one, the centres' bounds.
    for (int k : {0, 1}) {
        const SimulationBox& b = ds->frame(std::size_t(k))->box;
        EXPECT_TRUE(b.known);
        EXPECT_EQ(b.lo, (std::array<double, 3>{-1, -2, -3}));
        const double hi = 10 + (k + 1);
        EXPECT_EQ(b.hi, (std::array<double, 3>{hi, hi, hi}));
        EXPECT_EQ(b.periodic, (std::array<bool, 3>{false, false, false}));
    }
    EXPECT_FALSE(ds->frame(2)->box.known);
    EXPECT_EQ(ds->frame(2)->box.hi[2], 6.0);
    // A box file that is no box: the frame's error names the file, the line and what was
    // expected, and nothing crashes.
    const std::pair<const char*, const char*> broken[] = {
        {"# vtk DataFile Version 2.0\nt\nASCII\nDATASET RECTILINEAR_GRID\nX_COORDINATES 2 "
         "float\n0 oops\n",
         ":6: expected a coordinate, found 'oops'"},
        {"# vtk DataFile Version 2.0\nt\nASCII\nDATASET RECTILINEAR_GRID\nX_COORDINATES "
         "99999999999 float\n0 1\n",
         ":5: expected X_COORDINATES <count> <type> and that many numbers"},
        {"# vtk DataFile Version 2.0\nt\nASCII\nDATASET RECTILINEAR_GRID\nX_COORDINATES 2 "
         "float\n0 1\nY_COORDINATES 1 float\n0\n",
         ": no Z_COORDINATES: expected all three"},
        {"# vtk DataFile Version 2.0\nt\nBINARY\nDATASET RECTILINEAR_GRID\n", ":3: expected ASCII"},
    };
    for (const auto& [text, expected] : broken) {
        std::ofstream(dir / "run_boundingBox_500.vtk") << text;
        auto again = Dataset::open({(dir / "run_*.vtk").string()});
        try {
            again->frame(0);
            ADD_FAILURE() << "read a broken box: " << text;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("run_boundingBox_500.vtk" + std::string(expected)),
                      std::string::npos)
                << e.what();
        }
    }
    // Only boxes: said so.
    try {
        Dataset::open({(dir / "run_boundingBox_*.vtk").string()});
        ADD_FAILURE() << "opened boxes as frames";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("RECTILINEAR_GRID"), std::string::npos) << e.what();
    }
    EXPECT_EQ(numberInFileName("a/b/spheres.0012.vtu"), 12);
    EXPECT_EQ(numberInFileName("t_5.csv.gz"), 5);
    EXPECT_EQ(numberInFileName("liggghts_customvtk_v51_fielddata_cohesion_49600.vtk"), 49600);
    EXPECT_EQ(numberInFileName("plain.vtk"), std::nullopt);
    std::filesystem::remove_all(dir);
}
