// The MPM material interface (src/mpm/include/lagfsi/mpm/mpm_material.hpp): the elastic constants, the linear elastic
// increment without rotation, and the factory that reads a body's "material" object. Mohr-Coulomb's return
// mapping is in mpm_mohr_coulomb.cpp.
#include <lagfsi/mpm/mpm_material.hpp>

#include <cmath>
#include <string>

namespace lagfsi::mpm {

namespace {

const KeyTable kMpmElasticKeys("/bodies/*/material (mpm body, type linear_elastic)", "Linear elasticity.",
                               {{"type", "linear_elastic", "`linear_elastic`."},
                                {"young", nullptr, "Young's modulus (Pa)."},
                                {"poisson", 0.0, "Poisson's ratio, in (-1, 0.5)."},
                                {"density", nullptr, "Mass density (kg/m^3)."}});

const KeyTable kMpmMohrCoulombKeys("/bodies/*/material (mpm body, type mohr_coulomb)",
                                   "Elastic-perfectly plastic Mohr-Coulomb.",
                                   {{"type", "mohr_coulomb", "`mohr_coulomb`."},
                                    {"young", nullptr, "Young's modulus (Pa)."},
                                    {"poisson", 0.0, "Poisson's ratio, in (-1, 0.5)."},
                                    {"density", nullptr, "Mass density (kg/m^3)."},
                                    {"cohesion", 0.0, "Cohesion c (Pa)."},
                                    {"friction_angle", nullptr, "Friction angle (degrees), in (0, 90)."},
                                    {"dilatancy_angle", 0.0, "Dilatancy angle (degrees), in [0, friction_angle]."},
                                    {"tension_cutoff", -1.0,
                                     "Tensile strength (Pa), at most c cot(friction angle); -1: the apex."}});

}  // namespace

MpmMaterial::MpmMaterial(double young, double poisson, double density)
    : MaterialLaw(young, poisson, density), lambda_(lame_lambda()), mu_(shear_modulus()) {}

void MpmMaterial::add_elastic_increment(Stress& s, double dxx, double dyy, double dxy) const {
  const double tr = dxx + dyy;
  s[0] += lambda_ * tr + 2 * mu_ * dxx;
  s[1] += lambda_ * tr + 2 * mu_ * dyy;
  s[2] += 2 * mu_ * dxy;
  s[3] += lambda_ * tr;
}

std::unique_ptr<MpmMaterial> make_mpm_material(Params mat) {
  if (!mat.json().is_object() || !mat.has("type")) mat.fail("type", "required key is missing");
  const bool plastic = mat.choice("type", {"linear_elastic", "mohr_coulomb"}) == "mohr_coulomb";
  double cohesion = 0, phi = 0, psi = 0, tension_cutoff = -1;
  if (plastic) {
    mat.validate(kMpmMohrCoulombKeys);
    cohesion = mat.non_negative("cohesion");
    phi = mat.number("friction_angle");
    psi = mat.number("dilatancy_angle");
    if (!(phi > 0 && phi < 90)) mat.fail("friction_angle", "must lie in (0, 90) degrees");
    if (!(psi >= 0 && psi <= phi)) mat.fail("dilatancy_angle", "must lie in [0, friction_angle] degrees");
    const double apex = cohesion * std::cos(phi * M_PI / 180) / std::sin(phi * M_PI / 180);
    if (mat.number("tension_cutoff") >= 0) {  // -1: at the apex
      tension_cutoff = mat.number("tension_cutoff");
      if (tension_cutoff > apex)
        mat.fail("tension_cutoff", "must not exceed c cot(phi) = " + std::to_string(apex) + " Pa");
    }
  } else {
    mat.validate(kMpmElasticKeys);
  }
  const double E = mat.positive("young");
  const double nu = mat.number("poisson");
  const double rho = mat.positive("density");
  if (!(nu > -1.0 && nu < 0.5)) mat.fail("poisson", "must lie in (-1, 0.5)");
  if (plastic) return std::make_unique<MohrCoulomb>(E, nu, rho, cohesion, phi, psi, tension_cutoff);
  return std::make_unique<LinearElastic>(E, nu, rho);
}

}  // namespace lagfsi::mpm
