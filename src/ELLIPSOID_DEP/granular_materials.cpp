/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: named material parameter sets (see granular_materials.h)
------------------------------------------------------------------------- */

#include "granular_materials.h"

#include "comm.h"
#include "lammps.h"
#include "tokenizer.h"
#include "utils.h"

#include <cstdio>
#include <map>
#include <string>

using namespace LAMMPS_NS;

namespace {
struct Material {
  double youngs, poisson, restitution;
};

// rank 0 reads, everybody parses the broadcast text: "name E nu e [more columns]" per line
std::map<std::string, Material> read_materials(LAMMPS *lmp)
{
  std::string text;
  if (lmp->comm->me == 0) {
    FILE *fp = utils::open_potential(MATERIALS_FILE, lmp, nullptr);
    if (fp) {
      char buffer[1024];
      while (fgets(buffer, sizeof(buffer), fp)) text += buffer;
      fclose(fp);
    }
  }
  int size = static_cast<int>(text.size());
  MPI_Bcast(&size, 1, MPI_INT, 0, lmp->world);
  text.resize(size);
  MPI_Bcast(text.data(), size, MPI_CHAR, 0, lmp->world);

  std::map<std::string, Material> materials;
  for (const auto &line : Tokenizer(text, "\n").as_vector()) {
    auto words = Tokenizer(utils::trim_comment(line)).as_vector();
    if (words.size() < 4) continue;
    if (!utils::is_double(words[1]) || !utils::is_double(words[2]) || !utils::is_double(words[3]))
      continue;
    materials[words[0]] = {std::stod(words[1]), std::stod(words[2]), std::stod(words[3])};
  }
  return materials;
}
}    // namespace

EllipsoidDep::MaterialLookup LAMMPS_NS::material_lookup(LAMMPS *lmp)
{
  return [lmp](const std::string &name, double &youngs, double &poisson, double &restitution) {
    const auto materials = read_materials(lmp);
    const auto found = materials.find(name);
    if (found == materials.end()) return false;
    youngs = found->second.youngs;
    poisson = found->second.poisson;
    restitution = found->second.restitution;
    return true;
  };
}
