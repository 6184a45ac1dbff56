// The calibration recorder without any middleware: what it keeps, what it
// refuses and counts, gap detection, when a calibration is due, and that one
// sample stamped far ahead or back cannot stop the recording while a clock
// that really jumped back restarts it.
#include <gtest/gtest.h>

#include <cmath>

#include "structloc/calibration_core/calibration_recorder.hpp"

namespace structloc::calibration_core {
namespace {

EncoderSample Encoders(double t) {
  EncoderSample s;
  s.t = t;
  s.traction_ticks = static_cast<uint64_t>(100 * t);
  return s;
}

Fix FixAt(double t, double x = 0.0) {
  Fix f;
  f.t = t;
  f.pose = {x, 0.0, 0.0};
  return f;
}

TEST(CalibrationRecorder, KeepsEncodersInOrderAndCountsGaps) {
  CalibrationRecorder recorder({60.0, 0.5, {}});
  EXPECT_TRUE(recorder.AddEncoders(Encoders(1.0)));
  EXPECT_TRUE(recorder.AddEncoders(Encoders(1.1)));
  EXPECT_FALSE(recorder.AddEncoders(Encoders(1.1)));  // not after the previous one
  EXPECT_FALSE(recorder.AddEncoders(Encoders(0.5)));
  EXPECT_TRUE(recorder.AddEncoders(Encoders(2.1)));  // a 1 s gap: kept and counted
  EXPECT_TRUE(recorder.AddEncoders(Encoders(2.2)));
  const auto stats = recorder.Stats();
  EXPECT_EQ(stats.encoders, 4u);
  EXPECT_EQ(stats.encoders_out_of_order, 2u);
  EXPECT_EQ(stats.gaps, 1u);
  EXPECT_NEAR(stats.largest_gap_s, 1.0, 1e-12);
}

TEST(CalibrationRecorder, RefusesFixesThatAreNotFiniteOrNotInOrder) {
  CalibrationRecorder recorder({60.0, 0.5, {}});
  EXPECT_TRUE(recorder.AddFix(FixAt(1.0)));
  EXPECT_FALSE(recorder.AddFix(FixAt(2.0, NAN)));
  EXPECT_FALSE(recorder.AddFix(FixAt(1.0)));
  EXPECT_TRUE(recorder.AddFix(FixAt(2.0)));
  EXPECT_EQ(recorder.Stats().fixes, 2u);
  EXPECT_EQ(recorder.Stats().fixes_rejected, 2u);
}

TEST(CalibrationRecorder, IsDueOnceTheEncodersSpanTheRecordingLength) {
  CalibrationRecorder recorder({10.0, 0.5, {}});
  for (int k = 0; k < 100; ++k) recorder.AddEncoders(Encoders(5.0 + 0.1 * k));
  EXPECT_FALSE(recorder.Due());  // 9.9 s
  recorder.AddEncoders(Encoders(15.0));
  EXPECT_TRUE(recorder.Due());
  const auto recording = recorder.Finish();
  EXPECT_EQ(recording.encoders.size(), 101u);
  EXPECT_TRUE(recorder.Finished());
  EXPECT_FALSE(recorder.Due());                        // estimated once
  EXPECT_FALSE(recorder.AddEncoders(Encoders(16.0)));  // the recording has ended
  EXPECT_EQ(recorder.Stats().encoders, 101u);
}

TEST(CalibrationRecorder, UntilStoppedIsNeverDueAndAStopEstimatesWhenThereIsEnough) {
  CalibrationRecorder until_stopped({0.0, 0.5, {}});
  for (int k = 0; k < 1000; ++k) until_stopped.AddEncoders(Encoders(0.1 * k));
  EXPECT_FALSE(until_stopped.Due());
  EXPECT_FALSE(until_stopped.StopIsEarly());
  EXPECT_FALSE(until_stopped.WorthEstimating());  // no fixes
  for (int k = 0; k < 3; ++k) until_stopped.AddFix(FixAt(k));
  EXPECT_TRUE(until_stopped.WorthEstimating());
  CalibrationRecorder timed({60.0, 0.5, {}});
  EXPECT_TRUE(timed.StopIsEarly());
}

TEST(CalibrationRecorder, RefusesImpossibleOptions) {
  EXPECT_THROW(CalibrationRecorder({-1.0, 0.5, {}}), std::invalid_argument);
  EXPECT_THROW(CalibrationRecorder({10.0, 0.0, {}}), std::invalid_argument);
  EXPECT_THROW(CalibrationRecorder({10.0, 0.5, {0.0, 3}}), std::invalid_argument);
  EXPECT_THROW(CalibrationRecorder({10.0, 0.5, {60.0, 0}}), std::invalid_argument);
}

// One encoder sample stamped a day ahead made every later, true sample "out
// of order" until the component was restarted.
TEST(CalibrationRecorder, ALoneSampleFarAheadOrBackIsRefusedAndTheStreamGoesOn) {
  CalibrationRecorder recorder({0.0, 0.5, {}});
  for (int k = 0; k < 10; ++k) EXPECT_TRUE(recorder.AddEncoders(Encoders(1.0 + 0.1 * k)));
  EXPECT_FALSE(recorder.AddEncoders(Encoders(86400.0)));  // a day ahead
  EXPECT_FALSE(recorder.AddEncoders(Encoders(-5.0)));     // far back
  for (int k = 10; k < 20; ++k) EXPECT_TRUE(recorder.AddEncoders(Encoders(1.0 + 0.1 * k)));
  EXPECT_TRUE(recorder.AddFix(FixAt(1.0)));
  EXPECT_FALSE(recorder.AddFix(FixAt(1e9)));
  EXPECT_TRUE(recorder.AddFix(FixAt(2.0)));
  const auto stats = recorder.Stats();
  EXPECT_EQ(stats.encoders, 20u);
  EXPECT_EQ(stats.encoders_out_of_order, 2u);
  EXPECT_EQ(stats.fixes, 2u);
  EXPECT_EQ(stats.fixes_rejected, 1u);
  EXPECT_EQ(stats.restarts, 0u);
  EXPECT_EQ(stats.gaps, 0u);
}

TEST(CalibrationRecorder, AClockSteppedBackRestartsAndOneSteppedForwardLeavesAGap) {
  CalibrationRecorder recorder({0.0, 0.5, {60.0, 3}});
  for (int k = 0; k < 10; ++k) recorder.AddEncoders(Encoders(1000.0 + 0.1 * k));
  recorder.AddFix(FixAt(1000.5));
  // Stepped back by NTP: the first two samples on the new clock are held out,
  // the third confirms the jump and the recording starts again from it.
  EXPECT_FALSE(recorder.AddEncoders(Encoders(500.0)));
  EXPECT_FALSE(recorder.AddEncoders(Encoders(500.1)));
  EXPECT_TRUE(recorder.AddEncoders(Encoders(500.2)));
  EXPECT_EQ(recorder.Stats().restarts, 1u);
  EXPECT_EQ(recorder.Current().encoders.size(), 1u);
  EXPECT_TRUE(recorder.Current().fixes.empty());
  EXPECT_TRUE(recorder.AddFix(FixAt(500.3)));  // the fixes follow the new clock at once
  EXPECT_TRUE(recorder.AddEncoders(Encoders(500.3)));
  // Stepped forward by two minutes: a gap, nothing forgotten.
  EXPECT_FALSE(recorder.AddEncoders(Encoders(620.0)));
  EXPECT_FALSE(recorder.AddEncoders(Encoders(620.1)));
  EXPECT_TRUE(recorder.AddEncoders(Encoders(620.2)));
  EXPECT_EQ(recorder.Stats().restarts, 1u);
  EXPECT_EQ(recorder.Current().encoders.size(), 3u);
  EXPECT_EQ(recorder.Stats().gaps, 1u);
}

}  // namespace
}  // namespace structloc::calibration_core
