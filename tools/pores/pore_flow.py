"""Permeability of a voxel image from a Stokes-flow solve with OpenFOAM (doc/howto_pores.md).

    permeability(solid, spacing, periodic=(True, True, False)) -> {"xx", "yy", "zz", ...}

solid[i, j, k] is True in the solid; periodic says which axes of the image are periodic (a
deposit's slab: x and y). Along an axis that is not, the image is cut out of something larger:
its two faces are symmetry planes (slip walls: the same as continuing the image by its mirror
image) for flow across the other axes, and for flow along that axis the image is followed by
its mirror image along it, which makes the domain periodic there at twice the cells. Mesh:
blockMesh makes one hexahedral cell per voxel (cyclic patches on the periodic faces, symmetry
planes on the others); subsetMesh keeps
the pore voxels and puts the faces it exposes into the wall patch "walls" (the stair-step
surface of the particles). Flow: simpleFoam (laminar, SIMPLEC) driven by a uniform body force g
along x, y, z in turn at a Reynolds number far below 1. Darcy's law gives k_ii = nu <u_i> / g
with <u_i> the superficial (box-averaged) velocity. OpenFOAM is Debian's openfoam (1912), its
environment sourced in the subshell that runs each utility, every utility under nice -n 10.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

OPENFOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"
NU = 1.0                 # kinematic viscosity
BODY_FORCE = 1.0e-3      # g (pressure gradient per density); Re = <u> L / nu stays << 1
TOLERANCE = 1.0e-6       # initial residuals of U and p at which the solve stops
MAX_ITERATIONS = 4000
WRITE_EVERY = 10         # iterations between writes of the fields (the last two are kept)
PARALLEL_CELLS = 300_000  # decomposePar onto 2 ranks above this many cells
DIRECTIONS = {"xx": 0, "yy": 1, "zz": 2}
NICENESS = 10            # the machine is shared: every OpenFOAM utility runs at this niceness
PROGRESS_SECONDS = 10.0  # between the progress lines of a solve (the first comes at once)


class FlowError(RuntimeError):
    """a flow solve that cannot run or did not converge (the message says why)"""


def require_openfoam():
    if not os.path.exists(OPENFOAM_BASHRC):
        raise FlowError("OpenFOAM is not installed (%s missing): `./ellipsoid-dep pores DIR "
                        "--flow` installs Debian's openfoam on first use (apt-get install "
                        "openfoam)" % OPENFOAM_BASHRC)


def foam(case, command, log=None, on_line=None):
    """run an OpenFOAM command in case (a subshell with its environment, nice -n 10); the
    output goes to case/log.<name> and each line to on_line; FlowError on failure"""
    name = log or command.split()[0]
    nice = max(0, NICENESS - os.nice(0))    # niceness 10 in all, not 10 more
    script = ('source %s >/dev/null 2>&1 || true; cd "%s" && exec nice -n %d %s'
              % (OPENFOAM_BASHRC, case, nice, command))
    path = os.path.join(case, "log." + name)
    with open(path, "w") as out:
        # as the entry script: Open MPI may run as root (containers) and oversubscribe
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
        proc = subprocess.Popen(["bash", "-c", script], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, env=env)
        if on_line is not None and hasattr(on_line, "process"):
            on_line.process = proc    # bash execs the utility (or mpirun): the same pid
        for line in proc.stdout:
            out.write(line)
            if on_line:
                on_line(line)
        proc.wait()
    if proc.returncode != 0 and not getattr(on_line, "stopped", False):
        with open(path) as f:
            tail = "".join(f.readlines()[-15:])
        raise FlowError("OpenFOAM %s failed (exit %d):\n%s" % (name, proc.returncode, tail))


def header(cls, obj, location=None):
    loc = '    location "%s";\n' % location if location else ""
    return ("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n%s"
            "    object %s;\n}\n" % (cls, loc, obj))


def write(case, rel, text):
    path = os.path.join(case, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


AXIS_PATCHES = (("left", "right"), ("front", "back"), ("bottom", "top"))


def block_mesh_dict(shape, lengths, periodic):
    nx, ny, nz = shape
    lx, ly, lz = lengths
    v = [(0, 0, 0), (lx, 0, 0), (lx, ly, 0), (0, ly, 0),
         (0, 0, lz), (lx, 0, lz), (lx, ly, lz), (0, ly, lz)]
    pairs = (("left", "(0 4 7 3)", "right", "(1 2 6 5)"),
             ("front", "(0 1 5 4)", "back", "(3 7 6 2)"),
             ("bottom", "(0 3 2 1)", "top", "(4 5 6 7)"))
    patches = ""
    for axis, (a, fa, b, fb) in enumerate(pairs):
        for me, faces, other in ((a, fa, b), (b, fb, a)):
            if not periodic[axis]:
                kind = "symmetryPlane;"
            else:
                kind = "cyclic;\n        neighbourPatch %s;" % other
            patches += ("    %s\n    {\n        type %s\n        faces (%s);\n    }\n"
                        % (me, kind, faces))
    patches += "    walls\n    {\n        type wall;\n        faces ();\n    }\n"
    return (header("dictionary", "blockMeshDict") + "scale 1;\nvertices\n(\n"
            + "".join("    (%.17g %.17g %.17g)\n" % p for p in v) + ");\n"
            + "blocks\n(\n    hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1)\n);\n"
            % (nx, ny, nz) + "edges ();\nboundary\n(\n" + patches + ");\n")


def cell_set(labels):
    return (header("cellSet", "fluid", "constant/polyMesh/sets") + "%d\n(\n" % len(labels)
            + "\n".join(map(str, labels)) + "\n)\n")


CONTROL = """application simpleFoam;
startFrom latestTime;
startTime 0;
stopAt endTime;
endTime %d;
deltaT 1;
writeControl timeStep;
writeInterval %d;
purgeWrite 2;
writeFormat ascii;
writePrecision 12;
writeCompression off;
timeFormat general;
timePrecision 8;
runTimeModifiable false;
"""

SCHEMES = """ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) bounded Gauss linear;
             div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
"""

SOLUTION = """solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-10; relTol 0.01; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-12; relTol 0.05; }
}
SIMPLE
{
    nNonOrthogonalCorrectors 0;
    consistent yes;
    pRefCell 0;
    pRefValue 0;
}
relaxationFactors { equations { U 0.9; ".*" 0.9; } }
"""


def field(cls, name, dims, value, walls, periodic):
    patches = "".join('    %s { type %s; }\n'
                      % (p, "cyclic" if periodic[axis] else "symmetryPlane")
                      for axis, pair in enumerate(AXIS_PATCHES) for p in pair)
    return (header(cls, name) + "dimensions %s;\ninternalField uniform %s;\n"
            "boundaryField\n{\n%s    walls { %s }\n}\n" % (dims, value, patches, walls))


def mirrored(solid, axis):
    """the image followed by its mirror image along axis: periodic along it"""
    return np.concatenate([solid, np.flip(solid, axis)], axis=axis)


def setup_case(case, solid, spacing, periodic, progress):
    """the mesh of the pore voxels of the image (faces cyclic where periodic, else symmetry
    planes) and the case files; returns the number of cells"""
    shape = solid.shape
    lengths = [n * h for n, h in zip(shape, spacing)]
    write(case, "system/blockMeshDict", block_mesh_dict(shape, lengths, periodic))
    write(case, "system/controlDict", header("dictionary", "controlDict")
          + CONTROL % (MAX_ITERATIONS, WRITE_EVERY))
    write(case, "system/fvSchemes", header("dictionary", "fvSchemes") + SCHEMES)
    write(case, "system/fvSolution", header("dictionary", "fvSolution")
          + SOLUTION)
    write(case, "system/decomposeParDict", header("dictionary", "decomposeParDict")
          + "numberOfSubdomains 2;\nmethod simple;\n"
          "simpleCoeffs\n{\n    n (2 1 1);\n    delta 0.001;\n}\n")
    write(case, "constant/transportProperties", header("dictionary", "transportProperties")
          + "transportModel Newtonian;\nnu %.17g;\n" % NU)
    write(case, "constant/turbulenceProperties", header("dictionary", "turbulenceProperties")
          + "simulationType laminar;\n")
    progress("flow mesh: blockMesh %d x %d x %d" % shape)
    foam(case, "blockMesh")
    # blockMesh numbers the cells x fastest, then y, then z
    fluid = np.flatnonzero(~solid.transpose(2, 1, 0).ravel())
    write(case, "constant/polyMesh/sets/fluid", cell_set(fluid))
    progress("flow mesh: subsetMesh keeps %d pore cells" % len(fluid))
    foam(case, "subsetMesh fluid -patch walls -overwrite")
    return len(fluid)


def write_start_fields(case, direction, periodic):
    g = [0.0, 0.0, 0.0]
    g[direction] = BODY_FORCE
    shutil.rmtree(os.path.join(case, "0"), ignore_errors=True)
    write(case, "0/U", field("volVectorField", "U", "[0 1 -1 0 0 0 0]", "(0 0 0)",
                             "type noSlip;", periodic))
    write(case, "0/p", field("volScalarField", "p", "[0 2 -2 0 0 0 0]", "0",
                             "type zeroGradient;", periodic))
    write(case, "constant/fvOptions", header("dictionary", "fvOptions")
          + "bodyForce\n{\n    type vectorSemiImplicitSource;\n    selectionMode all;\n"
          "    volumeMode specific;\n    injectionRateSuSp\n    {\n"
          "        U ((%.17g %.17g %.17g) 0);\n    }\n}\n" % tuple(g))


RESIDUAL = re.compile(r"Solving for (Ux|Uy|Uz|p), Initial residual = ([0-9.eE+-]+)")
CPU_TIME = re.compile(r"^ExecutionTime = ([0-9.eE+-]+) s")    # simpleFoam's (rank 0's) CPU


def solve_name(label, key):
    """the start of a solve's progress lines: flow, the resolution, the direction"""
    return " ".join(w for w in ("flow", label, key) if w)


class ResidualMonitor:
    """the initial residuals of each SIMPLE iteration; a progress line (the resolution, the
    direction, the iteration and the residuals) at the first iteration and then every
    PROGRESS_SECONDS. Once the driven velocity component's residual is below TOLERANCE it
    ends simpleFoam (or mpirun) once every rank has written the fields the next time. The other
    components and p are reported, not tested: where their exact solution is zero or uniform
    (a slit, a straight duct) a normalised residual is round-off over round-off."""

    def __init__(self, progress, key, label):
        self.progress, self.name = progress, solve_name(label, key)
        self.driven = "U" + "xyz"[DIRECTIONS[key]]
        self.iteration, self.residuals, self.last = 0, {}, None
        self.completed = {}
        self.converged = False
        self.stopped = False
        self.process = None
        self.last_write = None
        self.cpu_seconds = 0.0

    def __call__(self, line):
        cpu = CPU_TIME.match(line)
        if cpu:
            self.cpu_seconds = float(cpu.group(1))
        if line.startswith("Time = "):
            if not self.converged and self.residuals.get(self.driven, 1.0) <= TOLERANCE:
                self.converged = True
                self.last_write = WRITE_EVERY * -(-self.iteration // WRITE_EVERY)
            self.completed = self.residuals    # of the iteration just finished
            if self.completed and (self.last is None
                                   or time.time() - self.last >= PROGRESS_SECONDS):
                self.last = time.time()
                self.progress("%s: iteration %d, residual %s %.2e (%s; stops below %.0e)" % (
                    self.name, self.iteration, self.driven, self.completed.get(self.driven, 1.0),
                    " ".join("%s %.1e" % kv for kv in sorted(self.completed.items())
                             if kv[0] != self.driven), TOLERANCE))
            self.iteration = int(float(line.split()[2]))
            self.residuals = {}
        m = RESIDUAL.search(line)
        if m and self.converged and not self.stopped and self.iteration > self.last_write:
            # the first residual of the next iteration is a reduction over all ranks: each
            # has finished writing the fields of iteration last_write
            self.stopped = True
            self.process.terminate()
        if m and m.group(1) not in self.residuals:
            self.residuals[m.group(1)] = float(m.group(2))


def written_times(folder):
    """the time folders simpleFoam wrote in folder (not the start fields), newest first"""
    return sorted((d for d in os.listdir(folder) if re.fullmatch(r"[0-9.eE+-]+", d) and d != "0"),
                  key=float, reverse=True)


def complete(path):
    """whether OpenFOAM finished writing the file: it ends every file with its trailer line"""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            f.seek(max(0, f.tell() - 200))
            return f.read().rstrip().endswith(b"// " + b"*" * 73 + b" //")
    except OSError:
        return False


def newest_complete_time(folders, last_write):
    """the newest time whose U every folder (the case, or each rank's processor folder) holds
    complete. The monitor ends simpleFoam once it has read past the write of last_write, but it
    reads the solver's output through a pipe and may lag behind it: the solver can be killed
    while writing a later time. The write before that one, kept by purgeWrite 2, is complete
    and no older than last_write."""
    common = set.intersection(*(set(written_times(f)) for f in folders))
    for t in sorted(common, key=float, reverse=True):
        if all(complete(os.path.join(f, t, "U")) for f in folders):
            if last_write is not None and float(t) < last_write:
                raise FlowError("the newest complete write, %s, is older than the converged "
                                "one, %d" % (t, last_write))
            return t
    raise FlowError("simpleFoam wrote no complete result")


def read_velocity(case, ncells, latest):
    """the internal velocity field of time latest (ascii) -> (ncells, 3)"""
    with open(os.path.join(case, latest, "U")) as f:
        text = f.read()
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    if not m:
        raise FlowError("cannot read %s/U" % latest)
    n = int(m.group(1))
    body = text[m.end():text.index("\n)\n", m.end())]
    u = np.array(body.replace("(", " ").replace(")", " ").split(), dtype=float).reshape(n, 3)
    if n != ncells:
        raise FlowError("U has %d values for %d cells" % (n, ncells))
    return u, int(float(latest))


def solve(case, key, ncells, total, parallel, progress, label):
    """one direction on the mesh in case: (k, residuals, iterations, simpleFoam's CPU s)"""
    a = DIRECTIONS[key]
    for d in [d for d in os.listdir(case) if d.startswith("processor")] + written_times(case):
        shutil.rmtree(os.path.join(case, d))
    monitor = ResidualMonitor(progress, key, label)
    progress("%s: simpleFoam on %d cells, %d rank%s" % (monitor.name, ncells, 1 + parallel,
                                                          "s" if parallel else ""))
    if parallel:
        foam(case, "decomposePar -force")
        foam(case, "mpirun -np 2 simpleFoam -parallel", log="simpleFoam." + key,
             on_line=monitor)
        ranks = sorted(os.path.join(case, d) for d in os.listdir(case) if d.startswith("processor"))
        latest = newest_complete_time(ranks, monitor.last_write)
        foam(case, "reconstructPar -time %s" % latest)
    else:
        foam(case, "simpleFoam", log="simpleFoam." + key, on_line=monitor)
        latest = newest_complete_time([case], monitor.last_write)
    u, iterations = read_velocity(case, ncells, latest)
    residuals = dict(monitor.completed if monitor.stopped else monitor.residuals)
    if not monitor.converged:
        raise FlowError("flow %s did not converge in %d iterations (residuals %s)"
                        % (key, iterations, residuals))
    return NU * u[:, a].sum() / total / BODY_FORCE, residuals, iterations, monitor.cpu_seconds


def permeability(solid, spacing, directions=("xx", "yy", "zz"), progress=None, workdir=None,
                 periodic=(True, True, False), label=""):
    """k along the given directions (units of spacing^2) of the pore space of solid; the axes
    that are not periodic are mirrored for the flow along them and symmetry planes otherwise
    (see above). label (the resolution) starts the progress lines."""
    require_openfoam()
    progress = progress or (lambda msg: None)
    solid = np.asarray(solid, bool)
    periodic = tuple(bool(p) for p in periodic)
    result = {"voxel_spacing": list(map(float, spacing)), "image_xyz": list(solid.shape),
              "periodic": list(periodic), "body_force": BODY_FORCE, "nu": NU,
              "tolerance": TOLERANCE, "cells": {}, "ranks": {}, "residuals": {},
              "iterations": {}, "seconds": {}, "solver_cpu_seconds": {}}
    meshes = {}    # mirrored axis (None: the image as it is) -> directions solved on it
    for key in directions:
        a = DIRECTIONS[key]
        meshes.setdefault(None if periodic[a] else a, []).append(key)
    for axis, keys in meshes.items():
        image, cyclic = solid, periodic
        if axis is not None:
            image = mirrored(solid, axis)
            cyclic = tuple(p or a == axis for a, p in enumerate(periodic))
        case = tempfile.mkdtemp(prefix="pore_flow_", dir=workdir)
        try:
            t0 = time.time()
            ncells = setup_case(case, image, spacing, cyclic, progress)
            parallel = ncells > PARALLEL_CELLS
            for key in keys:
                write_start_fields(case, DIRECTIONS[key], cyclic)
                k, residuals, iterations, cpu = solve(case, key, ncells, image.size,
                                                      parallel, progress, label)
                result[key] = k
                result["cells"][key] = ncells
                result["ranks"][key] = 2 if parallel else 1
                result["residuals"][key] = residuals
                result["iterations"][key] = iterations
                result["seconds"][key] = time.time() - t0    # with the meshing
                result["solver_cpu_seconds"][key] = cpu
                progress("%s: k = %.5g after %d iterations (%.0f s)" % (
                    solve_name(label, key), k, iterations, result["seconds"][key]))
                t0 = time.time()
        finally:
            shutil.rmtree(case, ignore_errors=True)
    return result


if __name__ == "__main__":    # a quick look: a slit of 8 cells between two solid layers
    s = np.zeros((2, 2, 10), bool)
    s[:, :, 0] = s[:, :, -1] = True
    print(permeability(s, (0.125,) * 3, ("xx",), periodic=(True, True, True),
                       progress=lambda m: print(m, file=sys.stderr)))
