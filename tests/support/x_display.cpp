#include "support/x_display.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <stdexcept>
#include <string>

namespace geolens::testing {

XDisplay::XDisplay() {
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0) throw std::runtime_error("XDisplay: pipe failed");
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("XDisplay: fork failed");
  if (pid_ == 0) {
    // The server: ends with the test program, writes nothing to its output (which would keep
    // ctest waiting on the pipe), and writes its display number to the pipe once it is ready.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::close(pipe_ends[0]);
    const std::string fd = std::to_string(pipe_ends[1]);
    ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x1024x24", "-nolisten",
             "tcp", "-noreset", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(pipe_ends[1]);
  std::string number;
  char c;
  while (::read(pipe_ends[0], &c, 1) == 1 && c != '\n') number += c;
  ::close(pipe_ends[0]);
  if (number.empty() || !std::isdigit(static_cast<unsigned char>(number[0]))) {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
    throw std::runtime_error("XDisplay: Xvfb did not start (is the xvfb package installed?)");
  }
  name_ = ":" + number;
}

XDisplay::~XDisplay() {
  ::kill(pid_, SIGTERM);
  ::waitpid(pid_, nullptr, 0);
}

}  // namespace geolens::testing
