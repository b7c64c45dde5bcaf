#include "geolens/core/solve_control.h"

#include <string>

#include "geolens/core/errors.h"

namespace geolens {

void SolveControl::step(const SolveProgress& p, const char* function) const {
  if (progress) progress(p);
  if (cancel != nullptr && cancel->load(std::memory_order_relaxed))
    throw Cancelled(std::string(function) + ": cancelled");
}

}  // namespace geolens
