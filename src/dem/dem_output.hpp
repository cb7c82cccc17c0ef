#pragma once
// ParaView output of a DEM body (src/dem/include/lagfsi/dem/dem_model.hpp): the discs as a .vtp series of vertices
// (fields radius, velocity, angular_velocity, momentum |m v|, mark, id, group; for ParaView's glyph filter:
// Glyph type "Sphere", scale by "radius", factor 2) and the walls as polylines (a second series).
#include "dem_body.hpp"

#include <lagfsi/vtk_output.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace lagfsi::dem {

/// The crater profile (Sabatucci et al. 2013, Fig. 2; Ambrosini et al. 2002): the bed's surface height per bin
/// of x, the top of the pile of discs connected to the bottom (in each bin the discs sorted by height are walked
/// up while the gap to the next one is below one diameter: airborne ejecta are not part of the surface); depth =
/// the mean of surface - height at centre + offsets (H1, H2, H3); diameter = the distance between the crossings of
/// the ground level nearest the centre on either side.
struct CraterProfile {
  std::vector<double> x, height;
  double depth = 0, diameter = 0, left = 0, right = 0;
};

/// The profile of the discs now (surface = settings.surface).
CraterProfile crater_profile(const DemBody& b, const CraterSettings& s);

class DemWriter {
 public:
  DemWriter(std::filesystem::path out_dir, bool csv) : out_dir_(std::move(out_dir)), csv_(csv) {}
  /// The .vtp series, and with csv <name>_discs.csv (id, x, y, r, vx, vy, omega, mark of every disc, the last
  /// output; written to a temporary, then renamed).
  void write(double t, const DemBody& b);
  /// Checkpoints: the series written so far (dem_checkpoint.cpp).
  void serialize(StateArchive& ar, const std::string& name);
  // with b.crater.enabled also crater.csv (the last output: the crater at the end of the run)

 private:
  std::filesystem::path out_dir_;
  bool csv_ = false;
  std::unique_ptr<PvdSeries> discs_, walls_;
};

}  // namespace lagfsi::dem
