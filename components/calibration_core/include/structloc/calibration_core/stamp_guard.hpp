// The stamps of one stream of samples (wheel encoders, or pose fixes), kept
// in order without letting one sample far out of line stop the stream: a
// sample stamped a day ahead (a writer with a wrong clock, or any writer on an
// unsecured domain) would otherwise make every later, true sample "out of
// order", and a clock stepped back by NTP would do the same for good. A sample
// that jumps forward by more than max_jump_s, or goes back, is held out; it
// is taken only when the next confirm_samples - 1 samples continue from it
// (the clock really jumped), and a lone one is forgotten when the stream goes
// on where it was. DDS-free.
#pragma once

#include <optional>

namespace structloc::calibration_core {

struct StampGuardOptions {
  double max_jump_s = 60.0;  // a longer step forward is out of line until confirmed
  int confirm_samples = 3;   // samples in line with an out-of-line one that confirm it
};

class StampGuard {
 public:
  enum class Verdict {
    kNext,           // after the last sample, within max_jump_s: take it
    kOutOfLine,      // back, or too far ahead, not (yet) confirmed: refuse it
    kJumpedForward,  // confirms a jump forward: take it (a gap in the stream)
    kJumpedBack,     // confirms a jump back: the stream restarts from it
  };

  // Throws std::invalid_argument when max_jump_s is not positive or
  // confirm_samples is below 1.
  explicit StampGuard(const StampGuardOptions& options = {});
  Verdict Check(double t);
  // The newest stamp taken, if any.
  std::optional<double> Last() const { return last_; }

 private:
  StampGuardOptions options_;
  std::optional<double> last_;
  std::optional<double> held_;  // the newest out-of-line stamp
  int held_count_ = 0;          // out-of-line samples in line with one another
};

}  // namespace structloc::calibration_core
