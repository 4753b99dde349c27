// The `record` time function (app/scene/record_reader.h): PEER files of both header forms and
// tables read into SI units, scaled, halved for an outcrop, given as velocity or displacement;
// every malformed file or contradictory key refused with the file, the line and what was expected.
#include "app/scene/scene.h"
#include "common/input_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ddafem
{
namespace
{
namespace fs = std::filesystem;

/// A far field that takes `velocity` as its incident wave, its top free or absorbing.
std::string column_scene(const std::string& velocity, const std::string& top = "lysmer")
{
  return "materials:\n  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}\n"
         "far_field:\n  material: rock\n  lower: [0, 0]\n  upper: [40, 400]\n"
         "  boundaries:\n    - {part: bottom, type: input}\n    - {part: top, type: " +
         top +
         "}\n    - {part: left, type: roller}\n    - {part: right, type: roller}\n"
         "  incident:\n    type: sv\n    velocity: " +
         velocity + "\ntime: {dt: 1e-3, end_time: 1, integrator: newmark_trapezoidal}\n";
}

/// 40 samples every 0.01 s of one cycle of a 2.5 Hz sine (0.4 s) of peak `peak`, one per line
/// or five per line, as text.
std::string sine_samples(double peak, int per_line)
{
  std::ostringstream s;
  s.precision(17);
  for (int i = 0; i < 41; ++i)
    s << peak * std::sin(2.0 * M_PI * 2.5 * 0.01 * i) << ((i + 1) % per_line == 0 ? "\n" : " ");
  return s.str();
}

class RecordTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory = fs::temp_directory_path() / (std::string("ddafem_test_record_") + info->name());
    fs::remove_all(directory);
    fs::create_directories(directory);
  }
  void TearDown() override { fs::remove_all(directory); }

  void write(const std::string& name, const std::string& text) const
  {
    std::ofstream(directory / name) << text;
  }

  /// The incident velocity of the column scene with `velocity`.
  TimeFunction incident(const std::string& velocity, const std::string& top = "lysmer") const
  {
    write("scene.yaml", column_scene(velocity, top));
    return read_scene((directory / "scene.yaml").string()).far_field->incident.velocity;
  }

  std::string error_of(const std::string& velocity, const std::string& top = "lysmer") const
  {
    try
    {
      incident(velocity, top);
    }
    catch (const InputError& e)
    {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << velocity;
    return "";
  }

  fs::path directory;
};

const char* peer_header = "PEER NGA STRONG MOTION DATABASE RECORD\nTEST, 1/1/2000, STATION, 090\n"
                          "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=     41, DT=   .0100 SEC\n";

TEST_F(RecordTest, PeerFileInGIsReadIntoSiUnitsAndHalvedForAnOutcrop)
{
  write("a.AT2", std::string(peer_header) + sine_samples(0.1, 5));
  const TimeFunction v =
      incident("{type: record, file: a.AT2, motion: outcrop, baseline: none, taper: 0}");
  const RecordInfo& r = *v.record_info();
  EXPECT_EQ(r.dt, 0.01);
  EXPECT_NEAR(r.summary.pga, 0.1 * standard_gravity, 1e-12);
  // v = A / omega (1 - cos omega t): at the half cycle, 2 A / omega, up to the trapezoidal rule's
  // (omega dt)^2 / 12 = 2.1e-3; the incident wave is half of it.
  const double omega = 2.0 * M_PI * 2.5, a = 0.1 * standard_gravity;
  EXPECT_NEAR(v.value(0.2), 0.5 * 2.0 * a / omega, 2.5e-3 * a / omega);
  EXPECT_EQ(v.active_until(), 0.4);
}

TEST_F(RecordTest, OldPeerHeaderAndVelocityFilesInCmPerS)
{
  write("v.VT2", "PEER STRONG MOTION DATABASE RECORD\nTEST\n"
                 "VELOCITY TIME HISTORY IN UNITS OF CM/SEC\n  41    0.0100    NPTS, DT\n" +
                     sine_samples(10.0, 5));
  const TimeFunction v = incident("{type: record, file: v.VT2, motion: incident, baseline: none, "
                                  "taper: 0, start: 1}");
  // 10 cm/s peak at 0.1 s after the start; central differences and the trapezoidal rule smooth
  // the peak by (omega dt)^2 / 4 = 6.2e-3.
  EXPECT_NEAR(v.value(1.1), 0.1, 7e-4);
  EXPECT_EQ(v.value(0.5), 0.0);
}

TEST_F(RecordTest, TablesWithATimeColumnOrAFixedDtAndScaling)
{
  std::ostringstream rows;
  rows.precision(17);
  rows << "t [s], a [cm/s^2]\n";
  for (int i = 0; i < 41; ++i)
    rows << 0.01 * i << ", " << 50.0 * std::sin(2.0 * M_PI * 2.5 * 0.01 * i) << "\n";
  write("a.csv", rows.str());
  write("a.txt", sine_samples(50.0, 3));
  const TimeFunction columns = incident("{type: record, file: a.csv, skip_rows: 1, units: "
                                        "cm/s^2, motion: incident, scale_to_pga: 2, "
                                        "baseline: none, taper: 0}");
  const TimeFunction fixed = incident("{type: record, file: a.txt, dt: 0.01, units: cm/s^2, "
                                      "motion: incident, scale_to_pga: 2, baseline: none, "
                                      "taper: 0}");
  EXPECT_NEAR(columns.record_info()->summary.pga, 2.0, 1e-12);
  EXPECT_NEAR(columns.record_info()->scale, 4.0, 1e-9); // 0.5 m/s^2 to 2 m/s^2
  for (double t = 0.0; t < 0.5; t += 0.037)
    EXPECT_NEAR(columns.value(t), fixed.value(t), 1e-12);
  const TimeFunction pgv = incident("{type: record, file: a.txt, dt: 0.01, units: cm/s^2, "
                                    "motion: incident, scale_to_pgv: 0.3}");
  EXPECT_NEAR(pgv.record_info()->summary.pgv, 0.3, 1e-12);
}

TEST_F(RecordTest, TheSpectrumNotTheSamplingGivesTheFrequencies)
{
  // One cycle of 2.5 Hz sampled every 0.1 ms: a table would say 10 kHz.
  std::ostringstream samples;
  for (int i = 0; i <= 4000; ++i)
    samples << std::sin(2.0 * M_PI * 2.5 * 1e-4 * i) << "\n";
  write("dense.txt", samples.str());
  const TimeFunction v =
      incident("{type: record, file: dense.txt, dt: 1e-4, units: m/s^2, motion: incident}");
  EXPECT_LT(v.characteristic_frequency(), 50.0);
  EXPECT_GT(v.dominant_frequency(), 1.0);
  EXPECT_LT(v.dominant_frequency(), 5.0);
}

TEST_F(RecordTest, BadFilesAndKeysAreRefusedWithWhereAndWhat)
{
  const auto refused = [&](const std::string& velocity, const std::string& expected,
                           const std::string& top = "lysmer")
  {
    const std::string message = error_of(velocity, top);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_NE(message.find("scene.yaml"), std::string::npos) << message;
  };
  write("short.AT2", std::string(peer_header) + "0.1 0.2 0.3\n");
  refused("{type: record, file: short.AT2, motion: outcrop}",
          "has 3 samples, its header says NPTS= 41");
  write("odd.AT2", "PEER\nTEST\nSPECTRAL ORDINATES\nNPTS= 3, DT= .01 SEC\n1 2 3\n");
  refused("{type: record, file: odd.AT2, motion: outcrop}",
          "line 3: found 'SPECTRAL ORDINATES', expected ACCELERATION, VELOCITY or DISPLACEMENT");
  write("huge.AT2", "PEER\nTEST\nACCELERATION IN UNITS OF G\nNPTS= 123456789012, DT= .01 SEC\n1\n");
  refused("{type: record, file: huge.AT2, motion: outcrop}",
          "line 4: found 'NPTS= 123456789012, DT= .01 SEC', expected 'NPTS= n, DT= dt SEC'");
  write("word.AT2", std::string(peer_header) + "0.1 0.2\n0.3 x\n");
  refused("{type: record, file: word.AT2, motion: outcrop}", "line 6: 'x' is not a number");
  write("a.AT2", std::string(peer_header) + sine_samples(0.1, 5));
  refused("{type: record, file: a.AT2, motion: outcrop, units: cm/s^2}",
          "the file's header says its samples are in g");
  refused("{type: record, file: a.AT2, motion: outcrop, dt: 0.01}",
          "a PEER file gives its own layout");
  refused("{type: record, file: a.AT2, motion: outcrop, scale: 2, scale_to_pga: 3}",
          "at most one of scale, scale_to_pga and scale_to_pgv");
  refused("{type: record, file: a.AT2, motion: outcrop, to: 0.5}",
          "at most the record's length (0.4 s)");
  refused("{type: record, file: missing.AT2, motion: outcrop}", "cannot open record file");
  refused("{type: record, file: a.AT2, motion: within}", "taken `within`", "free");
  write("t.csv", "0, 1\n0.01, 2\n0.02, 3\n0.04, 4\n");
  refused("{type: record, file: t.csv, motion: outcrop}", "expected `units`");
  refused("{type: record, file: t.csv, motion: outcrop, units: g}",
          "the times are not uniformly sampled: 0.02 to 0.04 s after intervals of 0.01 s");
}

TEST_F(RecordTest, ARecordIsNotALoadFactor)
{
  write("a.AT2", std::string(peer_header) + sine_samples(0.1, 5));
  write("blocks.yaml",
        "materials:\n  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}\n"
        "blocks:\n  - material: rock\n    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]\n"
        "point_loads:\n  - {point: [0.5, 0.5], force: [1, 0], time_function: {type: record, "
        "file: a.AT2, motion: outcrop}}\ntime: {dt: 1e-4, end_time: 0.01}\n");
  try
  {
    read_scene((directory / "blocks.yaml").string());
    ADD_FAILURE() << "a record as a load factor was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("not as a load's factor"), std::string::npos) << e.what();
  }
}

TEST_F(RecordTest, AFixedPointTakesTheRecordsDisplacement)
{
  write("a.AT2", std::string(peer_header) + sine_samples(0.1, 5));
  write("blocks.yaml",
        "materials:\n  rock: {density: 2650, youngs_modulus: 50e9, poisson_ratio: 0.25}\n"
        "blocks:\n  - material: rock\n    vertices: [[0, 0], [1, 0], [1, 1], [0, 1]]\n"
        "fixed_points:\n  - {point: [0.5, 0.5], displacement_x: {type: record, file: a.AT2, "
        "motion: incident, baseline: none, taper: 0}}\ntime: {dt: 1e-4, end_time: 0.01}\n");
  const Scene scene = read_scene((directory / "blocks.yaml").string());
  // u = A / omega (t - sin(omega t) / omega): at the end of the cycle, A T / omega, up to the
  // trapezoidal rule's (omega dt)^2 / 12 = 2.1e-3.
  const double a = 0.1 * standard_gravity, omega = 2.0 * M_PI * 2.5;
  EXPECT_NEAR(scene.model.fixed_points[0].displacement_x.value(0.4), a * 0.4 / omega,
              2.5e-3 * a * 0.4 / omega);
}

} // namespace
} // namespace ddafem
