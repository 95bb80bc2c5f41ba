// Compiled with the native build's flags by tests/CMakeLists.txt: Eigen calls FMA intrinsics
// whenever the target has FMA, so this product shows whether those flags leave them out.
#include <Eigen/Dense>

namespace vorodec {

Eigen::Matrix4d fma_probe_product(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return a * b;
}

}  // namespace vorodec
