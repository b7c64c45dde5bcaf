#include "interrupt.h"

#include <csignal>
#include <stdexcept>

namespace geolens::cli {

namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
// The process's signal dispositions are process state: the one run they guard, and what they
// were before it.
const RunFiles* guarded = nullptr;
struct sigaction before[3];

extern "C" void remove_and_die(int signal) {
  if (guarded) guarded->remove_temporaries();
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

RemoveOnInterrupt::RemoveOnInterrupt(const RunFiles& files) {
  if (guarded) throw std::logic_error("RemoveOnInterrupt: one run at a time");
  guarded = &files;
  struct sigaction action {};
  action.sa_handler = remove_and_die;
  sigemptyset(&action.sa_mask);
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &action, &before[k]);
}

RemoveOnInterrupt::~RemoveOnInterrupt() {
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &before[k], nullptr);
  guarded = nullptr;
}

}  // namespace geolens::cli
