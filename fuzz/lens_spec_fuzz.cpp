// Fuzzes lens specs: the input is the text of a --lens spec (circle:CX,CY,R[:ZOOM],
// polygon:FILE[:ZOOM], mask:FILE[:ZOOM]) read by parse_lens_spec for a 64 x 48 image. The files
// a spec may name are fixtures made at start in the scratch folder: "square" (a polygon), "mask"
// (a 64 x 48 mask of two blobs and a speck) and "junk" (neither); a spec naming a path with a
// '/' is skipped (the fuzzer must not read the machine's files), any other name is looked up in
// the scratch folder.
// A finding: a crash, a sanitizer report, an exception other than InvalidInput, a hang, an
// allocation past libFuzzer's limit.
#include "fuzz_support.h"
#include "geolens/lens/lens_spec.h"

namespace {

void make_fixtures() {
  using namespace geolens;
  std::ofstream(fuzz::scratch() / "square") << "10 10\n30 10\n30 30\n10 30\n";
  std::ofstream(fuzz::scratch() / "junk") << "not a polygon nor an image\n";
  Image mask(64, 48, 1);
  for (int y = 5; y < 20; ++y)
    for (int x = 5; x < 25; ++x) *mask.at(x, y) = 255;
  for (int y = 25; y < 45; ++y)
    for (int x = 35; x < 60; ++x) *mask.at(x, y) = 255;
  *mask.at(62, 2) = 255;
  save_image((fuzz::scratch() / "mask.png").string(), mask);
  fuzz::fs::rename(fuzz::scratch() / "mask.png", fuzz::scratch() / "mask");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  make_fixtures();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace geolens;
  std::string spec(reinterpret_cast<const char*>(data), size);
  if (const std::optional<LensSpecFile> file = lens_spec_file(spec)) {
    if (file->path.find('/') != std::string::npos) return 0;
    // KIND:FILE[:ZOOM] with FILE in the scratch folder.
    spec = file->kind + ":" + (fuzz::scratch() / file->path).string() +
           spec.substr(file->kind.size() + 1 + file->path.size());
  }
  fuzz::read_or_refuse([&] {
    std::vector<std::string> warnings;
    parse_lens_spec(spec, 2, Profile::kGaussian, 0, 64, 48, &warnings);
  });
  return 0;
}
