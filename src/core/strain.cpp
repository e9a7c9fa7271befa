#include "deformable_sim/core/strain.h"

#include <algorithm>

#include "deformable_sim/core/rotation.h"
#include "deformable_sim/core/tetrahedron.h"

namespace deformable_sim::core {

void nodalStrain(const FemBody& body, std::vector<double>& strain) {
  strain.assign(body.numNodes(), 0.0);
  const Eigen::VectorXd& x = body.positions();
  const std::vector<TetrahedronRest>& rest = body.elasticity().restData();
  const std::vector<Tetrahedron>& tetrahedra = body.mesh().tetrahedra;
  for (size_t e = 0; e < tetrahedra.size(); ++e) {
    const Tetrahedron& t = tetrahedra[e];
    const Eigen::Matrix3d f =
        deformationGradient(rest[e], x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                            x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3]));
    const Eigen::Matrix3d unrotated = extractRotation(f).transpose() * f;
    const double magnitude =
        (0.5 * (unrotated + unrotated.transpose()) - Eigen::Matrix3d::Identity()).norm();
    for (int i : t) strain[i] = std::max(strain[i], magnitude);
  }
}

}  // namespace deformable_sim::core
