#include "deformable_sim/core/corotational_elasticity.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "deformable_sim/core/parallel_for.h"
#include "deformable_sim/core/rotation.h"

namespace deformable_sim::core {

namespace {
constexpr int kChunkElements = 256;  ///< elements per partial sum
constexpr int kPrefetchAhead = 8;    ///< elements between a prefetch and its use in assembly
}  // namespace

CorotationalElasticity::CorotationalElasticity(const Mesh& mesh,
                                               const LinearElasticMaterial& material)
    : tetrahedra_(mesh.tetrahedra),
      rest_positions_(3 * mesh.numNodes()),
      rotations_(mesh.numElements(), Eigen::Matrix3d::Identity()),
      stiffness_(mesh),
      force_offset_(Eigen::VectorXd::Zero(3 * mesh.numNodes())) {
  validate(material);
  for (int i = 0; i < mesh.numNodes(); ++i) rest_positions_.segment<3>(3 * i) = mesh.positions[i];
  rest_.reserve(tetrahedra_.size());
  block_index_.reserve(tetrahedra_.size());
  for (const Tetrahedron& t : tetrahedra_) {
    rest_.push_back(computeTetrahedronRest(
        {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]}));
    std::array<int, 16> slots;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) slots[4 * i + j] = stiffness_.blockIndex(t[i], t[j]);
    }
    block_index_.push_back(slots);
  }
  lambda_ = lameLambda(material);
  mu_ = lameMu(material);
  setRestForces();
  listIncidences(mesh.numNodes());
  cells_.reserve(mesh.cells.size());
  for (const Cell& c : mesh.cells) {
    CellElement cell;
    cell.cell = c;
    cell.rest = computeCellRest(c.type, cellCorners(c, mesh.positions));
    for (int i = 0; i < c.size(); ++i) {
      for (int j = 0; j < c.size(); ++j) {
        cell.block_index[c.size() * i + j] = stiffness_.blockIndex(c.nodes[i], c.nodes[j]);
      }
    }
    cells_.push_back(std::move(cell));
  }
  setCellStiffness();
  // Sized here so that no step allocates them.
  const size_t chunks = (tetrahedra_.size() + cells_.size() + kChunkElements - 1) / kChunkElements;
  partial_sums_.resize(chunks);
  partial_energies_.resize(chunks);
}

void CorotationalElasticity::setCellStiffness() {
  for (CellElement& cell : cells_) {
    const int n = cell.cell.size();
    const CellVectors corners = currentCorners(cell.cell, rest_positions_);
    cell.stiffness = cellStiffness(cell.cell.type, corners, lambda_, mu_);
    Eigen::VectorXd x0(3 * n);
    for (int k = 0; k < n; ++k) x0.segment<3>(3 * k) = corners[k];
    cell.rest_forces = cell.stiffness * x0;
  }
}

CellVectors CorotationalElasticity::currentCorners(const Cell& cell, const Eigen::VectorXd& x) {
  CellVectors corners;
  for (int k = 0; k < cell.size(); ++k) corners[k] = x.segment<3>(3 * cell.nodes[k]);
  return corners;
}

void CorotationalElasticity::listIncidences(int num_nodes) {
  incidence_start_.assign(num_nodes + 1, 0);
  for (const Tetrahedron& t : tetrahedra_) {
    for (int i : t) ++incidence_start_[i + 1];
  }
  for (int i = 0; i < num_nodes; ++i) incidence_start_[i + 1] += incidence_start_[i];
  incidences_.resize(4 * tetrahedra_.size());
  std::vector<int> next(incidence_start_.begin(), incidence_start_.end() - 1);
  // Element order within each node's list: the order in which its blocks are summed.
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    for (int a = 0; a < 4; ++a)
      incidences_[next[tetrahedra_[e][a]]++] = 4 * static_cast<int>(e) + a;
  }
}

void CorotationalElasticity::setThreads(int threads) {
  threads_ = threads;
  warped_.resize(threads > 1 ? tetrahedra_.size() : 0);
  warped_.shrink_to_fit();
}

void CorotationalElasticity::setMaterial(const LinearElasticMaterial& material) {
  validate(material);
  lambda_ = lameLambda(material);
  mu_ = lameMu(material);
  setRestForces();
  setCellStiffness();
}

void CorotationalElasticity::setRestForces() {
  rest_forces_.resize(tetrahedra_.size());
  for (size_t e = 0; e < tetrahedra_.size(); ++e) {
    const Tetrahedron& t = tetrahedra_[e];
    const TetrahedronRest& rest = rest_[e];
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector3d force = Eigen::Vector3d::Zero();
      for (int j = 0; j < 4; ++j) {
        force += stiffnessBlock(lambda_ * rest.volume, mu_ * rest.volume, rest.gradients[i],
                                rest.gradients[j]) *
                 rest_positions_.segment<3>(3 * t[j]);
      }
      rest_forces_[e][i] = force;
    }
  }
}

int CorotationalElasticity::update(const Eigen::VectorXd& x, bool warping) {
  const int inverted = warping ? updateRotations(x).inverted : 0;
  if (!warping) {
    for (Eigen::Matrix3d& r : rotations_) r.setIdentity();
  }
  assemble();
  return inverted;
}

namespace {

/// Linear elasticity's energy density for a displacement gradient h, J/m^3.
double energyDensity(const Eigen::Matrix3d& h, double lambda, double mu) {
  const double trace = h.trace();
  return mu * (0.5 * (h + h.transpose())).squaredNorm() + 0.5 * lambda * trace * trace;
}

}  // namespace

CorotationalElasticity::ElementSums& CorotationalElasticity::ElementSums::operator+=(
    const ElementSums& other) {
  inverted += other.inverted;
  largest_change2 = std::max(largest_change2, other.largest_change2);
  energy += other.energy;
  energy_before += other.energy_before;
  return *this;
}

double CorotationalElasticity::tetrahedronEnergy(int e, const Eigen::Matrix3d& r,
                                                 const Eigen::Matrix3d& f) const {
  return rest_[e].volume *
         energyDensity(r.transpose() * f - Eigen::Matrix3d::Identity(), lambda_, mu_);
}

double CorotationalElasticity::cellEnergy(const CellElement& cell, const Eigen::Matrix3d& r,
                                          const Eigen::VectorXd& x) const {
  using CellVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kMaxCellNodes, 1>;
  const int n = cell.cell.size();
  CellVector u(3 * n), ku(3 * n);  // fixed capacity: no heap
  for (int i = 0; i < n; ++i) {
    const int node = cell.cell.nodes[i];
    u.segment<3>(3 * i) =
        r.transpose() * x.segment<3>(3 * node) - rest_positions_.segment<3>(3 * node);
  }
  ku.noalias() = cell.stiffness * u;
  return 0.5 * u.dot(ku);
}

Eigen::Matrix3d CorotationalElasticity::elementDeformationGradient(int e,
                                                                   const Eigen::VectorXd& x) const {
  const int num_tetrahedra = static_cast<int>(tetrahedra_.size());
  if (e < num_tetrahedra) {
    const Tetrahedron& t = tetrahedra_[e];
    return deformationGradient(rest_[e], x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
                               x.segment<3>(3 * t[2]), x.segment<3>(3 * t[3]));
  }
  // Other cells: F at the centre.
  const CellElement& cell = cells_[e - num_tetrahedra];
  return cellDeformationGradient(cell.rest, cell.cell.size(), currentCorners(cell.cell, x));
}

double CorotationalElasticity::elementEnergy(int e, const Eigen::Matrix3d& r,
                                             const Eigen::Matrix3d& f,
                                             const Eigen::VectorXd& x) const {
  const int num_tetrahedra = static_cast<int>(tetrahedra_.size());
  return e < num_tetrahedra ? tetrahedronEnergy(e, r, f)
                            : cellEnergy(cells_[e - num_tetrahedra], r, x);
}

CorotationalElasticity::RotationUpdate CorotationalElasticity::updateRotations(
    const Eigen::VectorXd& x) {
  // Each element's new rotation, how far it turned, and its energy with the new and the old one.
  // Chunk by chunk, the rotations a batch at a time, the sums in element order.
  const int num_elements = static_cast<int>(rotations_.size());
  const int num_chunks = (num_elements + kChunkElements - 1) / kChunkElements;
  const ElementSums sums =
      parallelChunkedSum(threads_, 0, num_chunks, 1, partial_sums_, [&](int chunk) {
        ElementSums chunk_sums;
        const int end = std::min(num_elements, (chunk + 1) * kChunkElements);
        for (int first = chunk * kChunkElements; first < end; first += kRotationBatch) {
          const int count = std::min(kRotationBatch, end - first);
          std::array<Eigen::Matrix3d, kRotationBatch> f, r;
          for (int k = 0; k < count; ++k) f[k] = elementDeformationGradient(first + k, x);
          extractRotations(f.data(), r.data(), count);
          for (int k = 0; k < count; ++k) {
            const int e = first + k;
            ElementSums one;
            one.inverted = f[k].determinant() > 0.0 ? 0 : 1;
            one.energy = elementEnergy(e, r[k], f[k], x);
            one.energy_before = elementEnergy(e, rotations_[e], f[k], x);
            one.largest_change2 = (r[k] - rotations_[e]).squaredNorm();
            rotations_[e] = r[k];
            chunk_sums += one;
          }
        }
        return chunk_sums;
      });
  RotationUpdate update;
  update.inverted = sums.inverted;
  update.largest_change = 2.0 * std::asin(std::min(1.0, std::sqrt(sums.largest_change2 / 8.0)));
  update.energy = sums.energy;
  update.energy_before = sums.energy_before;
  return update;
}

CorotationalElasticity::WarpedElement CorotationalElasticity::warp(int e) const {
  const double root_volume = std::sqrt(rest_[e].volume);
  WarpedElement w;
  for (int a = 0; a < 4; ++a) {
    w.gradients[a].noalias() = root_volume * (rotations_[e] * rest_[e].gradients[a]);
    w.offsets[a].noalias() = rotations_[e] * rest_forces_[e][a];
  }
  return w;
}

void CorotationalElasticity::assemble() {
  // Every block sums its elements' contributions in element order, whichever way is taken.
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  const std::vector<int>& row_start = stiffness_.rowStart();
  const int num_nodes = stiffness_.numBlockRows();
  if (threads_ == 1) {
    // Element by element, each symmetric pair of blocks computed once and added to the upper
    // one of the two; the lower ones are copied as transposes at the end.
    for (int i = 0; i < num_nodes; ++i) {
      for (int s = stiffness_.diagonalIndex(i); s < row_start[i + 1]; ++s) blocks[s].setZero();
    }
    force_offset_.setZero();
    const int num_tetrahedra = static_cast<int>(tetrahedra_.size());
    // The upper block of corners a and b of element e.
    auto upperSlot = [&](int e, int a, int b) {
      const Tetrahedron& t = tetrahedra_[e];
      return t[a] <= t[b] ? block_index_[e][4 * a + b] : block_index_[e][4 * b + a];
    };
    for (int e = 0; e < num_tetrahedra; ++e) {
      if (e + kPrefetchAhead < num_tetrahedra) {
        // The blocks a later element adds into are scattered over four rows: ask for them now.
        for (int a = 0; a < 4; ++a) {
          for (int b = a; b < 4; ++b) {
            const char* block =
                reinterpret_cast<const char*>(blocks.data() + upperSlot(e + kPrefetchAhead, a, b));
            __builtin_prefetch(block, 1);
            __builtin_prefetch(block + sizeof(Eigen::Matrix3d) - 1, 1);
          }
        }
      }
      const WarpedElement w = warp(e);
      const Tetrahedron& t = tetrahedra_[e];
      for (int a = 0; a < 4; ++a) {
        blocks[block_index_[e][5 * a]] +=
            stiffnessBlock(lambda_, mu_, w.gradients[a], w.gradients[a]);
        for (int b = a + 1; b < 4; ++b) {
          const Eigen::Matrix3d k = stiffnessBlock(lambda_, mu_, w.gradients[a], w.gradients[b]);
          if (t[a] < t[b]) {
            blocks[block_index_[e][4 * a + b]] += k;
          } else {
            blocks[block_index_[e][4 * b + a]] += k.transpose();
          }
        }
        force_offset_.segment<3>(3 * t[a]) -= w.offsets[a];
      }
    }
    copyLowerBlocks();
    addCells();
    return;
  }
  // On several threads, row by row: rows are disjoint, so no two threads add into one block.
  // Each row sums its diagonal and upper blocks in element order, as the element path does;
  // the lower ones are then copied as transposes.
  parallelFor(threads_, 0, static_cast<int>(tetrahedra_.size()),
              [&](int e) { warped_[e] = warp(e); });
  parallelFor(threads_, 0, num_nodes, [&](int i) {
    for (int s = stiffness_.diagonalIndex(i); s < row_start[i + 1]; ++s) blocks[s].setZero();
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    const int last = static_cast<int>(incidences_.size()) - 1;
    for (int k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k) {
      const char* ahead = reinterpret_cast<const char*>(
          &warped_[incidences_[std::min(k + kPrefetchAhead, last)] / 4]);
      for (size_t byte = 0; byte < sizeof(WarpedElement); byte += 64)
        __builtin_prefetch(ahead + byte);
      const int e = incidences_[k] / 4, a = incidences_[k] % 4;
      const WarpedElement& w = warped_[e];
      for (int b = 0; b < 4; ++b) {
        if (tetrahedra_[e][b] < i) continue;
        blocks[block_index_[e][4 * a + b]] +=
            stiffnessBlock(lambda_, mu_, w.gradients[a], w.gradients[b]);
      }
      offset -= w.offsets[a];
    }
    force_offset_.segment<3>(3 * i) = offset;
  });
  copyLowerBlocks();
  addCells();
}

void CorotationalElasticity::copyLowerBlocks() {
  // Once every upper block is summed: the lower ones are their exact transposes.
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  const std::vector<int>& row_start = stiffness_.rowStart();
  const std::vector<int>& transpose = stiffness_.transposeIndex();
  parallelFor(threads_, 0, stiffness_.numBlockRows(), [&](int i) {
    for (int s = row_start[i]; s < stiffness_.diagonalIndex(i); ++s) {
      blocks[s] = blocks[transpose[s]].transpose();
    }
  });
}

void CorotationalElasticity::addCells() {
  // After every tetrahedron, in cell order, on one thread: the same sums on any thread count.
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  const int num_tetrahedra = static_cast<int>(tetrahedra_.size());
  for (size_t c = 0; c < cells_.size(); ++c) {
    const CellElement& cell = cells_[c];
    const Eigen::Matrix3d& r = rotations_[num_tetrahedra + c];
    const int n = cell.cell.size();
    for (int i = 0; i < n; ++i) {
      blocks[cell.block_index[n * i + i]] +=
          r * cell.stiffness.block<3, 3>(3 * i, 3 * i) * r.transpose();
      for (int j = i + 1; j < n; ++j) {  // K'_ji = K'_ij^T
        const Eigen::Matrix3d warped = r * cell.stiffness.block<3, 3>(3 * i, 3 * j) * r.transpose();
        blocks[cell.block_index[n * i + j]] += warped;
        blocks[cell.block_index[n * j + i]] += warped.transpose();
      }
      force_offset_.segment<3>(3 * cell.cell.nodes[i]) -= r * cell.rest_forces.segment<3>(3 * i);
    }
  }
}

void CorotationalElasticity::addElasticForces(const Eigen::VectorXd& x, Eigen::VectorXd& f,
                                              Eigen::VectorXd& scratch) const {
  stiffness_.multiply(x, scratch);
  f -= scratch + force_offset_;
}

double CorotationalElasticity::elasticEnergy(const Eigen::VectorXd& x) const {
  return parallelChunkedSum(
      threads_, 0, static_cast<int>(rotations_.size()), kChunkElements, partial_energies_,
      [&](int e) { return elementEnergy(e, rotations_[e], elementDeformationGradient(e, x), x); });
}

}  // namespace deformable_sim::core
