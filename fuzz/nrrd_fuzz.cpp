// Fuzzes NRRD volumes: the input is a NRRD file (.nrrd) opened as a source of 4 x 4 pixels
// (open_source, as the CLI opens it: load_nrrd, then the volume renderer with its default
// transfer function) and, if it reads, drawn whole. An input whose header names a detached data
// file (nrrd_data_path) outside the scratch folder is skipped, so that the fuzzer reads none of
// the machine's files; one inside it is the input itself, or missing.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "render3d/nrrd_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  const std::string path = fuzz::write_input("input.nrrd", data, size);
  if (const std::string detached = nrrd_data_path(path); !detached.empty()) {
    std::error_code error;
    const fuzz::fs::path inside = fuzz::fs::weakly_canonical(detached, error);
    const std::string folder = fuzz::fs::weakly_canonical(fuzz::scratch(), error).string() + "/";
    if (error || inside.string().compare(0, folder.size(), folder) != 0) return 0;
  }
  fuzz::open_and_draw(path, 4);
  return 0;
}
