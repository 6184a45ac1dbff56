// The calibration recorder without any middleware: what it keeps, what it
// refuses and counts, gap detection, and when a calibration is due.
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
  CalibrationRecorder recorder({60.0, 0.5});
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
  CalibrationRecorder recorder({60.0, 0.5});
  EXPECT_TRUE(recorder.AddFix(FixAt(1.0)));
  EXPECT_FALSE(recorder.AddFix(FixAt(2.0, NAN)));
  EXPECT_FALSE(recorder.AddFix(FixAt(1.0)));
  EXPECT_TRUE(recorder.AddFix(FixAt(2.0)));
  EXPECT_EQ(recorder.Stats().fixes, 2u);
  EXPECT_EQ(recorder.Stats().fixes_rejected, 2u);
}

TEST(CalibrationRecorder, IsDueOnceTheEncodersSpanTheRecordingLength) {
  CalibrationRecorder recorder({10.0, 0.5});
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
  CalibrationRecorder until_stopped({0.0, 0.5});
  for (int k = 0; k < 1000; ++k) until_stopped.AddEncoders(Encoders(0.1 * k));
  EXPECT_FALSE(until_stopped.Due());
  EXPECT_FALSE(until_stopped.StopIsEarly());
  EXPECT_FALSE(until_stopped.WorthEstimating());  // no fixes
  for (int k = 0; k < 3; ++k) until_stopped.AddFix(FixAt(k));
  EXPECT_TRUE(until_stopped.WorthEstimating());
  CalibrationRecorder timed({60.0, 0.5});
  EXPECT_TRUE(timed.StopIsEarly());
}

TEST(CalibrationRecorder, RefusesImpossibleOptions) {
  EXPECT_THROW(CalibrationRecorder({-1.0, 0.5}), std::invalid_argument);
  EXPECT_THROW(CalibrationRecorder({10.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace structloc::calibration_core
