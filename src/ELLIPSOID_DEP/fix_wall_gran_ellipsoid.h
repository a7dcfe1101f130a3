/* -*- c++ -*- ----------------------------------------------------------
   ELLIPSOID_DEP: fix wall/gran/ellipsoid
   Flat walls (planes normal to x, y or z) for general ellipsoids: the kernel's exact
   ellipsoid-plane contact and the SAME force law as pair granular/ellipsoid (ForceLaw,
   parsed by parse_force_law from the pair_coeff words). See doc/fix_wall_gran_ellipsoid.rst.
   The base of fix wall/gran/region/ellipsoid, whose walls are a region's faces: the force
   law's words, the per-atom history per wall, the contacts array and the force loop are
   this class's; the walls' source and motion are the hooks below.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_WALL_GRAN_ELLIPSOID_H
#define LMP_FIX_WALL_GRAN_ELLIPSOID_H

#include "fix.h"

#include "ellipsoid_force_law.h"
#include "ellipsoid_wall_contact.h"
#include "granular_contact_time.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallGranEllipsoid : public Fix {
 public:
  FixWallGranEllipsoid(class LAMMPS *, int, char **);
  ~FixWallGranEllipsoid() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  void post_run() override;
  double compute_vector(int) override;
  double memory_usage() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // the walls' law (fix pour/ellipsoid checks the time step of its particles against it)
  const EllipsoidDep::ForceLaw &force_law() const { return law; }
  // the walls where the last step placed them (fix pour/ellipsoid inserts clear of them)
  const std::vector<EllipsoidDep::WallSurface> &surfaces() const { return walls; }

 protected:
  // region_style: the words of fix wall/gran/region/ellipsoid (region ID, no planes, no
  // wiggle, shear or servo); the derived class builds the walls and calls allocate_walls()
  FixWallGranEllipsoid(class LAMMPS *, int, char **, bool region_style);
  void allocate_walls();
  bool allocated = false;    // allocate_walls() registered the atom callbacks
  bool setup_reported = false;    // the first run's setup checks were reported
  const bool region_style;
  std::string region_id;    // region_style: the region keyword's value
  // the hooks: the walls at this step, a wall's velocity at a point of its surface (LAMMPS's
  // region walls: at the wall's point of the contact), whether atom i can touch the walls
  virtual void update_walls() { move_walls(); }
  virtual EllipsoidDep::Vec3 velocity_at(int /*wall*/, const EllipsoidDep::Vec3 & /*point*/) const
  {
    return wall_velocity;
  }
  virtual bool reaches_walls(int /*i*/) const { return true; }

  // the walls' surfaces in the kernel's terms (planes: xplane, yplane, zplane), at this step
  std::vector<EllipsoidDep::WallSurface> walls;
  // wiggle or shear, as fix wall/gran's: every wall of the fix moves along dim; a wiggled
  // wall normal to dim is at rest_offset + A (1 - cos(omega t)) along its normal's dim
  // component, t the simulation time since the fix was defined (a timestep changed between
  // runs keeps the phase)
  // servo: the one wall moves along its normal n at u = G (F_target - F), |u| <= vmax, F the
  // normal force the particles exerted on it at the previous step, or that force low-pass
  // filtered with the time constant filter_time (> 0: the loop then stays away from the time
  // step's frequency, where the contacts' inertia and damping make it chatter)
  struct Motion {
    enum class Kind { None, Wiggle, Shear, Servo } kind = Kind::None;
    int dim = -1;
    double amplitude = 0.0, omega = 0.0, vshear = 0.0;
    double time_origin = 0.0;    // the simulation time the fix was defined at
    bool stress = false;          // servo target: a stress (times area)
    double area = 0.0;            // servo stress: the area it acts on (0: the box's cross-section)
    double target = 0.0, gain = 0.0, vmax = 0.0;
    double force = 0.0;           // servo: its measure of the particles' push on the wall
    double filter_time = 0.0;     // servo: the measure's low-pass time constant (0: none)
    bool measured = false;        // servo: force holds a measure (a run or the restart set it)
    double speed = 0.0;           // servo: u of this step
  } motion;
  std::vector<double> rest_offset;     // the walls' offsets when the wiggle's phase is 0
  EllipsoidDep::Vec3 wall_velocity;    // of every wall, at this step
  int parse_wall_material(int iarg, int narg, char **arg, const EllipsoidDep::ForceLaw &particle_law,
                          const EllipsoidDep::MaterialLookup &lookup);
  int parse_plane(int iarg, int narg, char **arg, bool seen[3]);
  int parse_motion(int iarg, int narg, char **arg);
  int parse_servo(int iarg, int narg, char **arg);
  void move_walls();
  double simulation_time() const;    // LAMMPS's thermo keyword time
  void measure_servo_force();
  // the contacts keyword: fix wall/gran's per-atom array of 8 columns
  static constexpr int CONTACT_COLUMNS = 8;
  void record_contact(int i, const EllipsoidDep::ContactForce &result,
                      const EllipsoidDep::ContactGeometry &g);
  double servo_target() const;    // in force units
  EllipsoidDep::ForceLaw law;
  // the per-atom history (fix_wall_gran_ellipsoid_history.cpp): per wall one slot per contact
  // region it may have (several_contacts: MAX_FACE_CONTACTS, each the contact's last normal
  // and the law's history; other walls: one, the law's history); none without a law history
  int size_history;                   // per atom
  std::vector<int> history_offset;    // of each wall's first slot
  int history_layout();
  void match_history(int i, int k, const EllipsoidDep::FaceContacts &found, double *slot[]);
  double **history_one;    // per atom
  bool history_update;
  double impact_velocity;          // keyword; 0: the fastest atom of the group
  ContactTimes times_reported;    // last contact and damping times logged
  void update_contact_times();

  std::vector<double> wall_force;        // local sums, 3 per wall
  std::vector<double> wall_force_all;    // summed over ranks
  int force_flag;
  bigint unconverged = 0, degenerate = 0;    // curved walls' kernel failures in this run

  void wall_forces();
};

}    // namespace LAMMPS_NS

#endif
