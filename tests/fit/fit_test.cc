// SPDX-License-Identifier: GPL-3.0-or-later
// Calibration (docs/calibrate.md): logs of the sysid test pattern made by the simulator from
// robot files whose motor constants are drawn from a seed, fitted against the bundled file; the
// truth is the drawn values. Bad logs: exit 2, one line naming file:line, nothing written.
#include "fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "bundled_components.h"
#include "dc_motor.h"
#include "png_file.h"
#include "replay.h"
#include "robot_patch.h"
#include "run_program.h"
#include "sysid_log.h"
#include "text_file.h"

namespace unimouse::fit {
namespace {

using testing::FreshDirectory;
using testing::Unimouse;
using testing::UnimouseRun;

const std::string kRobot = std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse.yaml";

struct MotorConstants {
  double kt_left, r_left, kt_right, r_right;
};

// the bundled robot with other motor constants and encoder noise (jitter_counts_sd) on
std::string ChangedRobot(const MotorConstants& m, const std::string& file = kRobot) {
  std::string text = ReadTextFile(file);
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  const auto constants = [](double kt, double r) {
    return " kt_nm_per_a: " + std::to_string(kt) + ", resistance_ohm: " + std::to_string(r) + ",";
  };
  replace(
      "params: { actuator: left_motor, model: pololu_30_1_lp,",
      "params: { actuator: left_motor, model: pololu_30_1_lp," + constants(m.kt_left, m.r_left));
  replace(
      "params: { actuator: right_motor, model: pololu_30_1_lp,",
      "params: { actuator: right_motor, model: pololu_30_1_lp," + constants(m.kt_right, m.r_right));
  for (const char* side : {"left", "right"}) {
    replace(std::string("cpr: 12, counts_out: ") + side,
            std::string("cpr: 12, jitter_counts_sd: 0.1, counts_out: ") + side);
  }
  return text;
}

// runs the sysid example in the sysid scenario on a robot file; returns the log's path
std::string SimulatedLog(const std::string& robot_file, const std::string& name) {
  const testing::RunResult run =
      UnimouseRun("--robot " + robot_file + " --scenario sysid --link inproc:sysid", name);
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  return (std::filesystem::temp_directory_path() / name / "sysid.csv").string();
}

PluginRegistry Registry() {
  PluginRegistry registry;
  AddBundledComponents(registry);
  return registry;
}

TEST(SysidScenarioTest, TheExampleLogsTheDocumentedColumnsForTheWholeSequence) {
  const SysidLog log = ReadSysidLog(SimulatedLog(kRobot, "sysid_default"));
  // 48.4 s of sequence at one row every 10 ms (arduino-lib/examples/sysid), less the first
  // 20 ms in which the sketch listens for a gyro
  ASSERT_EQ(log.rows(), 4839u);
  EXPECT_DOUBLE_EQ(log.time_s.front(), 0.02);
  EXPECT_DOUBLE_EQ(log.time_s.back(), 48.4);
  EXPECT_TRUE(log.gyro_z_rad_s.empty());
  double largest = 0;
  for (double c : log.left_command) largest = std::max(largest, c);
  // the forward ramp's last row: 700 x 7.99 s / 8 s, in whole commands
  EXPECT_EQ(largest, 699);
  EXPECT_NE(log.left_counts.back(), 0);
}

TEST(CompareTest, TheSimulatorsOwnLogReplaysOnItsRobotWithinTheEncodersQuantisation) {
  const SysidLog log = ReadSysidLog(SimulatedLog(kRobot, "sysid_compare"));
  const PluginRegistry registry = Registry();
  const std::vector<ChannelComparison> channels =
      CompareLog(ParseRobotSpec(ReadTextFile(kRobot), kRobot), registry, log);
  ASSERT_EQ(channels.size(), 2u);
  // a speed from two rounded counts 10 ms apart is off by the difference of two uniform
  // roundings: sd 1 / sqrt(6) counts, 40.8 counts/s; the replay reads the wheel unrounded
  const double quantisation = 100 / std::sqrt(6.0);
  for (const ChannelComparison& c : channels) {
    EXPECT_LT(c.rmse, 1.1 * quantisation) << c.channel;
    EXPECT_GT(c.rmse, 0.5 * quantisation) << c.channel;
    EXPECT_GT(c.r2, 0.99) << c.channel;
  }
}

TEST(CompareTest, TheHalfSizeRobotsOwnLogReplaysOnItsFileWithinTheEncodersQuantisation) {
  const std::string file = std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse-half.yaml";
  const SysidLog log = ReadSysidLog(SimulatedLog(file, "sysid_half"));
  const PluginRegistry registry = Registry();
  const double quantisation = 100 / std::sqrt(6.0);  // as above
  for (const ChannelComparison& c :
       CompareLog(ParseRobotSpec(ReadTextFile(file), file), registry, log)) {
    EXPECT_LT(c.rmse, 1.1 * quantisation) << c.channel;
    EXPECT_GT(c.r2, 0.99) << c.channel;
  }
}

TEST(ReplayTest, IsTheSameBitForBitEveryTime) {
  const SysidLog log = ReadSysidLog(SimulatedLog(kRobot, "sysid_replay"));
  const RobotSpec robot = ParseRobotSpec(ReadTextFile(kRobot), kRobot);
  const PluginRegistry registry = Registry();
  const Channels a = ReplayChannels(robot, WireRobot(robot), registry, log);
  const Channels b = ReplayChannels(robot, WireRobot(robot), registry, log);
  EXPECT_EQ(a.values, b.values);
}

TEST(FitTest, RecoversEachMotorsConstantsDrawnFromASeedWithinFivePercent) {
  // each side's Kt and Ra within +-30 % of table 3.1's, drawn from seed 31
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> change(-0.3, 0.3);
  const MotorConstants truth{0.079025 * (1 + change(rng)), 16.66667 * (1 + change(rng)),
                             0.079025 * (1 + change(rng)), 16.66667 * (1 + change(rng))};
  const std::string dir = FreshDirectory("fit_round_trip");
  const std::string robot_file = dir + "/changed.yaml";
  WriteTextFile(robot_file, ChangedRobot(truth));
  const SysidLog log = ReadSysidLog(SimulatedLog(robot_file, "sysid_changed"));

  const RobotSpec robot = ParseRobotSpec(ReadTextFile(kRobot), kRobot);
  const FitReport report = FitRobot(robot, Registry(), {log});
  ASSERT_EQ(report.parameters.size(), 4u);
  const double truths[] = {truth.kt_left, truth.r_left, truth.kt_right, truth.r_right};
  for (size_t i = 0; i < 4; ++i) {
    const FittedParameter& p = report.parameters[i];
    SCOPED_TRACE(p.ref.component + "." + p.ref.key);
    EXPECT_TRUE(p.identified);
    EXPECT_LT(std::abs(p.value / truths[i] - 1), 0.05);  // the acceptance bound
  }
  for (const ChannelFit& c : report.channels) {
    SCOPED_TRACE(c.channel);
    EXPECT_GE(c.r2_after, 0.98);
    EXPECT_LT(c.rmse_after, c.rmse_before);
  }

  // the fitted file replays the log within the sensors' noise: the rounding of two counts
  // (sd 1 / sqrt(6) counts) and the edges' jitter (0.1 count at each end) over 10 ms
  RobotSpec fitted = robot;
  for (const FittedParameter& p : report.parameters) SetParameter(fitted, p.ref, p.value);
  const double noise = 100 * std::sqrt(1.0 / 6 + 2 * 0.1 * 0.1);
  for (const ChannelComparison& c : CompareLog(fitted, Registry(), log)) {
    EXPECT_LT(c.rmse, 1.2 * noise) << c.channel;
  }
}

TEST(FitTest, TheHalfSizeRobotGivesBackItsMotorConstantsWithinFivePercent) {
  // the same draw as above, on the half-size robot, fitted against its own file
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> change(-0.3, 0.3);
  const MotorConstants truth{0.079025 * (1 + change(rng)), 16.66667 * (1 + change(rng)),
                             0.079025 * (1 + change(rng)), 16.66667 * (1 + change(rng))};
  const std::string half = std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse-half.yaml";
  const std::string dir = FreshDirectory("fit_half_round_trip");
  WriteTextFile(dir + "/changed.yaml", ChangedRobot(truth, half));
  const SysidLog log = ReadSysidLog(SimulatedLog(dir + "/changed.yaml", "sysid_half_changed"));
  const FitReport report = FitRobot(ParseRobotSpec(ReadTextFile(half), half), Registry(), {log});
  ASSERT_EQ(report.parameters.size(), 4u);
  const double truths[] = {truth.kt_left, truth.r_left, truth.kt_right, truth.r_right};
  for (size_t i = 0; i < 4; ++i) {
    const FittedParameter& p = report.parameters[i];
    SCOPED_TRACE(p.ref.component + "." + p.ref.key);
    // Ra too, now that the replay counts as the encoder does (its play of a count when the wheel
    // turns back): without it both Ra came back 6 and 16 % high (docs/calibrate.md, limits)
    EXPECT_LT(std::abs(p.value / truths[i] - 1), 0.05);  // the acceptance bound
  }
  for (const ChannelFit& c : report.channels) EXPECT_GE(c.r2_after, 0.98) << c.channel;
}

TEST(FitTest, EndsNoFurtherFromTheFilesOwnLogThanTheFileItself) {
  // the file's values are the truth here: a search that wanders off them (it did, to RMSE 39.8
  // from 34.3 counts/s, starting from the quasi-static Kt) makes the fitted file worse. What
  // docs/calibrate.md promises is the total of both wheels' squared speed residuals, each
  // channel divided by its RMS; one wheel alone may end a little worse
  const SysidLog log = ReadSysidLog(SimulatedLog(kRobot, "sysid_own"));
  const FitReport report =
      FitRobot(ParseRobotSpec(ReadTextFile(kRobot), kRobot), Registry(), {log});
  ASSERT_EQ(report.channels.size(), 2u);
  double before = 0, after = 0;
  for (const ChannelFit& c : report.channels) {
    double mean_square = 0;
    for (double v : c.logged) mean_square += v * v / static_cast<double>(c.logged.size());
    before += c.rmse_before * c.rmse_before / mean_square;
    after += c.rmse_after * c.rmse_after / mean_square;
  }
  EXPECT_LE(after, before);
}

// the gyro robot's log: the sysid sketch logs the gyro when the link sends its z frame
std::string SimulatedGyroLog(const std::string& robot_file, const std::string& name) {
  return SimulatedLog(robot_file +
                          " --link-set send='3 left.encoder_counts i16; 4 right.encoder_counts "
                          "i16; 34 imu.gyro_z_counts i16'",
                      name);
}

TEST(FitTest, RecoversTheGyrosBiasAndScaleErrorDrawnFromASeed) {
  // the ICM-20602 of the gyro robot with a z bias within +-1 dps and a scale error within +-3 %
  // (its datasheet's tolerances are +-1 dps and +-1 %; the MPU-6500's scale error +-3 %), drawn
  // from seed 31; its drift, noise and cross-axis draws stay on
  std::mt19937_64 rng(31);
  const std::string bias = std::to_string(std::uniform_real_distribution<double>(-1, 1)(rng));
  const std::string scale =
      std::to_string(std::uniform_real_distribution<double>(-0.03, 0.03)(rng));
  const std::string gyro = std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse-gyro.yaml";
  std::string text = ReadTextFile(gyro);
  const std::string imu = "odr_hz: 1000, dlpf_hz: 250 }";
  ASSERT_NE(text.find(imu), std::string::npos);
  text.replace(text.find(imu), imu.size(),
               "odr_hz: 1000, dlpf_hz: 250, gyro_z_bias_dps: " + bias +
                   ", gyro_z_scale_error: " + scale + " }");
  const std::string dir = FreshDirectory("fit_gyro_round_trip");
  WriteTextFile(dir + "/changed.yaml", text);
  const SysidLog log = ReadSysidLog(SimulatedGyroLog(dir + "/changed.yaml", "sysid_gyro"));
  ASSERT_EQ(log.gyro_z_rad_s.size(), log.rows());

  const RobotSpec robot = ParseRobotSpec(ReadTextFile(gyro), gyro);
  const FitReport report = FitRobot(robot, Registry(), {log});
  ASSERT_EQ(report.parameters.size(), 6u);
  const FittedParameter& b = report.parameters[4];
  const FittedParameter& s = report.parameters[5];
  ASSERT_EQ(b.ref.key, "gyro_z_bias_dps");
  ASSERT_EQ(s.ref.key, "gyro_z_scale_error");
  EXPECT_TRUE(b.identified);
  EXPECT_TRUE(s.identified);
  // within 5 % of the drawn values; for a bias under 0.2 dps within 0.01 dps instead: the
  // chip's own drift (bias instability 0.003 dps, a Gauss-Markov sd of 0.005 dps) moves it
  // that much during the log
  EXPECT_NEAR(b.value, std::stod(bias), std::max(0.05 * std::abs(std::stod(bias)), 0.01));
  EXPECT_NEAR(s.value, std::stod(scale), 0.05 * std::abs(std::stod(scale)));
  EXPECT_LE(b.ci_low, b.value);
  EXPECT_GE(b.ci_high, b.value);

  bool has_gyro = false;
  for (const ChannelFit& c : report.channels) {
    if (c.channel != "gyro_z_rad_s") continue;
    has_gyro = true;
    EXPECT_GE(c.r2_after, 0.98);
    EXPECT_LT(c.rmse_after, c.rmse_before);
  }
  EXPECT_TRUE(has_gyro);

  // the fitted file writes them where the imu reads them: replayed, it reads as the log within
  // the chip's noise and resolution (0.004 dps/sqrt(Hz) at 250 Hz, and 1 / 16.4 dps a count)
  const std::string patched = PatchRobotText(ReadTextFile(gyro), robot, report.parameters, "fit");
  const RobotSpec back = ParseRobotSpec(patched, "patched");
  EXPECT_NE(patched.find("# fit: gyro_z_bias_dps "), std::string::npos) << patched;
  EXPECT_NE(patched.find(" (was drawn), gyro_z_scale_error "), std::string::npos) << patched;
  EXPECT_NEAR(ParameterValue(back, {"imu", "gyro_z_bias_dps"}), std::stod(bias),
              std::max(0.05 * std::abs(std::stod(bias)), 0.01));
  for (const ChannelComparison& c : CompareLog(back, Registry(), log)) {
    if (c.channel != "gyro_z_rad_s") continue;
    EXPECT_GE(c.r2, 0.98);
    EXPECT_LT(c.rmse, 0.01);  // rad/s: 0.6 dps, ten counts
  }
}

TEST(FitTest, TheAfterColumnsAndPlotsAreTheReplayOfTheFittedFileAlsoWhereAValueIsKept) {
  // the log of a gyro robot whose z gyro's bias is 0.4 dps and whose motors' Ra are five times
  // the file's (beyond the search's bound of four: not identified, the file's Ra kept), cut
  // before its steps and spins (the first 20 s: standstill and ramps, driving straight): the
  // standstills pin the bias, nothing pins the scale error, which keeps the file's draw. The
  // "after" lines must be the fitted file's replay, not the search's last point
  const std::string gyro = std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse-gyro.yaml";
  const std::string text = ReadTextFile(gyro);
  const std::string imu = "odr_hz: 1000, dlpf_hz: 250 }";
  ASSERT_NE(text.find(imu), std::string::npos);
  std::string changed = text;
  changed.replace(changed.find(imu), imu.size(),
                  "odr_hz: 1000, dlpf_hz: 250, gyro_z_bias_dps: 0.4 }");
  for (const std::string side : {"left", "right"}) {
    const std::string motor = "params: { actuator: " + side + "_motor, model: pololu_30_1_lp,";
    ASSERT_NE(changed.find(motor), std::string::npos);
    changed.replace(changed.find(motor), motor.size(), motor + " resistance_ohm: 166.7,");
  }
  const std::string dir = FreshDirectory("fit_ramps_only");
  WriteTextFile(dir + "/changed.yaml", changed);
  std::istringstream full(
      ReadTextFile(SimulatedGyroLog(dir + "/changed.yaml", "sysid_gyro_ramps")));
  std::string cut, line;
  std::getline(full, line);
  cut = line + "\n";
  while (std::getline(full, line) && std::stod(line.substr(0, line.find(','))) < 20) {
    cut += line + "\n";
  }
  WriteTextFile(dir + "/ramps.csv", cut);
  const SysidLog log = ReadSysidLog(dir + "/ramps.csv");
  const RobotSpec robot = ParseRobotSpec(text, gyro);
  const FitReport report = FitRobot(robot, Registry(), {log});
  ASSERT_EQ(report.parameters.size(), 6u);
  EXPECT_FALSE(report.parameters[1].identified);
  EXPECT_FALSE(report.parameters[3].identified);
  EXPECT_TRUE(report.parameters[4].identified);
  EXPECT_NEAR(report.parameters[4].value, 0.4, 0.05 * 0.4);
  ASSERT_FALSE(report.parameters[5].identified) << "the test needs a value that is kept";

  const RobotSpec fitted =
      ParseRobotSpec(PatchRobotText(text, robot, report.parameters, "fit"), "fitted");
  const Channels replayed = ReplayChannels(fitted, WireRobot(fitted), Registry(), log);
  ASSERT_EQ(report.channels.size(), 3u);
  for (size_t c = 0; c < 3; ++c) {
    const ChannelFit& channel = report.channels[c];
    SCOPED_TRACE(channel.channel);
    const std::vector<double>& file = c < 2 ? replayed.values[c] : replayed.gyro_z_rad_s;
    // the file writes six significant digits: the replays differ by less than that
    const std::vector<double> zero(channel.logged.size(), 0.0);
    EXPECT_LT(Rmse(file, channel.replayed_after), 1e-3 * Rmse(channel.logged, zero));
  }
}

TEST(FitTest, TheFittedFileChangesOnlyTheFittedValuesAndSaysSo) {
  const std::string text = ReadTextFile(kRobot);
  const RobotSpec robot = ParseRobotSpec(text, kRobot);
  std::vector<FittedParameter> fitted(3);
  fitted[0].ref = {"left_motor", "kt_nm_per_a"};
  fitted[0].file_value = 0.079025;
  fitted[0].value = 0.0812;
  fitted[0].identified = true;
  fitted[1].ref = {"right_motor", "resistance_ohm"};
  fitted[1].file_value = 16.66667;
  fitted[1].value = 15.5;
  fitted[1].identified = true;
  fitted[2].ref = {"right_motor", "kt_nm_per_a"};
  fitted[2].file_value = 0.079025;
  fitted[2].value = 0.09;
  fitted[2].identified = false;  // not identified: stays as it was
  const std::string patched = PatchRobotText(text, robot, fitted, "fitted to log.csv");
  const RobotSpec back = ParseRobotSpec(patched, "patched");
  EXPECT_DOUBLE_EQ(ParameterValue(back, {"left_motor", "kt_nm_per_a"}), 0.0812);
  EXPECT_DOUBLE_EQ(ParameterValue(back, {"right_motor", "resistance_ohm"}), 15.5);
  EXPECT_DOUBLE_EQ(ParameterValue(back, {"right_motor", "kt_nm_per_a"}), 0.079025);
  EXPECT_DOUBLE_EQ(ParameterValue(back, {"left_motor", "resistance_ohm"}), 16.66667);
  EXPECT_NE(patched.find("# fitted to log.csv: kt_nm_per_a 0.0812 (was 0.079025)"),
            std::string::npos);
  // every line of the original is still there, the two motors' params lines aside
  std::istringstream original(text);
  std::string line;
  int changed = 0;
  while (std::getline(original, line)) {
    if (patched.find(line) == std::string::npos) ++changed;
  }
  EXPECT_EQ(changed, 2);
}

TEST(ReplayTest, KnowsTheMotorModelsDefaultsAsTheMotorDoes) {
  for (const char* model : {"pololu_30_1_lp", "pololu_50_1_lp", "pololu_100_1_lp",
                            "pololu_150_1_lp", "pololu_1000_1_lp", "pololu_30_1_hp"}) {
    RobotSpec robot = ParseRobotSpec(ReadTextFile(kRobot), kRobot);
    for (ComponentSpec& c : robot.components) {
      for (YamlEntry& e : c.params.entries) {
        if (c.name == "left_motor" && e.first.scalar == "model") e.second.scalar = model;
      }
    }
    const plugins::MotorConstants k = plugins::MotorModel(model);
    EXPECT_DOUBLE_EQ(ParameterValue(robot, {"left_motor", "kt_nm_per_a"}), k.kt_nm_per_a);
    EXPECT_DOUBLE_EQ(ParameterValue(robot, {"left_motor", "resistance_ohm"}), k.resistance_ohm);
  }
}

// a log of the default robot, edited into a bad one
class BadLogTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { good_ = ReadTextFile(SimulatedLog(kRobot, "sysid_bad_logs")); }

  // runs `unimouse fit` (or `compare`) on the log; expects exit 2, one line naming `where`,
  // nothing written
  void ExpectRefused(const std::string& log_text, const std::string& where, const std::string& why,
                     const std::string& command = "fit") {
    const std::string dir = FreshDirectory("bad_log");
    WriteTextFile(dir + "/log.csv", log_text);
    const testing::Outcome o =
        Unimouse(command + " " + kRobot + " " + dir + "/log.csv --out " + dir + "/fitted");
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(dir + "/log.csv" + where), std::string::npos) << o.output;
    EXPECT_NE(o.output.find(why), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/fitted"));
  }
  // the log with line `number` (1 = the header) replaced
  static std::string WithLine(int number, const std::string& replacement) {
    std::istringstream in(good_);
    std::string out, line;
    for (int n = 1; std::getline(in, line); ++n) out += (n == number ? replacement : line) + "\n";
    return out;
  }
  // the first `rows` rows of the log
  static std::string FirstRows(int rows) {
    std::istringstream in(good_);
    std::string out, line;
    for (int n = 0; n <= rows && std::getline(in, line); ++n) out += line + "\n";
    return out;
  }
  static inline std::string good_;
};

TEST_F(BadLogTest, AMissingColumn) {
  ExpectRefused(WithLine(1, "time_s,left_command,right_command,battery_v,left_counts"),
                ":1:", "no column 'right_counts'");
}

TEST_F(BadLogTest, TimeGoingBackwards) {
  ExpectRefused(WithLine(5, "0.020,0,0,6.000,0,0"), ":5:", "time must increase");
}

TEST_F(BadLogTest, NotANumber) {
  ExpectRefused(WithLine(3, "0.010,nan,0,6.000,0,0"), ":3:", "is not a finite number");
}

TEST_F(BadLogTest, NotANumberStopsCompareBeforeItPlotsAnything) {
  ExpectRefused(WithLine(3, "0.010,nan,0,6.000,0,0"), ":3:", "is not a finite number", "compare");
}

TEST_F(BadLogTest, TooShort) { ExpectRefused(FirstRows(100), ":", "too short to identify"); }

TEST_F(BadLogTest, TooFlat) {
  // 3 s of rows whose commands stay below any useful one and whose wheels never turn
  std::istringstream in(FirstRows(300));
  std::string out, line;
  std::getline(in, line);
  out = line + "\n";
  while (std::getline(in, line)) out += line.substr(0, line.find(',')) + ",20,20,6.000,0,0\n";
  ExpectRefused(out, ":", "too flat to identify");
}

TEST_F(BadLogTest, AnotherRobotsCountsPerTurn) {
  // the same motion counted by an encoder with four times the counts per turn
  std::istringstream in(good_);
  std::string out, line;
  std::getline(in, line);
  out = line + "\n";
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) f.push_back(field);
    f[4] = std::to_string(4 * std::stol(f[4]));
    f[5] = std::to_string(4 * std::stol(f[5]));
    out += f[0] + "," + f[1] + "," + f[2] + "," + f[3] + "," + f[4] + "," + f[5] + "\n";
  }
  ExpectRefused(out, ":", "a log of another robot");
}

}  // namespace
}  // namespace unimouse::fit

namespace unimouse::fit {
namespace {

TEST(DocumentedCommandsTest, TheWorkedExampleOfCalibrateMdRunsFromLogToFittedFile) {
  const std::vector<std::string> commands =
      testing::DocumentedCommands("docs/calibrate.md", "## Worked example, in the simulator");
  ASSERT_EQ(commands.size(), 3u);
  const std::string dir = FreshDirectory("documented_calibrate");
  for (const std::string& command : commands) {
    const testing::Outcome o = testing::RunDocumented(command, dir);
    EXPECT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    // what wheel speeds cannot pin, said so and kept (docs/calibrate.md, Limits)
    if (command.find(" fit ") != std::string::npos) {
      for (const char* kept :
           {"each motor's damping_nm_s_per_rad", "each wheel joint's armature"}) {
        EXPECT_NE(o.output.find(kept), std::string::npos) << kept << "\n" << o.output;
      }
    }
  }
  const std::string fitted = ReadTextFile(dir + "/out/fit/unimouse-fitted.yaml");
  // the log is of the very robot: whatever is fitted stays the file's within the fit's bounds
  const RobotSpec back = ParseRobotSpec(fitted, "fitted");
  EXPECT_NEAR(ParameterValue(back, {"left_motor", "kt_nm_per_a"}), 0.079025, 0.05 * 0.079025);
  EXPECT_NEAR(ParameterValue(back, {"right_motor", "kt_nm_per_a"}), 0.079025, 0.05 * 0.079025);
  // beside it, the plots of both: per channel, PNGs of the stated size
  for (const char* channel : {"left_counts_per_s", "right_counts_per_s"}) {
    for (const char* kind : {"fit", "compare"}) {
      const std::string plot = dir + "/out/fit/sysid-" + channel + "-" + kind + ".png";
      SCOPED_TRACE(plot);
      int width = 0, height = 0;
      ASSERT_TRUE(std::filesystem::exists(plot));
      EXPECT_FALSE(ReadPng(plot, &width, &height).empty());
      EXPECT_EQ(width, 960);
      EXPECT_EQ(height, 540);
    }
  }
}

TEST(DocumentedCommandsTest, TheGyroRobotsWorkedExampleFitsItsGyroWithinThePartsTolerances) {
  const std::vector<std::string> commands = testing::DocumentedCommands(
      "docs/calibrate.md", "The gyro robot (`robots/unimouse-gyro.yaml`");
  ASSERT_EQ(commands.size(), 2u);
  const std::string dir = FreshDirectory("documented_calibrate_gyro");
  for (const std::string& command : commands) {
    const testing::Outcome o = testing::RunDocumented(command, dir);
    EXPECT_EQ(o.exit_code, 0) << command << "\n" << o.output;
    if (command.find(" fit ") != std::string::npos) {
      EXPECT_NE(o.output.find("imu.gyro_z_bias_dps"), std::string::npos) << o.output;
    }
  }
  // the run's imu drew its z bias within the ICM-20602's +-1 dps and its scale error within
  // +-1 %: the fitted file gives values inside those
  const RobotSpec back =
      ParseRobotSpec(ReadTextFile(dir + "/out/fit-gyro/unimouse-gyro-fitted.yaml"), "fitted");
  EXPECT_FALSE(ParameterDrawn(back, {"imu", "gyro_z_bias_dps"}));
  EXPECT_LE(std::abs(ParameterValue(back, {"imu", "gyro_z_bias_dps"})), 1.0);
  EXPECT_LE(std::abs(ParameterValue(back, {"imu", "gyro_z_scale_error"})), 0.01);
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/fit-gyro/sysid-gyro_z_rad_s-fit.png"));
  // the same log against the robot without an imu: the motors are fitted, and the report says
  // that the gyro's column is not used
  const testing::Outcome plain =
      Unimouse("fit unimouse " + dir + "/out/sysid-gyro/sysid.csv --out " + dir + "/out/fit-plain");
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_NE(
      plain.output.find("the robot file has no unimouse.imu; the logs' gyro_z_rad_s is not used"),
      std::string::npos)
      << plain.output;
  EXPECT_EQ(plain.output.find("imu.gyro_z_bias_dps"), std::string::npos) << plain.output;
}

// docs/calibrate.md, limits: the round-trip script's one draw, word for word from the source tree
// (the script finds the built program in UNIMOUSE_BINARY, the environment of this build)
TEST(DocumentedCommandsTest, TheRoundTripScriptOfCalibrateMdGivesBackItsDrawWithinFivePercent) {
  if (!testing::HavePython()) GTEST_SKIP() << "no python3";
  const std::vector<std::string> commands =
      testing::DocumentedCommands("docs/calibrate.md", "- **Other draws than the tests'**");
  ASSERT_EQ(commands.size(), 1u);
  ASSERT_EQ(commands[0].rfind("bench/fit_round_trips.py ", 0), 0u) << commands[0];
  const testing::Outcome o = testing::Shell(
      "cd " UNIMOUSE_SOURCE_DIR " && UNIMOUSE_BINARY=" UNIMOUSE_BINARY " " + commands[0]);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("unimouse-half  seed  3  Kt left"), std::string::npos) << o.output;
  // its last line: the worst fitted constant against the drawn one, within the acceptance's 5 %
  const size_t at = o.output.find("worst error ");
  ASSERT_NE(at, std::string::npos) << o.output;
  EXPECT_LT(std::stod(o.output.substr(at + 12)), 5) << o.output;
}

}  // namespace
}  // namespace unimouse::fit
