// Fuzzes PLY meshes: the input is a PLY file (ascii or binary) opened as a source of 16 x 16
// pixels (open_source, as the CLI opens it: load_ply, then the mesh renderer) and, if it reads,
// drawn whole.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("input.ply", data, size);
  fuzz::open_and_draw(path, 16);
  return 0;
}
