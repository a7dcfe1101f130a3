/* ----------------------------------------------------------------------
   ELLIPSOID_DEP: everything the models' parameter rows drive (force_law_model.h): parsing,
   validation, mixing of unlike types, the restart layout. A family is the variant of its
   models (force_law_registry.h); its models are found by NAME, their parameters read,
   checked, mixed and stored row by row. Adding a parameter is one row in its model's header.
------------------------------------------------------------------------- */

#include "ellipsoid_force_law.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace EllipsoidDep {

namespace {

  std::string range_text(const Range &range)
  {
    char buffer[64];
    if (range.hi == INF)
      std::snprintf(buffer, sizeof(buffer), "%s %g", range.lo_closed ? ">=" : ">", range.lo);
    else
      std::snprintf(buffer, sizeof(buffer), "in %c%g, %g%c", range.lo_closed ? '[' : '(', range.lo,
                    range.hi, range.hi_closed ? ']' : ')');
    return buffer;
  }

  // f(std::integral_constant<std::size_t, I>) for every model I of a family, in list order
  template <class Variant, class F, std::size_t... I>
  void for_each_model(F &&f, std::index_sequence<I...>)
  {
    (f(std::integral_constant<std::size_t, I>{}), ...);
  }
  template <class Variant, class F> void for_each_model(F &&f)
  {
    for_each_model<Variant>(f, std::make_index_sequence<std::variant_size_v<Variant>>{});
  }
  template <class Variant, std::size_t I> using ModelAt = std::variant_alternative_t<I, Variant>;

  // One family with its keyword ("" for the normal model, which has none).
  template <class Variant> struct Family {
    const char *keyword;
    static constexpr std::size_t COUNT = std::variant_size_v<Variant>;

    const char *name(const Variant &v) const
    {
      return visit_model(v, [](const auto &model) {
        return model.NAME;
      });
    }
    // "hertz/material" or "tangential history": how messages name a model
    std::string label(const Variant &v) const
    {
      return *keyword ? std::string(keyword) + " " + name(v) : std::string(name(v));
    }
    std::string what() const { return *keyword ? keyword : "normal"; }
    std::string expected() const
    {
      std::string list;
      for_each_model<Variant>([&](auto index) {
        if (index > 0) list += index + 1 == COUNT ? " or " : ", ";
        list += ModelAt<Variant, index>::NAME;
      });
      return list;
    }
    // makes v the model called name (its defaults); false when there is none
    bool select(const std::string &name, Variant &v) const
    {
      bool found = false;
      for_each_model<Variant>([&](auto index) {
        if (!found && name == ModelAt<Variant, index>::NAME) {
          v.template emplace<index>();
          found = true;
        }
      });
      return found;
    }
    std::string validate(const Variant &v) const
    {
      return visit_model(v, [&](const auto &model) {
        for (const auto &row : model.ROWS)
          if (!row.range.contains(model.*row.field))
            return label(v) + " " + row.word + " must be " + range_text(row.range);
        return std::string();
      });
    }
    // a and b hold the same model
    void mix(const Variant &a, const Variant &b, Variant &mixed) const
    {
      visit_model(mixed, [&](auto &out) {
        using Model = std::decay_t<decltype(out)>;
        const Model &x = *std::get_if<Model>(&a), &y = *std::get_if<Model>(&b);
        for (const auto &row : Model::ROWS) {
          const double p = x.*row.field, q = y.*row.field;
          if (row.mix == Mix::Geometric)
            out.*row.field = p == q ? p : std::sqrt(p * q);
          else if (row.mix == Mix::Arithmetic)
            out.*row.field = 0.5 * (p + q);
        }
        // after the Poisson ratios: E_mix / (2 (1 - nu_mix^2)) is the pair's E*
        for (const auto &row : Model::ROWS) {
          if (row.mix != Mix::ReducedModulus) continue;
          const double nu_a = x.*row.poisson, nu_b = y.*row.poisson, nu = out.*row.poisson;
          const double compliance =
              (1.0 - nu_a * nu_a) / (x.*row.field) + (1.0 - nu_b * nu_b) / (y.*row.field);
          out.*row.field = 2.0 * (1.0 - nu * nu) / compliance;
        }
      });
    }
    // the model's code, then the parameters of every model (the defaults of the others);
    // optional: the optional rows of every model instead, without the code
    void pack(const Variant &v, std::vector<double> &out, bool optional = false) const
    {
      if (!optional) out.push_back(static_cast<double>(v.index()));
      for_each_model<Variant>([&](auto index) {
        using Model = ModelAt<Variant, index>;
        const Model *held = std::get_if<index>(&v);
        const Model model = held ? *held : Model();
        for (const auto &row : Model::ROWS)
          if (row.optional == optional) out.push_back(model.*row.field);
      });
    }
    bool unpack(const double *&in, Variant &v) const
    {
      const double code = *in++;
      if (!(code >= 0.0 && code < static_cast<double>(COUNT) && code == std::floor(code)))
        return false;
      for_each_model<Variant>([&](auto index) {
        if (index == static_cast<std::size_t>(code)) v.template emplace<index>();
      });
      read_rows(in, v, false);
      return true;
    }
    // the rows of every model that pack(optional) wrote, into the model v holds
    void read_rows(const double *&in, Variant &v, bool optional) const
    {
      for_each_model<Variant>([&](auto index) {
        using Model = ModelAt<Variant, index>;
        Model *held = std::get_if<index>(&v);
        for (const auto &row : Model::ROWS) {
          if (row.optional != optional) continue;
          if (held) held->*row.field = *in;
          ++in;
        }
      });
    }
    static int packed_size(bool optional = false)
    {
      int size = optional ? 0 : 1;
      for_each_model<Variant>([&](auto index) {
        for (const auto &row : ModelAt<Variant, index>::ROWS)
          if (row.optional == optional) ++size;
      });
      return size;
    }
  };

  const Family<NormalModel> NORMAL{""};
  const Family<TangentialModel> TANGENTIAL{"tangential"};
  const Family<RollingModel> ROLLING{"rolling"};

  bool to_number(const std::string &word, double &value)
  {
    if (word.empty()) return false;
    char *end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
  }

  // Reads words[k...]: a model name of a family, then its parameters in row order.
  class Reader {
   public:
    Reader(const std::vector<std::string> &words, std::string &error) : words(words), error(error)
    {
    }
    std::size_t k = 0;
    bool done() const { return k >= words.size(); }
    const std::string &peek() const { return words[k]; }

    template <class Variant> bool model(const Family<Variant> &family, Variant &v)
    {
      if (done()) {
        error = "missing " + family.what() + " model (" + family.expected() + ")";
        return false;
      }
      if (family.select(words[k], v)) {
        ++k;
        return true;
      }
      error = "unknown " + family.what() + " model '" + words[k] + "' (expected " +
          family.expected() + ")";
      return false;
    }
    // the model's numbers in row order, then its optional rows as "word value"
    template <class Variant> bool numbers(const Family<Variant> &family, Variant &v)
    {
      return visit_model(v, [&](auto &model) {
        const std::string label = family.label(v);
        std::size_t count = 0;
        std::string signature = label;
        for (const auto &row : model.ROWS)
          if (!row.optional) {
            ++count;
            signature += std::string(" ") + row.word;
          }
        if (k + count > words.size()) {
          error = "missing argument(s) for " + signature;
          return false;
        }
        for (const auto &row : model.ROWS)
          if (!row.optional && !number(label + " " + row.word, model.*row.field)) return false;
        for (bool found = true; found && !done();) {
          found = false;
          for (const auto &row : model.ROWS)
            if (!found && row.optional && words[k] == row.word) {
              found = true;
              if (++k >= words.size()) {
                error = "missing value for " + label + " " + row.word;
                return false;
              }
              if (!number(label + " " + row.word, model.*row.field)) return false;
            }
        }
        return true;
      });
    }

   private:
    bool number(const std::string &what, double &value)
    {
      if (!to_number(words[k], value)) {
        error = "expected a number for " + what + ", got '" + words[k] + "'";
        return false;
      }
      ++k;
      return true;
    }
    const std::vector<std::string> &words;
    std::string &error;
  };

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

  // hertz/material NAME: the material's E nu e in place of the numbers. 1 when read, 0 when
  // the next word is no name for this law, -1 on a refusal.
  int read_material(const std::vector<std::string> &words, std::size_t k, ForceLaw &law,
                    const MaterialLookup &lookup, std::string &error)
  {
    auto *normal = std::get_if<HertzMaterialNormal>(&law.normal);
    double value;
    if (!normal || k >= words.size() || to_number(words[k], value)) return 0;
    Material material{};
    const std::string &name = words[k];
    error = lookup ? lookup(name, material) : "unknown material '" + name + "' for hertz/material";
    if (!error.empty()) return -1;
    normal->set(material);
    return 1;
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
  const int material = read_material(words, in.k, law, lookup, error);
  if (material < 0) return -1;
  in.k += material;
  if (!material && !in.numbers(NORMAL, law.normal)) return -1;

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
      law.limit_damping = true;
    } else if (word == "damping") {
      ++in.k;
      if (in.done()) {
        error = "missing argument(s) for damping (coeff_restitution)";
        return -1;
      }
      error = lammps_damping(words[in.k++], std::get_if<HertzMaterialNormal>(&law.normal),
                             material == 0);
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
  return NORMAL.label(law.normal) + ", " + TANGENTIAL.label(law.tangential) + ", " +
      ROLLING.label(law.rolling) + (law.limit_damping ? ", limit_damping" : "");
}

std::string mix_laws(const ForceLaw &a, const ForceLaw &b, ForceLaw &mixed)
{
  if (a.normal.index() != b.normal.index() || a.tangential.index() != b.tangential.index() ||
      a.rolling.index() != b.rolling.index() || a.limit_damping != b.limit_damping)
    return "cannot mix '" + describe_models(a) + "' with '" + describe_models(b) + "'";
  mixed = a;
  NORMAL.mix(a.normal, b.normal, mixed.normal);
  TANGENTIAL.mix(a.tangential, b.tangential, mixed.tangential);
  ROLLING.mix(a.rolling, b.rolling, mixed.rolling);
  return {};
}

int packed_law_size()
{
  return 1 + NORMAL.packed_size() + TANGENTIAL.packed_size() + ROLLING.packed_size() +
      NORMAL.packed_size(true) + TANGENTIAL.packed_size(true) + ROLLING.packed_size(true);
}

std::vector<double> pack_law(const ForceLaw &law)
{
  std::vector<double> out;
  out.push_back(law.limit_damping ? 1.0 : 0.0);
  NORMAL.pack(law.normal, out);
  TANGENTIAL.pack(law.tangential, out);
  ROLLING.pack(law.rolling, out);
  NORMAL.pack(law.normal, out, true);
  TANGENTIAL.pack(law.tangential, out, true);
  ROLLING.pack(law.rolling, out, true);
  return out;
}

bool unpack_law(const double *values, ForceLaw &law)
{
  law.limit_damping = *values++ != 0.0;
  if (!NORMAL.unpack(values, law.normal) || !TANGENTIAL.unpack(values, law.tangential) ||
      !ROLLING.unpack(values, law.rolling))
    return false;
  NORMAL.read_rows(values, law.normal, true);
  TANGENTIAL.read_rows(values, law.tangential, true);
  ROLLING.read_rows(values, law.rolling, true);
  return true;
}

}    // namespace EllipsoidDep
