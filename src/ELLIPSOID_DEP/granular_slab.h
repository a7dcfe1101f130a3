/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: the horizontal slab zlo <= z < zhi of the histogram computes (contact/histo,
   orient/histo, force/histo) and their bins keyword. The slab: the keywords zlo and zhi as
   numbers, or slab ID, a compute packing/ellipsoid whose vector elements 5 and 6 are its zlo
   and zhi (e.g. its auto slab), read as a c_ID[5] and c_ID[6] reference would (its doc page;
   test_computes.py checks the histograms against zlo/zhi given as numbers).
------------------------------------------------------------------------- */

#ifndef LMP_GRANULAR_SLAB_H
#define LMP_GRANULAR_SLAB_H

namespace LAMMPS_NS {
class Compute;
class LAMMPS;

class SlabOption {
 public:
  static constexpr int ZLO_ELEMENT = 5, ZHI_ELEMENT = 6;

  struct Bounds {
    double zlo, zhi;    // -/+ HUGE_VAL for a side not given
    bool used;          // any of zlo, zhi, slab given
  };

  // name: the compute style as it appears in messages ("contact/histo")
  SlabOption(LAMMPS *lmp, const char *name) : lmp(lmp), name(name) {}
  ~SlabOption();
  SlabOption(const SlabOption &) = delete;
  SlabOption &operator=(const SlabOption &) = delete;

  // true when key is zlo, zhi or slab (value: its argument)
  bool parse(const char *key, const char *value);
  // after all keywords: ERROR for slab with zlo/zhi, or zhi <= zlo
  void check() const;
  // the compute's init(): finds the slab compute (ERROR when it is missing or not
  // packing/ellipsoid); bounds() finds it again by its ID
  void init();
  // the slab of this step (invokes the slab compute when it is not current)
  Bounds bounds() const;

 private:
  LAMMPS *lmp;
  const char *name;
  bool have_zlo = false, have_zhi = false;
  double zlo_user = 0.0, zhi_user = 0.0;
  char *slab_id = nullptr;
  Compute *find() const;
};

// the bins keyword's value arg[iarg] of a histogram compute (name: its style, for the
// messages), one limit for all of them: far above any histogram of a deposit, and small
// enough that the arrays stay a few tens of MB and the per-bin sums of one MPI reduction fit
// its int count
constexpr int HISTOGRAM_MAX_BINS = 1000000;
int parse_histogram_bins(LAMMPS *lmp, const char *name, int iarg, const char *value);

}    // namespace LAMMPS_NS

#endif
