// Issue 22: no undefined behaviour for any value a file can hold. Every place that turns a
// coordinate, distance, time or count held in a double into an integer is fed the extremes
// (±1e300, ±inf, NaN, 2^63) here; the sanitizer stage of the test command runs these tests
// with UndefinedBehaviorSanitizer, which aborts on any overflowing conversion. And the
// readers refuse the values no map or run can mean, naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "batch/logical_scenario.hpp"
#include "batch/progress.hpp"
#include "batch/sampler.hpp"
#include "core/checked_numeric.hpp"
#include "core/errors.hpp"
#include "core/plausible.hpp"
#include "core/polyline.hpp"
#include "opendrive/xodr_reader.hpp"
#include "scenario_executor/loader_internal.hpp"
#include "test_loader_support.hpp"

using namespace orch;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoTo63 = 9223372036854775808.0;
const double kExtremes[] = {1e300, -1e300, kInf, -kInf, kNaN, kTwoTo63, -kTwoTo63};

}  // namespace

TEST(CheckedNumeric, FloorToIntegerRefusesWhatDoesNotFit) {
  EXPECT_EQ(floor_to_integer(-2.5), -3);
  EXPECT_EQ(floor_to_integer(kExactIntegerLimit), 9007199254740992LL);
  for (const double v : kExtremes) EXPECT_FALSE(floor_to_integer(v).has_value()) << v;
}

TEST(CheckedNumeric, ClampedConversionsStayInTheirRange) {
  EXPECT_EQ(clamped_floor<int>(2.7, 0, 10), 2);
  EXPECT_EQ(clamped_ceil<int>(2.1, 0, 10), 3);
  EXPECT_EQ(clamped_round<long>(-2.5, -10, 10), -3);
  EXPECT_EQ(clamped_round<long long>(1e300, 0, 1LL << 40), 1LL << 40);
  EXPECT_EQ(clamped_round<long long>(-kInf, 0, 1LL << 40), 0);
  EXPECT_EQ(clamped_round<long long>(kNaN, 5, 9), 5);
  // The largest long long is not a double: 2^63 must clamp, not convert.
  EXPECT_EQ(clamped_floor<long long>(kTwoTo63, 0, std::numeric_limits<long long>::max()),
            std::numeric_limits<long long>::max());
  EXPECT_EQ(clamped_floor<std::uint64_t>(-kTwoTo63, 0, 100), 0u);
}

TEST(CheckedNumeric, PiecesCoveringIsBoundedForAnyLength) {
  EXPECT_EQ(pieces_covering(10.0, 2.0, 1, 100), 5);
  EXPECT_EQ(pieces_covering(0.0, 2.0, 1, 100), 1);
  EXPECT_EQ(pieces_covering(1e300, 2.0, 1, 100), 100);
  EXPECT_EQ(pieces_covering(kNaN, 2.0, 1, 100), 1);
  EXPECT_EQ(pieces_covering(kInf, 2.0, 2, 100), 2);
  EXPECT_EQ(pieces_covering(10.0, 0.0, 1, 100), 1);
}

TEST(CheckedNumeric, GridCellsOfExtremesStayWithinTheGrid) {
  EXPECT_EQ(grid_cell(15.9, 16), 0);
  EXPECT_EQ(grid_cell(-0.1, 16), -1);
  const long long edge = grid_cell(kGridReach, 16);
  for (const double v : kExtremes) {
    const long long c = grid_cell(v, 16);
    EXPECT_LE(std::llabs(c), edge) << v;
    // Keys are cx * 4000037 + cy at most: that must not overflow either.
    EXPECT_LT(static_cast<double>(std::llabs(c)) * 4000037.0 + static_cast<double>(edge), 9.2e18) << v;
  }
}

TEST(PolylineExtremes, ProjectingAPointFarAwayOrNotANumberIsDefined) {
  const Polyline line({{0, 0}, {100, 0}, {100, 100}});
  for (const double v : kExtremes) {
    const Vec2 p(v, 3);
    EXPECT_FALSE(line.project_within(p, 10).has_value()) << v;
    const auto pr = line.project(p);  // no undefined behaviour; finite points land on the line
    if (std::isfinite(v)) {
      EXPECT_GE(pr.s, 0.0);
      EXPECT_LE(pr.s, line.length());
    }
  }
  // A radius of any size: the same answer as the exhaustive projection.
  for (const double radius : {1e300, kInf, 1e6}) {
    const auto near = line.project_within({50, 7}, radius);
    ASSERT_TRUE(near.has_value()) << radius;
    EXPECT_NEAR(near->s, 50, 1e-9);
    EXPECT_NEAR(near->lateral, 7, 1e-9);
  }
  EXPECT_FALSE(line.project_within({50, 7}, kNaN).has_value());
  EXPECT_EQ(line.s_at_fractional_index(kNaN), 0.0);
  EXPECT_EQ(line.s_at_fractional_index(1e300), line.length());
  EXPECT_EQ(line.s_at_fractional_index(-kInf), 0.0);
}

TEST(PolylineExtremes, AShapeWithPointsBeyondTheGridStillProjects) {
  // Segments reaching beyond the grid (1e15 m; 1e300 would overflow the segment's squared
  // length, a double's limit, not the grid's) or spanning millions of cells are kept out of
  // the grid and checked on every projection: the nearest point is still found.
  const Polyline line({{0, 0}, {10, 0}, {1e15, 0}});
  const auto pr = line.project({5, 2});
  EXPECT_NEAR(pr.s, 5, 1e-9);
  EXPECT_NEAR(pr.lateral, 2, 1e-9);
  const auto far = line.project_within({2e6, 1}, 5);
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->distance, 1, 1e-9);
  const Polyline diagonal({{0, 0}, {5e5, 5e5}});
  const auto on = diagonal.project_within({1000, 1000.5}, 2);
  ASSERT_TRUE(on.has_value());
  EXPECT_NEAR(on->distance, 0.5 / std::sqrt(2.0), 1e-9);
}

TEST(ProgressExtremes, AClockOfAnyValueIsReadable) {
  EXPECT_EQ(batch::Progress::clock(65), "1:05");
  EXPECT_EQ(batch::Progress::clock(kNaN), "0:00");
  EXPECT_EQ(batch::Progress::clock(-1e300), "0:00");
  EXPECT_FALSE(batch::Progress::clock(kInf).empty());
  EXPECT_FALSE(batch::Progress::clock(1e300).empty());
}

TEST(SamplerExtremes, WholeNumberParametersOfHugeBoundsStayWholeNumbers) {
  batch::ParameterSpec spec;
  spec.group = "g";
  spec.name = "n";
  spec.type = batch::ValueType::Int;
  std::mt19937_64 engine(7);
  for (const double bound : {1e300, -1e300, kTwoTo63}) {
    spec.distribution = batch::Uniform{bound, bound};
    const auto v = batch::draw(spec, engine);
    EXPECT_TRUE(v.is_number_integer()) << bound;
    spec.distribution = batch::Normal{bound, 1.0, std::nullopt, std::nullopt};
    EXPECT_TRUE(batch::draw(spec, engine).is_number_integer()) << bound;
  }
}

TEST(Plausible, TheLimitsAndTheirMessages) {
  EXPECT_FALSE(implausible(9.9e6, Quantity::Length));
  EXPECT_FALSE(implausible(-5e7, Quantity::Coordinate));
  EXPECT_FALSE(implausible(300, Quantity::SpeedKmh));
  const auto why = implausible(1e300, Quantity::Length);
  ASSERT_TRUE(why);
  EXPECT_EQ(*why, "is 1e+300 m: its magnitude is beyond 10,000 km, more than any map holds");
  EXPECT_TRUE(implausible(kNaN, Quantity::Time));
  EXPECT_TRUE(implausible(-1e8, Quantity::Time));
  EXPECT_TRUE(implausible(3601, Quantity::SpeedKmh));
  EXPECT_TRUE(implausible(1001, Quantity::Speed));
  EXPECT_TRUE(implausible(2e3, Quantity::Acceleration));
}

// What `validate` says of a ScenarioExecutor value no map or run can mean: the key, its value
// and the limit, on the value's line.
TEST(Plausible, TheScenarioReaderRefusesImplausibleValuesNamingTheKey) {
  struct Case {
    std::string actions;
    std::string expected;
  };
  const Case cases[] = {
      {R"([{"route_move": {"actor_id": 2, "type": "waypoint", "route": [{"time": 3, "wp_id": "Waypoint03", "wp_idx": 60, "wp_offset": 1e300}]}}])",
       "\"wp_offset\" is 1e+300 m: its magnitude is beyond 10,000 km"},
      {R"([{"speed": {"actor_id": 1, "type": "absolute", "value": 1e7}}])", "\"value\" is 1e+07 km/h: its magnitude is beyond 3,600 km/h"},
      {R"([{"lane_offset": {"actor_id": 1, "value": 0.5, "time": 1e300}}])", "\"time\" is 1e+300 s: its magnitude is beyond"},
      {R"([{"speed": {"actor_id": 1, "type": "absolute", "value": 50, "accel": {"type": "specify", "value": -3e6}}}])",
       "\"value\" is -3e+06 m/s²: its magnitude is beyond 1,000 m/s²"},
  };
  for (const auto& c : cases) {
    Diagnostics diags;
    (void)scenario_loading::read_scenario(JsonDocument::parse(loader_test::with_actions(c.actions), "s.json"), diags);
    bool found = false;
    for (const auto& d : diags.items())
      if (d.message.find(c.expected) != std::string::npos && d.where.line > 0) found = true;
    EXPECT_TRUE(found) << c.actions << "\n" << diags.items().size() << " diagnostics";
  }
  // Extreme but plausible: 9,000 km of offset is read (and left to the checks and the run).
  Diagnostics diags;
  (void)scenario_loading::read_scenario(
      JsonDocument::parse(loader_test::with_actions(R"([{"lane_offset": {"actor_id": 1, "value": 9e6, "time": 1}}])"),
                          "s.json"),
      diags);
  EXPECT_EQ(diags.error_count(), 0);
}

TEST(Plausible, TheOpenDriveReaderRefusesImplausibleLengthsAndLaneIds) {
  const std::string road = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="LENGTH" junction="-1"><planView><geometry s="0" x="X" y="0" hdg="0" length="LENGTH"><line/></geometry></planView>
<lanes><laneSection s="0"><right><lane id="-1" type="driving"><link><successor id="LINK"/></link>
<width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes></road></OpenDRIVE>)";
  const auto read = [&](const std::string& length, const std::string& x, const std::string& link) -> std::string {
    std::string text = road;
    for (const auto& [from, to] : {std::pair{std::string("LENGTH"), length}, {"X", x}, {"LINK", link}})
      for (auto at = text.find(from); at != std::string::npos; at = text.find(from)) text.replace(at, from.size(), to);
    try {
      (void)opendrive::read_xodr_text(text, "r.xodr");
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "read";
  };
  EXPECT_EQ(read("100", "0", "-1"), "read");
  EXPECT_NE(read("1e300", "0", "-1").find("length is 1e+300 m"), std::string::npos) << read("1e300", "0", "-1");
  EXPECT_NE(read("100", "-1e300", "-1").find("x is -1e+300 m"), std::string::npos);
  EXPECT_NE(read("100", "0", "1e300").find("expected a whole number"), std::string::npos) << read("100", "0", "1e300");
  EXPECT_NE(read("100", "0", "9223372036854775808").find("expected a whole number"), std::string::npos);
  // The soak's first find (seed 4164491318): a geometry of negative length reached the
  // polyline code and ended the run as an internal error.
  EXPECT_NE(read("-2000", "0", "-1").find("geometry length must be > 0 m, found -2000"), std::string::npos)
      << read("-2000", "0", "-1");
  EXPECT_NE(read("0", "0", "-1").find("geometry length must be > 0 m"), std::string::npos);
  // The soak's seed 841508811: 2 m of reference line on a road of 2,000 m (its positions lay
  // off SUMO's net, and libsumo crashed).
  std::string short_line = road;
  short_line.replace(short_line.find("LENGTH"), 6, "2000");
  for (const auto& [from, to] : {std::pair{std::string("LENGTH"), std::string("2")}, {"X", "0"}, {"LINK", "-1"}})
    for (auto at = short_line.find(from); at != std::string::npos; at = short_line.find(from))
      short_line.replace(at, from.size(), to);
  try {
    (void)opendrive::read_xodr_text(short_line, "r.xodr");
    ADD_FAILURE() << "a road longer than its reference line was read";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("the road is 2000 m long but its planView geometries cover 2 m"),
              std::string::npos)
        << e.what();
  }
  // A lane wider than a kilometre anywhere along its width record: 3,000 km at its start (the
  // soak: a run of minutes), a slope of 9.2e18 (the soak: an abort), a cubic that bulges to
  // 1.2 km in the middle of a 100 m road. A taper from 3.5 m to 0 m still reads.
  const auto read_width = [&](const std::string& width) -> std::string {
    std::string t = road;
    t.replace(t.find(R"(a="3.5" b="0" c="0" d="0")"), 25, width);
    for (const auto& [from, to] : {std::pair{std::string("LENGTH"), std::string("100")}, {"X", "0"}, {"LINK", "-1"}})
      for (auto at = t.find(from); at != std::string::npos; at = t.find(from)) t.replace(at, from.size(), to);
    try {
      (void)opendrive::read_xodr_text(t, "r.xodr");
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "read";
  };
  EXPECT_NE(read_width(R"(a="3e6" b="0" c="0" d="0")").find("lane width reaches 3e+06 m within its record: a lane "
                                                            "is at most 1000 m wide"),
            std::string::npos)
      << read_width(R"(a="3e6" b="0" c="0" d="0")");
  EXPECT_NE(read_width(R"(a="3.5" b="9223372036854775808" c="0" d="0")").find("a lane is at most 1000 m wide"),
            std::string::npos);
  EXPECT_NE(read_width(R"(a="0" b="48" c="-0.48" d="0")").find("lane width reaches 1200 m"), std::string::npos)
      << read_width(R"(a="0" b="48" c="-0.48" d="0")");
  EXPECT_NE(read_width(R"(a="3.5" b="0" c="0" d="1e300")").find("at most 1000 m wide"), std::string::npos);
  EXPECT_EQ(read_width(R"(a="3.5" b="-0.035" c="0" d="0")"), "read");
}

TEST(Plausible, TheLargestMagnitudeOfACubicIsAtAnEndOrWhereItsSlopeIsZero) {
  using opendrive::CubicRecord;
  EXPECT_DOUBLE_EQ((CubicRecord{0, 3.5, 0, 0, 0}).largest_magnitude(100), 3.5);
  EXPECT_DOUBLE_EQ((CubicRecord{0, 0, 1, 0, 0}).largest_magnitude(10), 10.0);
  EXPECT_DOUBLE_EQ((CubicRecord{0, 0, 48, -0.48, 0}).largest_magnitude(100), 1200.0);  // peak at 50 m
  EXPECT_DOUBLE_EQ((CubicRecord{0, 0, 48, -0.48, 0}).largest_magnitude(20), 768.0);   // before the peak
  // x^3 - 3x on [0, 3]: a dip to -2 at x = 1, but 18 at the end.
  EXPECT_DOUBLE_EQ((CubicRecord{0, 0, -3, 0, 1}).largest_magnitude(3), 18.0);
  EXPECT_DOUBLE_EQ((CubicRecord{0, 0, -3, 0, 1}).largest_magnitude(1.5), 2.0);
  EXPECT_TRUE(std::isnan((CubicRecord{0, 0, 0, 0, std::numeric_limits<double>::infinity()}).largest_magnitude(1)));
}
