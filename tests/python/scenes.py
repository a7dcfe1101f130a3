"""Small LAMMPS scenes shared by the tests (inputs as text or lists of commands, so they run
anywhere: in a Python lammps instance or a separate lmp process under mpirun)."""


def _lattice_atoms(nx, ny, nz, spacing):
    """create_atoms single in a fixed order, so atom IDs do not depend on the rank count"""
    return "\n".join(f"create_atoms 1 single {(i + 0.5) * spacing} {(j + 0.5) * spacing} "
                     f"{(k + 0.5) * spacing}"
                     for k in range(nz) for j in range(ny) for i in range(nx))


def dense_ellipsoids(tangential="history 2.0e4 0.5", newton="off", seed=4827, extra=""):
    """A periodic box of triaxial ellipsoids (a:b:c = 0.7:0.5:0.36) with random orientations
    and velocities, packed so that many touch; gravity makes it move."""
    return f"""
units lj
atom_style ellipsoid
atom_modify map array
newton {newton}
comm_modify vel yes
boundary p p p
region box block 0 5.75 0 5.75 0 4.6
create_box 1 box
{_lattice_atoms(5, 5, 4, 1.15)}
set type 1 mass 1.0
set type 1 shape 1.4 1.0 0.72
set type 1 quat/random {seed}
velocity all create 0.5 {seed + 1} loop geom
pair_style granular/ellipsoid
pair_coeff * * hertz 2.0e4 20.0 tangential {tangential}
fix integrate all nve/ellipsoid
fix fall all gravity 1.0 vector 0 0 -1
timestep 2e-4
thermo_style custom step ke
{extra}
"""


def sphere_over_wall(radius, height, wall, velocity=(0.0, 0.0, 0.0), units="lj"):
    """One sphere of density 1 at height z over `fix w all wall/gran/ellipsoid {wall}` in a
    box periodic in x and y (its z boundary is fixed)."""
    return f"""
units {units}
atom_style ellipsoid
boundary p p f
comm_modify vel yes
region box block -2 2 -2 2 0 4
create_box 1 box
create_atoms 1 single 0 0 {height}
set atom 1 shape {2 * radius} {2 * radius} {2 * radius}
set atom 1 density 1.0
velocity all set {velocity[0]} {velocity[1]} {velocity[2]}
fix w all wall/gran/ellipsoid {wall}
"""


def spheres_in_box(style, box, positions, radius, density=1.0, boundary="p p f"):
    """Spheres of one radius at the given positions in a box periodic in x and y (z fixed;
    or `boundary`): LAMMPS's atom_style sphere (style 'sphere') or this package's ellipsoids
    (any other)."""
    size = (f"diameter {2 * radius}" if style == "sphere"
            else f"shape {2 * radius} {2 * radius} {2 * radius}")
    atoms = "\n".join("create_atoms 1 single {} {} {}".format(*p) for p in positions)
    return f"""
units lj
atom_style {style}
atom_modify map array
boundary {boundary}
comm_modify vel yes
region box block 0 {box[0]} 0 {box[1]} 0 {box[2]}
create_box 1 box
{atoms}
set type 1 {size}
set type 1 density {density}
"""


def particle_box(style, lo, hi, ntypes=1, boundary="p p p"):
    """The opening of a granular input: lj units, the atom style, an atom map (for setting
    values by ID), ghost velocities, and a cubic box [lo, hi]^3 of ntypes atom types."""
    return f"""
units lj
atom_style {style}
atom_modify map array
comm_modify vel yes
boundary {boundary}
region box block {lo} {hi} {lo} {hi} {lo} {hi}
create_box {ntypes} box
"""


def empty_pair_box(units="lj"):
    """A box of one ellipsoid with pair_style granular/ellipsoid defined and no coefficients:
    for what pair_coeff accepts and refuses."""
    return f"""
units {units}
atom_style ellipsoid
comm_modify vel yes
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 single 1 1 1
set type 1 shape 1.0 1.0 1.0
set type 1 density 1.0
pair_style granular/ellipsoid
"""


def shapeless_deposit(pair=True):
    """One ellipsoid on a wall; fix deposit adds plain atoms (no shape, the first, atom 2, at
    step 1) that fix nve/asphere integrates without a check: under pair granular/ellipsoid and
    the wall (pair=True), or the wall alone. Unchecked, the pair read outside its arrays, both
    ignored the new atoms, and the run ended in lost atoms."""
    return f"""
units lj
atom_style ellipsoid
boundary p p f
comm_modify vel yes
region box block 0 6 0 6 0 12
create_box 1 box
create_atoms 1 single 3 3 0.5
set atom 1 shape 1 0.8 0.6
set atom 1 density 1.0
{"pair_style granular/ellipsoid" if pair else ""}
{"pair_coeff * * hertz 1e4 10" if pair else ""}
fix g all gravity 1.0 vector 0 0 -1
fix w all wall/gran/ellipsoid hertz 1e4 10 zplane 0 NULL
region ins block 1 5 1 5 6 10
fix d all deposit 3 1 100 4767 region ins near 1.0 vz -1 -1
fix i all nve/asphere
timestep 1e-3
"""


# A pour of MID_POUR_N triaxial ellipsoids (pair and wall with tangential history and rolling,
# x and y periodic) inserted in batches every 1200 steps: at step MID_POUR_HALF some are still
# to come and many touch; MID_POUR_REST more steps insert the rest.
MID_POUR_N = 80
MID_POUR_HALF, MID_POUR_REST = 3000, 3000
MID_POUR_LAW = "hertz/material 2e6 0.3 0.5 tangential history 1e4 0.5 rolling constant 0.02"


def mid_pour_commands():
    """The whole input after `pair_style granular/ellipsoid`."""
    return [
        "units lj", "atom_style ellipsoid", "atom_modify map array", "boundary p p f",
        "comm_modify vel yes", "region box block 0 8 0 8 0 10", "create_box 1 box",
    ] + mid_pour_continuation() + ["timestep 1e-3"]


def mid_pour_continuation():
    """Everything an input re-specifies after read_restart (the pair style comes from the
    file) except the time step."""
    return [
        "region ins block 0 8 0 8 1.5 6",
        f"pair_coeff * * {MID_POUR_LAW}",
        f"fix p all pour/ellipsoid {MID_POUR_N} 1 8087 region ins size mean 0.7 delta_r 0.3 "
        "shape 1.5 1.3 density 1 vol 0.1 200 every 1200",
        "fix g all gravity 1.0 vector 0 0 -1",
        "fix i all nve/asphere",
        f"fix w all wall/gran/ellipsoid {MID_POUR_LAW} zplane 0 NULL",
        "compute pk all packing/ellipsoid 0.0 2.0",
        "thermo_style custom step atoms f_p c_pk[1] c_pk[2]",
        "thermo 500",
    ]


def floor_stack(contacts="contacts", walls="wall floor"):
    """Three ellipsoids above a floor wall (fix floor): A on the floor, B tilted on A, C in the
    air; compute unb all unbalanced/force (test_unbalanced_force.py's oracle scene)."""
    return f"""
units lj
atom_style ellipsoid
atom_modify map array
boundary p p f
comm_modify vel yes
region box block 0 4 0 4 0 6
create_box 1 box
create_atoms 1 single 2.0 2.0 0.24
create_atoms 1 single 2.1 2.05 0.70
create_atoms 1 single 1.0 1.0 4.0
set type 1 shape 1.0 0.8 0.5
set type 1 density 1.0
set atom 2 quat 1 1 0 30
pair_style granular/ellipsoid
pair_coeff * * hertz 1.0e4 50.0 tangential history 2.0e3 0.5
fix floor all wall/gran/ellipsoid hertz 1.0e4 50.0 tangential history 2.0e3 0.5 zplane 0.0 NULL {contacts}
fix grav all gravity 1.0 vector 0 0 -1
compute unb all unbalanced/force {walls}
timestep 1.0e-4
"""
