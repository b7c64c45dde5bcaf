#include "geolens/io/mesh_io.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iomanip>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

void write_obj(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixX3i& F) {
  require(V.cols() == 2 || V.cols() == 3, "write_obj",
          "vertices must have 2 or 3 columns, got " + std::to_string(V.cols()));
  std::ostringstream out;
  out << std::setprecision(17);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    out << "v " << V(i, 0) << ' ' << V(i, 1) << ' ' << (V.cols() == 3 ? V(i, 2) : 0.0) << '\n';
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out << "f " << F(f, 0) + 1 << ' ' << F(f, 1) + 1 << ' ' << F(f, 2) + 1 << '\n';
  }
  write_file(path, out.str());
}

}  // namespace geolens
