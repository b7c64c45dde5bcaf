#include "support/cli_runner.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace geolens::testing {

CliRun run_cli(const std::string& arguments, const std::string& stderr_path) {
  const std::string command =
      std::string(GEOLENS_CLI) + " " + arguments + " > /dev/null 2> " + stderr_path;
  const int status = std::system(command.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(stderr_path);
  std::stringstream s;
  s << in.rdbuf();
  r.err = s.str();
  return r;
}

}  // namespace geolens::testing
