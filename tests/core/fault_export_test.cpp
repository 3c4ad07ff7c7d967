#include "core/faults/fault_export.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace faultline::core;

namespace {
constexpr double kNaNDouble = std::numeric_limits<double>::quiet_NaN();

FaultMetricsSeries tinySeries() {
    FaultMetricsSeries s;
    s.frameCount = 1;
    s.faultCount = 2;
    FaultFrameMetrics a;
    a.frame = 0;
    a.fault = 0;
    a.name = "F1";
    a.count = 12;
    a.dip = 30;
    a.dipDirection = 90.5;
    a.strike = 0.5;
    a.thickness = 2.25;
    a.area = 100;
    a.length = 12.5;
    a.height = 8;
    a.throwStatus = ThrowStatus::Ok;
    a.throwVertical = -0.125;
    a.netSlip = 0.25;
    a.dipSlip = 0.25;
    a.strikeSlip = 0;
    a.hangingWallSamples = 40;
    a.footwallSamples = 41;
    a.centroid = {1, 2, 3};
    a.min = {0, 0, 0};
    a.max = {2, 4, 6};
    a.normal = {0.5, 0, 0.75};
    a.eigenvalues = {0.1, 2, 3};
    a.meanRadius = 0.5;
    a.broken = 3;
    FaultFrameMetrics b;
    b.frame = 0;
    b.fault = 1;
    b.name = "odd, \"name\"";
    b.count = 0;
    b.dip = b.dipDirection = b.strike = b.thickness = b.area = b.length = b.height = kNaNDouble;
    b.throwStatus = ThrowStatus::NoPlane;
    b.throwVertical = b.netSlip = b.dipSlip = b.strikeSlip = kNaNDouble;
    b.centroid = b.min = b.max = b.normal = b.eigenvalues = {kNaNDouble, kNaNDouble, kNaNDouble};
    b.meanRadius = kNaNDouble;
    s.rows = {a, b};
    s.seeds = {FaultSeed{true, 0, 3, {1.5, 2, 1e-7}}, FaultSeed{}};
    return s;
}
} // namespace

TEST(FaultExport, FaultsCsvHasARowPerMember) {
    Fault a, b;
    a.name = "F1";
    a.add({3, 1});
    b.name = "x,y";
    b.add({2});
    EXPECT_EQ(faultsCsv(std::vector<Fault>{a, b}), "id,fault\n1,F1\n3,F1\n2,\"x,y\"\n");
    EXPECT_EQ(faultsCsv(std::vector<Fault>{}), "id,fault\n");
}

TEST(FaultExport, MetricsCsvIsExact) {
    const std::string csv = faultMetricsCsv(tinySeries());
    const std::string expected =
        faultMetricsCsvHeader() + "\n" +
        "0,F1,12,30,90.5,0.5,2.25,100,-0.125,0.25,0.25,0,ok,40,41,1,2,3,0,0,0,2,4,6,0.5,0,0.75,"
        "0.1,2,3,0.5,3,0,1.5,2,1e-07,12.5,8\n"
        "0,\"odd, \"\"name\"\"\",0,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,no_plane,0,0,NaN,NaN,NaN,"
        "NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,NaN,0,,NaN,NaN,NaN,NaN,NaN\n";
    EXPECT_EQ(csv, expected);
    EXPECT_EQ(faultMetricsCsvHeader().rfind("frame,fault,count,dip,dip_direction,", 0), 0u);
}

TEST(FaultExport, MetricsJsonUsesNullForUndefined) {
    const nlohmann::json j = faultMetricsJson(tinySeries());
    EXPECT_EQ(j["frames"], 1);
    ASSERT_EQ(j["faults"].size(), 2u);
    EXPECT_EQ(j["faults"][0]["name"], "F1");
    EXPECT_EQ(j["faults"][0]["seed"]["frame"], 0);
    EXPECT_EQ(j["faults"][0]["frames"][0]["dip_direction"], 90.5);
    EXPECT_EQ(j["faults"][0]["frames"][0]["throw_status"], "ok");
    EXPECT_TRUE(j["faults"][1]["seed"].is_null());
    EXPECT_TRUE(j["faults"][1]["frames"][0]["dip"].is_null());
    EXPECT_TRUE(j["faults"][1]["frames"][0]["centroid"][0].is_null());
}

TEST(FaultExport, TracksJson) {
    Fault f;
    f.name = "F";
    FaultTrack t;
    FaultTrackPoint p;
    p.frame = 2;
    p.match.present = 4;
    p.match.candidate = 1;
    p.match.shared = 3;
    t.points.push_back(p);
    const nlohmann::json j = faultTracksJson(std::vector<Fault>{f}, std::vector<FaultTrack>{t});
    EXPECT_EQ(j[0]["name"], "F");
    EXPECT_EQ(j[0]["frames"][0]["frame"], 2);
    EXPECT_EQ(j[0]["frames"][0]["candidate"], 1);
    EXPECT_EQ(j[0]["frames"][0]["shared"], 3);
}
