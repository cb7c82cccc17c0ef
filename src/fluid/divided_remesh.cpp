// The remeshing divided among the processes of an MPI run (remesh_pipeline.hpp, remesh_over_processes): each process
// triangulates the particles of its part of space and a ghost layer and classifies the faces (meshing::remesh_part);
// the shares are gathered in rank order, the same on every process.
#include "remesh_pipeline.hpp"

#include <lagfsi/meshing/partition.hpp>
#include <lagfsi/mpi_run.hpp>
#include <lagfsi/stopwatch.hpp>

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagfsi::fluid {

namespace {

/// Triangles as 3 indices each, and back.
std::vector<Index> flatten(const std::vector<std::array<Index, 3>>& t) {
  std::vector<Index> f;
  f.reserve(3 * t.size());
  for (const auto& e : t) f.insert(f.end(), e.begin(), e.end());
  return f;
}

std::vector<std::array<Index, 3>> triangles(const std::vector<Index>& f) {
  std::vector<std::array<Index, 3>> t(f.size() / 3);
  for (size_t e = 0; e < t.size(); ++e) t[e] = {f[3 * e], f[3 * e + 1], f[3 * e + 2]};
  return t;
}

}  // namespace

double divided_halo(const std::vector<double>& h, double alpha, double separation_alpha) {
  // A kept element's circumradius is at most R = max(alpha, separation_alpha) h_e, and its circumdisc lies within 2 R
  // of its centroid (meshing::remesh_part); two spacings more for the previous mesh's edges flipped back in.
  const double h_max = h.empty() ? 0.0 : *std::max_element(h.begin(), h.end());
  const double reach = std::max(alpha, separation_alpha) * h_max;
  return 2.0 * reach + 2.0 * h_max;
}

meshing::RemeshResult remesh_over_processes(const std::vector<Vec2>& pts, const std::vector<ParticleKind>& kind,
                                            const std::vector<double>& h, const meshing::RemeshSettings& settings,
                                            DividedRemeshStats* stats, const meshing::SpacePartition* partition) {
  const bool previous = settings.previous != nullptr && !settings.previous->empty();
  const bool level_set = previous && settings.detection == meshing::DomainDetection::LevelSet;
  if (mpi_run::size() <= 1 || level_set) return meshing::remesh(pts, kind, h, settings);
  const double halo = divided_halo(h, settings.alpha, previous ? settings.separation_alpha : 0.0);
  meshing::RemeshResult mine;
  std::string failure;
  Index ghosts = 0;
  const auto t0 = SteadyClock::now();
  try {
    std::unique_ptr<meshing::SpacePartition> own;
    if (partition == nullptr) partition = (own = std::make_unique<meshing::SpacePartition>(pts, mpi_run::size())).get();
    mine = meshing::remesh_part(pts, kind, h, settings, *partition, mpi_run::rank(), halo, &ghosts);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  const auto t1 = SteadyClock::now();
  if (const std::string first = mpi_run::first_failure(failure); !first.empty()) throw std::invalid_argument(first);

  meshing::RemeshResult r;
  // The elements added outside the previous domain: their indices in the gathered list (the processes before
  // this one contributed theirs first).
  const std::vector<Index> counts = mpi_run::gather_all({static_cast<Index>(mine.triangles.size())});
  Index offset = 0;
  for (int k = 0; k < mpi_run::rank(); ++k) offset += counts[static_cast<size_t>(k)];
  for (Index& e : mine.added_elements) e += offset;
  r.added_elements = mpi_run::gather_all(mine.added_elements);
  r.triangles = triangles(mpi_run::gather_all(flatten(mine.triangles)));
  r.separated = triangles(mpi_run::gather_all(flatten(mine.separated)));
  r.boundary_only = triangles(mpi_run::gather_all(flatten(mine.boundary_only)));
  r.free_surface = std::move(mine.free_surface);
  r.connected = std::move(mine.connected);
  mpi_run::or_flags(r.free_surface.data(), static_cast<Index>(r.free_surface.size()));
  mpi_run::or_flags(r.connected.data(), static_cast<Index>(r.connected.size()));
  // The area, the counts and the ghosts summed in one reduction (the counts exact in double).
  double sums[] = {mine.area,
                   static_cast<double>(mine.removed_alpha),
                   static_cast<double>(mine.removed_boundary_only),
                   static_cast<double>(mine.added_outside),
                   static_cast<double>(mine.separated_inside),
                   static_cast<double>(mine.restored_edges),
                   static_cast<double>(mine.lost_edges),
                   static_cast<double>(mine.kept_edges),
                   static_cast<double>(ghosts)};
  mpi_run::sum_in_rank_order(sums, 9);
  r.area = sums[0];
  r.removed_alpha = static_cast<int>(sums[1]);
  r.removed_boundary_only = static_cast<int>(sums[2]);
  r.added_outside = static_cast<int>(sums[3]);
  r.separated_inside = static_cast<int>(sums[4]);
  r.restored_edges = static_cast<int>(sums[5]);
  r.lost_edges = static_cast<int>(sums[6]);
  r.kept_edges = static_cast<int>(sums[7]);
  if (stats != nullptr) {
    const long long received =
        static_cast<long long>(3 * (r.triangles.size() + r.separated.size() + r.boundary_only.size()) +
                               r.added_elements.size()) -
        static_cast<long long>(3 * (mine.triangles.size() + mine.separated.size() + mine.boundary_only.size()) +
                               mine.added_elements.size());
    ++stats->remeshes;
    stats->ghosts += sums[8];
    stats->particles += static_cast<double>(pts.size());
    stats->gathered_indices += static_cast<double>(received);
    stats->part_seconds += std::chrono::duration<double>(t1 - t0).count();
    stats->gather_seconds += seconds_since(t1);
  }
  return r;
}

Json DividedRemeshStats::summary(int processes) const {
  if (remeshes == 0) return Json::object();
  const double n = static_cast<double>(remeshes);
  return {{"processes", processes},
          {"remeshes", remeshes},
          {"ghosts_per_process", ghosts / (n * processes)},
          {"ghost_share", particles > 0 ? ghosts / particles : 0.0},
          {"gathered_mb_per_remesh", 4.0 * gathered_indices / n / 1e6},
          {"part_seconds", part_seconds},
          {"gather_seconds", gather_seconds}};
}

}  // namespace lagfsi::fluid
