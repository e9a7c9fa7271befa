#include "deformable_sim/core/elements/corotational_elasticity.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "deformable_sim/core/base/cpu_features.h"
#include "deformable_sim/core/base/parallel_for.h"
#include "deformable_sim/core/base/rotation.h"
#include "deformable_sim/core/elements/incompatible_modes.h"

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
      stiffness_(nodeNeighbours(mesh)),
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
  incompatible_modes_ = mesh.incompatible_modes;
  cells_.reserve(mesh.cells.size());
  for (size_t e = 0; e < mesh.cells.size(); ++e) {
    const Cell& c = mesh.cells[e];
    CellElement cell;
    cell.cell = c;
    if (const OctantFractions* fractions = mesh.cellOctants(e)) cell.fractions = *fractions;
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
  warped_.resize(tetrahedra_.size());
  const size_t chunks = (tetrahedra_.size() + cells_.size() + kChunkElements - 1) / kChunkElements;
  partial_sums_.resize(chunks);
  partial_energies_.resize(chunks);
}

void CorotationalElasticity::setCellStiffness() {
  for (CellElement& cell : cells_) {
    const int n = cell.cell.size();
    const CellVectors corners = currentCorners(cell.cell, rest_positions_);
    // A partial cell: the stiffness of its material, where it is.
    cell.stiffness = incompatible_modes_ && cell.cell.type == CellType::kHexahedron &&
                             incompatibleModesApply(cell.fractions)
                         ? incompatibleModesStiffness(corners, lambda_, mu_, &cell.fractions)
                         : cellStiffness(cell.cell.type, corners, lambda_, mu_, &cell.fractions);
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

void CorotationalElasticity::setThreads(int threads) { threads_ = threads; }

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
    return core::deformationGradient(rest_[e], x.segment<3>(3 * t[0]), x.segment<3>(3 * t[1]),
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
  // Row by row, on any number of threads: rows are disjoint, so no two threads add into one
  // block, and each row sums its diagonal and upper blocks in element order. (Element by element
  // on one thread was slower than this once the blocks were computed 4-wide.)
#if defined(__x86_64__)
  if (hasAvx2Fma()) {
    parallelFor(threads_, 0, static_cast<int>(tetrahedra_.size()), [&](int e) { warpAvx2(e); });
    parallelFor(threads_, 0, stiffness_.numBlockRows(), [&](int i) { assembleRowAvx2(i); });
    addCells();
    return;
  }
#endif
  parallelFor(threads_, 0, static_cast<int>(tetrahedra_.size()),
              [&](int e) { warped_[e] = warp(e); });
  parallelFor(threads_, 0, stiffness_.numBlockRows(), [&](int i) { assembleRowPortable(i); });
  addCells();
}

void CorotationalElasticity::startRow(int i) {
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  for (int s = stiffness_.diagonalIndex(i); s < stiffness_.rowStart()[i + 1]; ++s) {
    blocks[s].setZero();
  }
}

void CorotationalElasticity::finishRow(int i, const Eigen::Vector3d& offset) {
  force_offset_.segment<3>(3 * i) = offset;
  // Row i's upper blocks are summed: their transposes are the lower blocks of later rows.
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  const std::vector<int>& transpose = stiffness_.transposeIndex();
  for (int s = stiffness_.diagonalIndex(i) + 1; s < stiffness_.rowStart()[i + 1]; ++s) {
    blocks[transpose[s]] = blocks[s].transpose();
  }
}

void CorotationalElasticity::assembleRowPortable(int i) {
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  startRow(i);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  const int last = static_cast<int>(incidences_.size()) - 1;
  for (int k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k) {
    prefetchWarped(incidences_[std::min(k + kPrefetchAhead, last)] / 4);
    const int e = incidences_[k] / 4, a = incidences_[k] % 4;
    const WarpedElement& w = warped_[e];
    for (int b = 0; b < 4; ++b) {
      if (tetrahedra_[e][b] < i) continue;
      blocks[block_index_[e][4 * a + b]] +=
          stiffnessBlock(lambda_, mu_, w.gradients[a], w.gradients[b]);
    }
    offset -= w.offsets[a];
  }
  finishRow(i, offset);
}

#if defined(__x86_64__)
// stiffnessBlock entry by entry (lambda (gi_r gj_c) + mu (gj_r gi_c), then mu gi.gj on the
// diagonal), four entries a vector: a block's 9 column-major entries are lanes 0-3, 4-7 and 8,
// so that each block is read and written with two vector loads and stores and one scalar.
__attribute__((target("avx2,fma"))) void CorotationalElasticity::assembleRowAvx2(int i) {
  std::vector<Eigen::Matrix3d>& blocks = stiffness_.blocks();
  startRow(i);
  const __m256d lambda = _mm256_set1_pd(lambda_), mu = _mm256_set1_pd(mu_);
  const __m256d first_lane = _mm256_setr_pd(1.0, 0.0, 0.0, 0.0);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  const int last = static_cast<int>(incidences_.size()) - 1;
  for (int k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k) {
    prefetchWarped(incidences_[std::min(k + kPrefetchAhead, last)] / 4);
    const int e = incidences_[k] / 4, a = incidences_[k] % 4;
    const WarpedElement& w = warped_[e];
    const double* gi = w.gradients[a].data();
    // Lane 3 of a load is the next vector's first entry (or the first offset's): never used.
    const __m256d vi = _mm256_loadu_pd(gi);
    const __m256d i0120 = _mm256_permute4x64_pd(vi, 0x24), i0001 = _mm256_permute4x64_pd(vi, 0x40);
    const __m256d i1201 = _mm256_permute4x64_pd(vi, 0x49), i1122 = _mm256_permute4x64_pd(vi, 0xA5);
    for (int b = 0; b < 4; ++b) {
      if (tetrahedra_[e][b] < i) continue;
      const double* gj = w.gradients[b].data();
      const __m256d vj = _mm256_loadu_pd(gj);
      const __m256d j0001 = _mm256_permute4x64_pd(vj, 0x40),
                    j0120 = _mm256_permute4x64_pd(vj, 0x24);
      const __m256d j1122 = _mm256_permute4x64_pd(vj, 0xA5),
                    j1201 = _mm256_permute4x64_pd(vj, 0x49);
      const double dot = gi[0] * gj[0] + gi[1] * gj[1] + gi[2] * gj[2];
      const __m256d diagonal_term = _mm256_mul_pd(_mm256_set1_pd(mu_ * dot), first_lane);
      // Entries (0,0) (1,0) (2,0) (0,1), then (1,1) (2,1) (0,2) (1,2), then (2,2).
      __m256d k0 = _mm256_fmadd_pd(lambda, _mm256_mul_pd(i0120, j0001),
                                   _mm256_mul_pd(mu, _mm256_mul_pd(j0120, i0001)));
      __m256d k1 = _mm256_fmadd_pd(lambda, _mm256_mul_pd(i1201, j1122),
                                   _mm256_mul_pd(mu, _mm256_mul_pd(j1201, i1122)));
      const double k2 = std::fma(lambda_, gi[2] * gj[2], mu_ * (gj[2] * gi[2])) + mu_ * dot;
      k0 = _mm256_add_pd(k0, diagonal_term);
      k1 = _mm256_add_pd(k1, diagonal_term);
      double* block = blocks[block_index_[e][4 * a + b]].data();
      _mm256_storeu_pd(block, _mm256_add_pd(_mm256_loadu_pd(block), k0));
      _mm256_storeu_pd(block + 4, _mm256_add_pd(_mm256_loadu_pd(block + 4), k1));
      block[8] += k2;
    }
    offset -= w.offsets[a];
  }
  finishRow(i, offset);
}
#endif

#if defined(__x86_64__)
namespace {
// R v from R's columns c0, c1, c2 (fourth lanes unused).
__attribute__((target("avx2,fma"), always_inline)) inline __m256d rotateAvx2(__m256d c0, __m256d c1,
                                                                             __m256d c2,
                                                                             const double* v) {
  const __m256d t = _mm256_mul_pd(c0, _mm256_broadcast_sd(v));
  return _mm256_fmadd_pd(c2, _mm256_broadcast_sd(v + 2),
                         _mm256_fmadd_pd(c1, _mm256_broadcast_sd(v + 1), t));
}
}  // namespace

// warp(e) into warped_[e], 4-wide: R v = R_0 v_0 + R_1 v_1 + R_2 v_2 over R's columns (the last
// read from entry 5 and rotated down a lane, so that no load leaves R). The eight results are
// stored in order, each store's fourth lane overwritten by the next; the last one stores three.
__attribute__((target("avx2,fma"))) void CorotationalElasticity::warpAvx2(int e) {
  const double* r = rotations_[e].data();
  const __m256d c0 = _mm256_loadu_pd(r), c1 = _mm256_loadu_pd(r + 3);
  const __m256d c2 = _mm256_permute4x64_pd(_mm256_loadu_pd(r + 5), 0x39);

  const __m256d root_volume = _mm256_set1_pd(std::sqrt(rest_[e].volume));
  static_assert(sizeof(WarpedElement) == 24 * sizeof(double), "gradients then offsets, unpadded");
  double* out = warped_[e].gradients[0].data();
  for (int a = 0; a < 4; ++a) {
    _mm256_storeu_pd(
        out + 3 * a,
        _mm256_mul_pd(root_volume, rotateAvx2(c0, c1, c2, rest_[e].gradients[a].data())));
  }
  for (int a = 0; a < 3; ++a)
    _mm256_storeu_pd(out + 12 + 3 * a, rotateAvx2(c0, c1, c2, rest_forces_[e][a].data()));
  _mm256_maskstore_pd(out + 21, _mm256_setr_epi64x(-1, -1, -1, 0),
                      rotateAvx2(c0, c1, c2, rest_forces_[e][3].data()));
}
#endif

void CorotationalElasticity::prefetchWarped(int e) const {
  const char* ahead = reinterpret_cast<const char*>(&warped_[e]);
  for (size_t byte = 0; byte < sizeof(WarpedElement); byte += 64) __builtin_prefetch(ahead + byte);
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
