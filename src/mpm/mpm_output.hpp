#pragma once
// Output of an MPM body (mpm_output.cpp): the particles as a ParaView series <name>.pvd (displacement,
// velocity, stress, volume, plastic multiplier, and pore pressure for two-phase bodies), optionally the grid
// nodes that carry mass (<name>_grid.pvd) and a CSV of the particles at the last output (<name>_particles.csv).
#include "mpm_body.hpp"

#include <lagfsi/vtk_output.hpp>

#include <filesystem>
#include <memory>
#include <string>

namespace lagfsi::mpm {

class MpmWriter {
 public:
  MpmWriter(std::filesystem::path out_dir, bool particles_csv, bool grid_output)
      : out_dir_(std::move(out_dir)), particles_csv_(particles_csv), grid_output_(grid_output) {}
  void write(double t, const MpmBody& b);
  /// Checkpoints: the series written so far (mpm_checkpoint.cpp).
  void serialize(StateArchive& ar, const std::string& name);

 private:
  std::filesystem::path out_dir_;
  bool particles_csv_ = false;  // also write <out>/<name>_particles.csv (the particles at the last output)
  bool grid_output_ = false;    // also write the grid nodes that carry mass as <name>_grid.pvd
  std::unique_ptr<PvdSeries> series_, grid_series_;
};

}  // namespace lagfsi::mpm
