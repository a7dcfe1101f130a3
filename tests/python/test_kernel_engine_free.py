"""The kernel (src/kernel, with its force laws) is engine-free: C++17 and Eigen only, so that it
builds and is tested alone and the LIGGGHTS adapter reuses it. Every quoted #include of a kernel
file names another kernel file, every angle-bracket one a standard header (no file extension)
or Eigen, and no kernel file names LAMMPS's namespace or MPI. (Its CMake target also has no
LAMMPS include path, so such a header would not be found; this test names the file.)"""
import os
import re

from conftest import root_dir

KERNEL = os.path.join(root_dir(), "src", "kernel")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def kernel_files():
    for folder, _, names in os.walk(KERNEL):
        for name in names:
            if name.endswith((".h", ".cpp")):
                yield os.path.join(folder, name)


def violations(text, kernel_names):
    """What in one file's text is not engine-free."""
    found = []
    for kind, name in INCLUDE.findall(text):
        if kind == '"' and os.path.basename(name) not in kernel_names:
            found.append(f'#include "{name}"')
        if kind == "<" and not (name.startswith("Eigen/") or "." not in name):
            found.append(f"#include <{name}>")
    for word in ("LAMMPS_NS", "MPI_"):
        if word in text:
            found.append(word)
    return found


def test_kernel_includes_only_itself_the_standard_library_and_eigen():
    files = list(kernel_files())
    names = {os.path.basename(f) for f in files}
    assert len(files) > 15 and "ellipsoid_shape.h" in names and "ellipsoid_force_law.h" in names
    bad = {}
    for path in files:
        with open(path) as f:
            found = violations(f.read(), names)
        if found:
            bad[os.path.relpath(path, KERNEL)] = found
    assert not bad, bad


def test_the_check_finds_an_engine_header():
    names = {"ellipsoid_shape.h"}
    assert violations('#include "ellipsoid_shape.h"\n#include <cmath>\n#include <Eigen/Dense>\n',
                      names) == []
    assert violations('#include "pointers.h"\n', names) == ['#include "pointers.h"']
    assert violations("#include <mpi.h>\n", names) == ["#include <mpi.h>"]
    assert violations("using namespace LAMMPS_NS;\n", names) == ["LAMMPS_NS"]
