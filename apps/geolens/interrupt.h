#pragma once
// A run interrupted by a signal leaves no temporary file behind.

#include "geolens/io/run_files.h"

namespace geolens::cli {

/// While it lives, SIGINT, SIGTERM and SIGHUP remove `files`' temporary files and the folders it
/// made (RunFiles::remove_temporaries), then end the process by the signal as before (exit code
/// 128 + the signal's number in a shell). One at a time; the handlers before it come back when
/// it goes. (SIGKILL cannot be caught: a run killed so may leave STEM.tmp-PID-N.EXT files.)
class RemoveOnInterrupt {
 public:
  explicit RemoveOnInterrupt(const RunFiles& files);
  ~RemoveOnInterrupt();
  RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
  RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;
};

}  // namespace geolens::cli
