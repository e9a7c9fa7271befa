// The contact benchmark's scene: soft blocks (8 x 8 x 4 cm, 8 x 8 x 4 cells of six tetrahedra:
// 1,536 each; E = 100 kPa, nu = 0.3, 500 kg/m^3) side by side in a row on a floor, touching
// their neighbours, under gravity, dt = 0.01 s: every step has contact with the floor, and with
// `bodies` between neighbours, to find and to resolve. Without the floor the blocks hang apart.
#pragma once

#include "deformable_sim/core/session/simulation.h"

namespace deformable_sim::perf {

struct BlocksOnFloor {
  int count = 1;
  bool bodies = false;  ///< effects.contact.bodies
  bool self = false;    ///< effects.contact.self
  /// false: no floor and no contact; each block instead clamped at its x = min face, swinging
  /// down under gravity (bodies that move every step, apart).
  bool floor = true;
  int threads = 1;      ///< solver.threads: the bodies step side by side on them
  bool direct = false;  ///< solver.method direct instead of CG
};

/// The scene, built; its blocks are named block0, block1, ...
core::Simulation makeBlocksOnFloor(const BlocksOnFloor& scene);

}  // namespace deformable_sim::perf
