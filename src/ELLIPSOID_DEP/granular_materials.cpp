/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: named material parameter sets (see granular_materials.h)
------------------------------------------------------------------------- */

#include "granular_materials.h"

#include "comm.h"
#include "force.h"
#include "lammps.h"
#include "tokenizer.h"
#include "update.h"
#include "utils.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

using namespace LAMMPS_NS;

namespace {
// The pressure unit of each LAMMPS unit style in pascal (doc/src/units.rst). The internal
// force/area unit is that pressure unit times force->nktv2p; lj has no SI equivalent.
double pascal_per_pressure_unit(const std::string &style)
{
  if (style == "si" || style == "electron") return 1.0;
  if (style == "cgs") return 0.1;          // dyne/cm^2
  if (style == "metal") return 1.0e5;      // bar
  if (style == "real") return 101325.0;    // atm
  if (style == "micro") return 1.0e3;      // picogram/(micrometer microsecond^2)
  if (style == "nano") return 1.0e6;       // attogram/(nanometer nanosecond^2)
  return 0.0;
}

constexpr int COLUMNS = 3;    // E nu e; further columns are for reference
}    // namespace

MaterialTable::MaterialTable(LAMMPS *lmp) : unit_style(lmp->update->unit_style)
{
  pascal_per_unit = pascal_per_pressure_unit(unit_style) * lmp->force->nktv2p;

  // rank 0 parses "name E nu e [more columns]" lines; names and numbers go out in one
  // broadcast as text of "name E nu e" lines at full precision
  std::string packed;
  if (lmp->comm->me == 0) {
    FILE *fp = utils::open_potential(MATERIALS_FILE, lmp, nullptr);
    if (fp) {
      char buffer[1024];
      while (fgets(buffer, sizeof(buffer), fp)) {
        auto words = Tokenizer(utils::trim_comment(buffer)).as_vector();
        if (words.size() < 1 + COLUMNS) continue;
        bool numbers = true;
        for (int c = 1; c <= COLUMNS; c++) numbers &= utils::is_double(words[c]);
        if (numbers) packed += fmt::format("{} {} {} {}\n", words[0], words[1], words[2], words[3]);
      }
      fclose(fp);
    }
  }
  int size = static_cast<int>(packed.size());
  MPI_Bcast(&size, 1, MPI_INT, 0, lmp->world);
  packed.resize(size);
  MPI_Bcast(packed.data(), size, MPI_CHAR, 0, lmp->world);

  for (const auto &line : Tokenizer(packed, "\n").as_vector()) {
    auto words = Tokenizer(line).as_vector();
    // strtod, not stod: an entry beyond double range (1e999) becomes inf, which the force
    // law's parameter ranges then refuse with an ERROR naming it
    materials[words[0]] = {std::strtod(words[1].c_str(), nullptr),
                           std::strtod(words[2].c_str(), nullptr),
                           std::strtod(words[3].c_str(), nullptr)};
  }
}

EllipsoidDep::MaterialLookup MaterialTable::lookup() const
{
  return [this](const std::string &name, EllipsoidDep::Material &material) -> std::string {
    const auto found = materials.find(name);
    if (found == materials.end())
      return "unknown material '" + name + "' for hertz/material (not in " + MATERIALS_FILE + ")";
    if (!(pascal_per_unit > 0.0))
      return "hertz/material " + name + ": " + MATERIALS_FILE + " holds SI values and units " +
          unit_style + " has no SI equivalent; give E nu e as numbers in your units";
    material = found->second;
    material.youngs /= pascal_per_unit;
    return {};
  };
}

bool LAMMPS_NS::names_a_material(const std::vector<std::string> &words)
{
  for (std::size_t k = 0; k + 1 < words.size(); k++)
    if ((words[k] == "hertz/material" || words[k] == "wall_material") &&
        !utils::is_double(words[k + 1]) && words[k + 1] != "rigid")
      return true;
  return false;
}
