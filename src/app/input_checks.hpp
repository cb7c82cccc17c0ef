#pragma once
// Checks of a whole case that no single body can make (input_checks.cpp), run after the bodies are built (so
// that every body's own keys have been validated and defaulted): output file names, overlapping bodies, the
// time integrator's stability, the output folder against the input's.
#include <lagfsi/params.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace lagfsi {

/// Every output file and folder of a run, by owner: two bodies whose files would have one name (a fluid
/// "water" writes water_walls.pvd, the series of a solid "water_walls"), or a body whose name is one of the
/// run's own files (log, probes, summary, resolved_case) or whose folder would be one of them
/// ("summary.json"), is an InputError at /bodies/i/name. Names are compared ignoring case.
void check_output_names(const Params& root);

/// Bodies that overlap at the start: the regions of fluid and MPM bodies, the geometry of solids
/// (rectangles, polygons, circle_cut) and of shells (the mid-line widened to the thickness), and solids and
/// shells crossed by a fluid's rigid walls. InputError at the later body: "/bodies/i/regions/j: overlaps body 'plate'".
void check_overlaps(const Params& root);

/// The integrator of a dynamic analysis must be unconditionally stable (linear analysis): Newmark needs
/// gamma >= 1/2 and beta >= gamma / 2 (Hughes 1987, 9.1.2), generalized-alpha rho_inf in [0, 1]. With
/// "allow_conditionally_stable": true a conditionally stable Newmark (beta < gamma / 2) runs with a warning
/// (returned, for stderr and summary.json); otherwise it is an InputError.
std::vector<std::string> check_integrator_stability(Params integrator);

/// The output folder must not be the case file's own folder (running out/x/resolved_case.json would write
/// over it): InputError naming the case file.
void check_output_folder(const std::filesystem::path& case_file, const std::filesystem::path& out_dir);

}  // namespace lagfsi
