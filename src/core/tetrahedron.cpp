#include "deformable_sim/core/tetrahedron.h"

#include <Eigen/LU>

#include "deformable_sim/core/mesh.h"

namespace deformable_sim::core {

TetrahedronRest computeTetrahedronRest(const std::array<Eigen::Vector3d, 4>& x,
                                       const LinearElasticMaterial& material) {
  TetrahedronRest rest;
  Eigen::Matrix3d dm;
  dm.col(0) = x[1] - x[0];
  dm.col(1) = x[2] - x[0];
  dm.col(2) = x[3] - x[0];
  rest.volume = signedVolume(x[0], x[1], x[2], x[3]);
  rest.rest_edges_inverse = dm.inverse();

  // N_i = barycentric coordinate i; rows of Dm^-1 are grad N_1..N_3, and the gradients sum to
  // zero because the N_i sum to one.
  for (int i = 1; i < 4; ++i) rest.gradients[i] = rest.rest_edges_inverse.row(i - 1).transpose();
  rest.gradients[0] = -(rest.gradients[1] + rest.gradients[2] + rest.gradients[3]);

  // Strain-displacement matrix B_i (6x3, Voigt order xx yy zz xy xz yz, engineering shear).
  std::array<Eigen::Matrix<double, 6, 3>, 4> b;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d& g = rest.gradients[i];
    b[i] << g.x(), 0, 0,  //
        0, g.y(), 0,      //
        0, 0, g.z(),      //
        g.y(), g.x(), 0,  //
        g.z(), 0, g.x(),  //
        0, g.z(), g.y();
  }
  const Eigen::Matrix<double, 6, 6> d = elasticityMatrix(material);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      rest.stiffness[i][j] = rest.volume * b[i].transpose() * d * b[j];
    }
  }
  return rest;
}

}  // namespace deformable_sim::core
