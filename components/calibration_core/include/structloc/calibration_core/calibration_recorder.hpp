// Records what an odometry calibration (thesis 6.5.4) is estimated from, the
// policy the live calibration component holds apart from DDS: encoder samples
// in stamp order (out-of-order ones counted and refused; a lone sample far
// ahead or back is refused too, and a confirmed jump back restarts the
// recording: StampGuard), gaps in the encoder
// stream detected and counted (never silently bridged: the estimate sees
// them), fixes with a finite pose in stamp order, when the recording is long
// enough to calibrate, and whether a stop leaves enough to estimate from.
// Single-threaded: the component guards it.
#pragma once

#include <cstddef>
#include <vector>

#include "structloc/calibration_core/calibration_data.hpp"
#include "structloc/calibration_core/stamp_guard.hpp"

namespace structloc::calibration_core {

struct RecorderOptions {
  double record_s = 60.0;          // recording length in stamp time; 0 = until stopped
  double max_encoder_gap_s = 0.5;  // longer steps between encoder samples are gaps
  StampGuardOptions stamps;        // each stream's stamps (a jump back restarts both)
};

struct RecorderStats {
  size_t encoders = 0, fixes = 0;
  size_t encoders_out_of_order = 0, fixes_rejected = 0, gaps = 0;
  double largest_gap_s = 0.0;
  size_t restarts = 0;  // confirmed jumps back of a stream's stamps (clock stepped back)
};

struct Recording {
  std::vector<EncoderSample> encoders;
  std::vector<Fix> fixes;
};

class CalibrationRecorder {
 public:
  explicit CalibrationRecorder(const RecorderOptions& options);

  // Return false when the sample was refused (out of order or out of line,
  // not finite, or the recording has ended). A sample that confirms a jump
  // back of its stream's stamps restarts the recording from it.
  bool AddEncoders(const EncoderSample& sample);
  bool AddFix(const Fix& fix);

  // The recording has reached record_s of stamp time: calibrate now.
  bool Due() const;
  // At a stop: whether what was recorded is worth an estimate.
  bool WorthEstimating() const;
  // A stop before record_s: its estimate is a bonus whose failure is no error
  // ("until stopped" recordings end at the stop as planned).
  bool StopIsEarly() const { return options_.record_s > 0; }

  // Ends the recording (later samples are ignored) and returns it.
  Recording Finish();
  // What was recorded so far (the recording goes on).
  const Recording& Current() const { return recording_; }
  // Drops the samples stamped before `t` (a sliding window); the counts of
  // refused samples and gaps stay.
  void ForgetBefore(double t);
  bool Finished() const { return finished_; }
  RecorderStats Stats() const;

 private:
  // A confirmed jump back: what was recorded is on another clock.
  void Restart();
  // Whether a sample stamped `t` of `stream` is taken (a refusal is counted
  // in `refused`; a confirmed jump back restarts the recording first).
  bool Admit(StampGuard CalibrationRecorder::*stream, double t, size_t* refused);

  RecorderOptions options_;
  StampGuard encoder_stamps_, fix_stamps_;
  Recording recording_;
  RecorderStats stats_;
  bool finished_ = false;
};

}  // namespace structloc::calibration_core
