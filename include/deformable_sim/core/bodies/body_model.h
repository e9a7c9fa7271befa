// How a body moves: the three kinematic models of seed 004 (Solfec-1.0).
#pragma once

namespace deformable_sim::core {

enum class BodyModel {
  kFiniteElement,  ///< every node moves: warped-stiffness FEM over the mesh's elements
  kPseudoRigid,    ///< x = c + F (X - Xc): a centre and a homogeneous deformation gradient, 12 DOF
  kRigid,          ///< x = c + R (X - Xc): a centre and a rotation, 6 DOF
};

/// The scene file's name of a model: "fem", "pseudo_rigid", "rigid".
inline const char* modelName(BodyModel model) {
  switch (model) {
    case BodyModel::kPseudoRigid:
      return "pseudo_rigid";
    case BodyModel::kRigid:
      return "rigid";
    default:
      return "fem";
  }
}

}  // namespace deformable_sim::core
