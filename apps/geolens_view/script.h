#pragma once
// The scripted-event player of geolens-view: a text file of timed events (lens moves, zooms,
// option changes, mouse input, screenshots) that drives the viewer without a person, for tests,
// pictures and measurements. The grammar is in the README ("Viewer", "Scripts").

#include <Eigen/Core>
#include <string>
#include <vector>

#include "viewer.h"

namespace geolens::view {

/// One line of a script: at frame `frame` (counted from 0, the first drawn frame), `command`
/// with its arguments, as written.
struct ScriptEvent {
  int frame = 0;
  std::string command;
  std::vector<std::string> args;
  int line = 0;  ///< 1-based line in the file, for messages
};

/// Reads and checks a script: every command known, its argument count and every number, option
/// name and screenshot path valid, frames non-decreasing. `input_image` (may be empty) is the
/// viewer's input, which no screenshot may overwrite. Throws InvalidInput("script FILE:LINE:
/// ...") for the first bad line, or naming the file if it cannot be read.
std::vector<ScriptEvent> parse_script(const std::string& path, const std::string& input_image);

/// Throws InvalidInput naming `what` unless `path` ends in .png, .jpg or .jpeg, its folder
/// exists and it is not the file `input_image` (so a screenshot never overwrites the input).
void check_screenshot_path(const std::string& path, const std::string& input_image,
                           const std::string& what);

/// Where a ScriptEvent came from, for messages: "script FILE:LINE".
std::string where(const std::string& script, const ScriptEvent& event);

/// What a frame's events ask of the frame loop.
struct ScriptActions {
  struct Shot {
    std::string path;
    bool panel = false;  ///< with the panel drawn over the picture
  };
  std::vector<Shot> screenshots;  ///< taken once the solver is idle, after this frame is drawn
  bool quit = false;
};

/// Plays a parsed script on a Viewer: at each frame, the events due then, and one step of each
/// drag under way.
class ScriptRunner {
 public:
  ScriptRunner() = default;
  ScriptRunner(std::string path, std::vector<ScriptEvent> events);
  /// Applies what is due at `frame` (counted from 0) to `viewer`. Throws InvalidInput("script
  /// FILE:LINE: ...") for an event the viewer refuses (a lens number that does not exist).
  ScriptActions step(int frame, Viewer& viewer);
  bool active() const { return !events_.empty(); }

 private:
  struct Drag {
    ScriptEvent event;
    size_t lens;
    Eigen::Vector2d from, to;
    int steps, done = 0;
  };
  void apply(const ScriptEvent& e, Viewer& viewer, ScriptActions& actions);

  std::string path_;
  std::vector<ScriptEvent> events_;
  size_t next_ = 0;
  std::vector<Drag> drags_;
};

}  // namespace geolens::view
