// The particle management's searches divided among the processes of an MPI run (particle_management.hpp): each
// process searches for the particles of its part of space, and every process then takes what they found in particle
// order, as one process does over all of them.
//
// The management's stages are greedy: they take the particles in increasing index, and what one does (a merge) can
// change what a later one may do. Their decisions are therefore not divided; the searches that find which particles
// may do anything are, and those few are taken in the same order on every process. A particle whose search finds
// nothing does nothing, and changes nothing for the others, in the pass over all particles as in the pass over the
// candidates: the two passes make the same merges, in the same order, with the same bits.
#include "particle_management.hpp"

#include <algorithm>
#include <utility>

namespace lagfsi::fluid {

std::vector<Index> gather_pairs_in_order(const std::vector<Index>& pairs) {
  std::vector<Index> all = mpi_run::gather_all(pairs);
  std::vector<std::pair<Index, Index>> sorted(all.size() / 2);
  for (size_t k = 0; k < sorted.size(); ++k) sorted[k] = {all[2 * k], all[2 * k + 1]};
  std::sort(sorted.begin(), sorted.end());
  for (size_t k = 0; k < sorted.size(); ++k) {
    all[2 * k] = sorted[k].first;
    all[2 * k + 1] = sorted[k].second;
  }
  return all;
}

std::vector<Index> RemeshPipeline::meeting_candidates(const Management& m, double cell) const {
  // A fluid particle not yet touched whose search (within close_fraction h_i <= close_fraction h_max = reach) can
  // find another has one within reach; and that other has it within reach too, so it is a candidate as well. A
  // particle with none within reach finds nothing, and is found by no candidate.
  const double reach = s_.close_fraction * cloud_.h_max();
  const auto untouched = [&](Index i) { return cloud_.kind(i) == ParticleKind::Fluid && !m.touched[i]; };
  const int me = mpi_run::rank();
  // This process's particles and those within reach of its part (a hair more: the distances to the box are
  // computed, not exact).
  std::vector<Index> mine;
  for (Index i = 0; i < m.np; ++i)
    if (m.mine(i) && untouched(i)) mine.push_back(i);
  const std::vector<Index> beside = m.part->ghosts(m.pts, me, reach * (1 + 1e-9));
  PointGrid grid(cell, mine.size() + beside.size());
  for (Index i : mine) grid.add(m.pts[i], i);
  for (Index i : beside)
    if (untouched(i)) grid.add(m.pts[i], i);
  std::vector<Index> found;
  for (Index i : mine)
    if (grid.find(m.pts[i], reach, m.pts, i) >= 0) found.push_back(i);
  std::vector<Index> all = mpi_run::gather_all(found);
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace lagfsi::fluid
