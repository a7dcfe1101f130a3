/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: the parameter tables of the force-law sub-models, and everything that is
   driven by them: parsing, validation, mixing of unlike types, the restart layout.

   One row per parameter: the model that takes it, its word in messages, its field, its
   allowed range and its mixing rule. Rows of one model are read in table order, and the
   restart record holds every row of every table in table order. Adding a parameter is one
   row here (and its use in ForceLaw::compute).
------------------------------------------------------------------------- */

#include "ellipsoid_force_law.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace EllipsoidDep {

namespace {

  const double INF = std::numeric_limits<double>::infinity();

  struct Range {
    double lo, hi;
    bool lo_closed, hi_closed;

    bool contains(double x) const
    {
      return (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    }
    std::string text() const
    {
      char buffer[64];
      if (hi == INF)
        std::snprintf(buffer, sizeof(buffer), "%s %g", lo_closed ? ">=" : ">", lo);
      else
        std::snprintf(buffer, sizeof(buffer), "in %c%g, %g%c", lo_closed ? '[' : '(', lo, hi,
                      hi_closed ? ']' : ')');
      return buffer;
    }
  };

  const Range POSITIVE = {0.0, INF, false, false};
  const Range NON_NEGATIVE = {0.0, INF, true, false};
  const Range POISSON_RATIO = {-1.0, 0.5, false, false};
  const Range RESTITUTION = {0.0, 1.0, false, true};
  // rolling resistance mu_r: its torque arm mu_r R* cannot exceed the contact's radius R*
  // (beyond, one step's torque spins a particle at rest past what its orientation survives)
  const Range ROLLING_ARM = {0.0, 1.0, true, true};

  enum class Mix {
    Geometric,         // sqrt(a b)
    Arithmetic,        // (a + b) / 2
    ReducedModulus,    // Young's modulus: the like-material E with Hertz's E* at the mixed nu
  };

  template <class Model> struct Choice {
    typename Model::Kind kind;
    const char *name;
  };

  template <class Model> struct Row {
    typename Model::Kind kind;    // the model that takes this parameter
    const char *word;
    double Model::*field;
    Range range;
    Mix mix;
    double Model::*poisson = nullptr;    // ReducedModulus: the Poisson ratio it pairs with
  };

  using N = NormalModel;
  using T = TangentialModel;
  using R = RollingModel;

  const Choice<N> NORMAL_CHOICES[] = {{N::Kind::Hertz, "hertz"},
                                      {N::Kind::HertzMaterial, "hertz/material"}};
  const Row<N> NORMAL_ROWS[] = {
      {N::Kind::Hertz, "kn", &N::kn, POSITIVE, Mix::Geometric},
      {N::Kind::Hertz, "K", &N::damping, NON_NEGATIVE, Mix::Geometric},
      {N::Kind::HertzMaterial, "E", &N::youngs, POSITIVE, Mix::ReducedModulus, &N::poisson},
      {N::Kind::HertzMaterial, "nu", &N::poisson, POISSON_RATIO, Mix::Arithmetic},
      {N::Kind::HertzMaterial, "e", &N::restitution, RESTITUTION, Mix::Geometric},
  };

  const Choice<T> TANGENTIAL_CHOICES[] = {
      {T::Kind::None, "none"}, {T::Kind::Viscous, "viscous"}, {T::Kind::History, "history"}};
  const Row<T> TANGENTIAL_ROWS[] = {
      {T::Kind::Viscous, "mu", &T::mu_viscous, NON_NEGATIVE, Mix::Geometric},
      {T::Kind::History, "kt", &T::kt, POSITIVE, Mix::Geometric},
      {T::Kind::History, "mu", &T::mu, NON_NEGATIVE, Mix::Geometric},
  };

  const Choice<R> ROLLING_CHOICES[] = {{R::Kind::None, "none"}, {R::Kind::Constant, "constant"}};
  const Row<R> ROLLING_ROWS[] = {
      {R::Kind::Constant, "mu_r", &R::mu_roll, ROLLING_ARM, Mix::Geometric},
  };

  // One sub-model's table with its keyword ("" for the normal model, which has none).
  template <class Model, std::size_t NC, std::size_t NR> struct Table {
    const char *keyword;
    const Choice<Model> (&choices)[NC];
    const Row<Model> (&rows)[NR];

    const char *name(typename Model::Kind kind) const
    {
      for (const auto &c : choices)
        if (c.kind == kind) return c.name;
      return "?";
    }
    // "hertz/material" or "tangential history": how messages name a model
    std::string label(typename Model::Kind kind) const
    {
      return *keyword ? std::string(keyword) + " " + name(kind) : std::string(name(kind));
    }
    std::string expected() const
    {
      std::string list;
      for (std::size_t k = 0; k < NC; k++) {
        if (k > 0) list += k + 1 == NC ? " or " : ", ";
        list += choices[k].name;
      }
      return list;
    }
    std::string validate(const Model &model) const
    {
      for (const auto &row : rows)
        if (row.kind == model.kind && !row.range.contains(model.*row.field))
          return label(model.kind) + " " + row.word + " must be " + row.range.text();
      return {};
    }
    void mix(const Model &a, const Model &b, Model &mixed) const
    {
      for (const auto &row : rows) {
        if (row.kind != a.kind) continue;
        const double x = a.*row.field, y = b.*row.field;
        if (row.mix == Mix::Geometric)
          mixed.*row.field = x == y ? x : std::sqrt(x * y);
        else if (row.mix == Mix::Arithmetic)
          mixed.*row.field = 0.5 * (x + y);
      }
      // after the Poisson ratios: E_mix / (2 (1 - nu_mix^2)) is the pair's E*
      for (const auto &row : rows) {
        if (row.kind != a.kind || row.mix != Mix::ReducedModulus) continue;
        const double nu_a = a.*row.poisson, nu_b = b.*row.poisson, nu = mixed.*row.poisson;
        const double compliance =
            (1.0 - nu_a * nu_a) / (a.*row.field) + (1.0 - nu_b * nu_b) / (b.*row.field);
        mixed.*row.field = 2.0 * (1.0 - nu * nu) / compliance;
      }
    }
    void pack(const Model &model, std::vector<double> &out) const
    {
      out.push_back(static_cast<double>(model.kind));
      for (const auto &row : rows) out.push_back(model.*row.field);
    }
    bool unpack(const double *&in, Model &model) const
    {
      const double kind = *in++;
      if (!(kind >= 0.0 && kind < static_cast<double>(NC) && kind == std::floor(kind)))
        return false;
      model.kind = static_cast<typename Model::Kind>(static_cast<int>(kind));
      for (const auto &row : rows) model.*row.field = *in++;
      return true;
    }
    static constexpr int packed_size() { return 1 + static_cast<int>(NR); }
  };

  template <class Model, std::size_t NC, std::size_t NR>
  Table<Model, NC, NR> make_table(const char *keyword, const Choice<Model> (&choices)[NC],
                                  const Row<Model> (&rows)[NR])
  {
    return {keyword, choices, rows};
  }

  const auto NORMAL = make_table("", NORMAL_CHOICES, NORMAL_ROWS);
  const auto TANGENTIAL = make_table("tangential", TANGENTIAL_CHOICES, TANGENTIAL_ROWS);
  const auto ROLLING = make_table("rolling", ROLLING_CHOICES, ROLLING_ROWS);

  bool to_number(const std::string &word, double &value)
  {
    if (word.empty()) return false;
    char *end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
  }

  // Reads words[k...]: a model name of the table, then its rows in table order.
  class Reader {
   public:
    Reader(const std::vector<std::string> &words, std::string &error) : words(words), error(error)
    {
    }
    std::size_t k = 0;
    bool done() const { return k >= words.size(); }
    const std::string &peek() const { return words[k]; }

    template <class Table, class Model> bool model(const Table &table, Model &model)
    {
      const std::string what = *table.keyword ? table.keyword : "normal";
      if (done()) {
        error = "missing " + what + " model (" + table.expected() + ")";
        return false;
      }
      const std::string &name = words[k];
      for (const auto &c : table.choices)
        if (name == c.name) {
          ++k;
          model.kind = c.kind;
          return true;
        }
      error = "unknown " + what + " model '" + name + "' (expected " + table.expected() + ")";
      return false;
    }
    template <class Table, class Model> bool numbers(const Table &table, Model &model)
    {
      const std::string label = table.label(model.kind);
      std::string signature = label;
      int count = 0;
      for (const auto &row : table.rows)
        if (row.kind == model.kind) {
          signature += std::string(" ") + row.word;
          count++;
        }
      if (k + count > words.size()) {
        error = "missing argument(s) for " + signature;
        return false;
      }
      for (const auto &row : table.rows) {
        if (row.kind != model.kind) continue;
        if (!to_number(words[k], model.*row.field)) {
          error = "expected a number for " + label + " " + row.word + ", got '" + words[k] + "'";
          return false;
        }
        ++k;
      }
      return true;
    }

   private:
    const std::vector<std::string> &words;
    std::string &error;
  };

  // LAMMPS's pair granular writes "hertz/material E damping nu" and names the damping model
  // after the keyword "damping"; only the restitution damping is the one this package has.
  std::string lammps_damping(const std::string &model, NormalModel &normal, bool numbers_given)
  {
    const std::string ours = "write 'hertz/material E nu e' or, in LAMMPS's order, "
                             "'hertz/material E e nu damping coeff_restitution'";
    if (normal.kind != NormalModel::Kind::HertzMaterial || !numbers_given)
      return "damping " + model + " applies only to hertz/material with numbers (E e nu): " + ours;
    if (model != "coeff_restitution")
      return "damping " + model +
          " is not available: hertz/material damps by the restitution coefficient e; " + ours;
    // the numbers were read as E nu e; LAMMPS's order is E e nu
    std::swap(normal.poisson, normal.restitution);
    return {};
  }

  // Every LAMMPS pair granular line names one of its tangential models, none of which is
  // this package's: so a copied line stops here, with a pointer to the mapping.
  std::string lammps_tangential_hint(const std::string &model)
  {
    for (const char *name : {"linear_nohistory", "linear_history", "mindlin", "mindlin_rescale",
                             "mindlin/force", "mindlin_rescale/force"})
      if (model == name)
        return "; '" + model + "' is LAMMPS pair granular's syntax, whose hertz/material numbers " +
            "are in another order (E damping nu): see doc/pair_granular_ellipsoid.rst";
    return {};
  }

}    // namespace

std::string ForceLaw::validate() const
{
  std::string message = NORMAL.validate(normal);
  if (message.empty()) message = TANGENTIAL.validate(tangential);
  if (message.empty()) message = ROLLING.validate(rolling);
  return message;
}

int parse_force_law(const std::vector<std::string> &words, ForceLaw &law, std::string &error,
                    const MaterialLookup &lookup)
{
  Reader in(words, error);
  if (!in.model(NORMAL, law.normal)) return -1;
  bool numbers_given = true;
  double value;
  if (law.normal.kind == NormalModel::Kind::HertzMaterial && !in.done() &&
      !to_number(in.peek(), value)) {
    const std::string &name = in.peek();
    Material material{};
    const std::string refusal = lookup ? lookup(name, material)
                                       : "unknown material '" + name + "' for hertz/material";
    if (!refusal.empty()) {
      error = refusal;
      return -1;
    }
    law.normal.youngs = material.youngs;
    law.normal.poisson = material.poisson;
    law.normal.restitution = material.restitution;
    numbers_given = false;
    ++in.k;
  } else if (!in.numbers(NORMAL, law.normal)) {
    return -1;
  }

  while (!in.done()) {
    const std::string word = in.peek();
    if (word == TANGENTIAL.keyword) {
      ++in.k;
      if (!in.model(TANGENTIAL, law.tangential)) {
        if (!in.done()) error += lammps_tangential_hint(in.peek());
        return -1;
      }
      if (!in.numbers(TANGENTIAL, law.tangential)) return -1;
    } else if (word == ROLLING.keyword) {
      ++in.k;
      if (!in.model(ROLLING, law.rolling) || !in.numbers(ROLLING, law.rolling)) return -1;
    } else if (word == "limit_damping") {
      ++in.k;
      law.normal.limit_damping = true;
    } else if (word == "damping") {
      ++in.k;
      if (in.done()) {
        error = "missing argument(s) for damping (coeff_restitution)";
        return -1;
      }
      error = lammps_damping(words[in.k++], law.normal, numbers_given);
      if (!error.empty()) return -1;
    } else {
      break;
    }
  }

  error = law.validate();
  return error.empty() ? static_cast<int>(in.k) : -1;
}

std::string describe_models(const ForceLaw &law)
{
  return NORMAL.label(law.normal.kind) + ", " + TANGENTIAL.label(law.tangential.kind) + ", " +
      ROLLING.label(law.rolling.kind) + (law.normal.limit_damping ? ", limit_damping" : "");
}

std::string mix_laws(const ForceLaw &a, const ForceLaw &b, ForceLaw &mixed)
{
  if (a.normal.kind != b.normal.kind || a.tangential.kind != b.tangential.kind ||
      a.rolling.kind != b.rolling.kind || a.normal.limit_damping != b.normal.limit_damping)
    return "cannot mix '" + describe_models(a) + "' with '" + describe_models(b) + "'";
  mixed = a;
  NORMAL.mix(a.normal, b.normal, mixed.normal);
  TANGENTIAL.mix(a.tangential, b.tangential, mixed.tangential);
  ROLLING.mix(a.rolling, b.rolling, mixed.rolling);
  return {};
}

int packed_law_size()
{
  return 1 + NORMAL.packed_size() + TANGENTIAL.packed_size() + ROLLING.packed_size();
}

std::vector<double> pack_law(const ForceLaw &law)
{
  std::vector<double> out;
  out.push_back(law.normal.limit_damping ? 1.0 : 0.0);
  NORMAL.pack(law.normal, out);
  TANGENTIAL.pack(law.tangential, out);
  ROLLING.pack(law.rolling, out);
  return out;
}

bool unpack_law(const double *values, ForceLaw &law)
{
  law.normal.limit_damping = *values++ != 0.0;
  return NORMAL.unpack(values, law.normal) && TANGENTIAL.unpack(values, law.tangential) &&
      ROLLING.unpack(values, law.rolling);
}

}    // namespace EllipsoidDep
