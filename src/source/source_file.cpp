#include "geolens/source/source_file.h"

#include "geolens/io/image.h"
#include "geolens/source/mip_pyramid.h"

namespace geolens {

SourceFile image_source(const Image& image) {
  SourceFile file;
  file.source = std::make_shared<const MipPyramid>(image);
  file.frame_width = image.width;
  file.frame_height = image.height;
  file.kind = "image";
  return file;
}

SourceFile open_source(const std::string& path, const SourceFileOptions&) {
  // Each kind of source file has its branch here, by extension (or a folder), before the image.
  return image_source(load_image(path));
}

}  // namespace geolens
