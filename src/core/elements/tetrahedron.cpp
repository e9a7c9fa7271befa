#include "deformable_sim/core/elements/tetrahedron.h"

#include <Eigen/LU>

#include "deformable_sim/core/elements/mesh.h"

namespace deformable_sim::core {

TetrahedronRest computeTetrahedronRest(const std::array<Eigen::Vector3d, 4>& x) {
  TetrahedronRest rest;
  Eigen::Matrix3d dm;
  dm.col(0) = x[1] - x[0];
  dm.col(1) = x[2] - x[0];
  dm.col(2) = x[3] - x[0];
  rest.volume = signedVolume(x[0], x[1], x[2], x[3]);
  // N_i = barycentric coordinate i; rows of Dm^-1 are grad N_1..N_3, and the gradients sum to
  // zero because the N_i sum to one.
  const Eigen::Matrix3d dm_inverse = dm.inverse();
  for (int i = 1; i < 4; ++i) rest.gradients[i] = dm_inverse.row(i - 1).transpose();
  rest.gradients[0] = -(rest.gradients[1] + rest.gradients[2] + rest.gradients[3]);
  return rest;
}

ElementBlocks elementStiffness(const TetrahedronRest& rest, const LinearElasticMaterial& material) {
  const double lambda_volume = lameLambda(material) * rest.volume;
  const double mu_volume = lameMu(material) * rest.volume;
  ElementBlocks k;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      k[i][j] = stiffnessBlock(lambda_volume, mu_volume, rest.gradients[i], rest.gradients[j]);
    }
  }
  return k;
}

}  // namespace deformable_sim::core
