// Fuzzes NIfTI volumes: the input is a NIfTI-1 file (.nii) opened as a source of 4 x 4 pixels
// (open_source, as the CLI opens it: load_nifti, libnifti behind the library's own header checks,
// then the volume renderer with its default transfer function) and, if it reads, drawn whole.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("input.nii", data, size);
  fuzz::open_and_draw(path, 4);
  return 0;
}
