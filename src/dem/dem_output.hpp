#pragma once
// ParaView output of a DEM body (include/lagfsi/dem/dem_model.hpp): the discs as a .vtp series of vertices
// (fields radius, velocity, angular_velocity, momentum |m v|, mark, id, group; for ParaView's glyph filter:
// Glyph type "Sphere", scale by "radius", factor 2) and the walls as polylines (a second series).
#include "dem_body.hpp"

#include <lagfsi/vtk_output.hpp>

#include <filesystem>
#include <memory>

namespace lagfsi::dem {

class DemWriter {
 public:
  explicit DemWriter(std::filesystem::path out_dir) : out_dir_(std::move(out_dir)) {}
  void write(double t, const DemBody& b);

 private:
  std::filesystem::path out_dir_;
  std::unique_ptr<PvdSeries> discs_, walls_;
};

}  // namespace lagfsi::dem
