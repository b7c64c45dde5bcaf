#pragma once
// An Xvfb server of the test program's own, for the viewer's tests.

#include <sys/types.h>

#include <string>

namespace geolens::testing {

/// Starts Xvfb (a 1280 x 1024 x 24 screen, local connections only, no reset between clients) on
/// a display number the server picks itself (-displayfd), so tests in parallel processes never
/// race for one, and stops it on destruction; the server also ends with the test program.
/// xvfb-run is not used: it exits 5 ("problem while cleaning up temporary directory") when the X
/// server's reset signal reaches it while it removes its folder, which a program that fails fast
/// meets often.
class XDisplay {
 public:
  /// Throws std::runtime_error when Xvfb is missing or does not start.
  XDisplay();
  ~XDisplay();
  XDisplay(const XDisplay&) = delete;
  XDisplay& operator=(const XDisplay&) = delete;

  /// The display's name, e.g. ":3".
  const std::string& name() const { return name_; }

 private:
  pid_t pid_ = -1;
  std::string name_;
};

}  // namespace geolens::testing
