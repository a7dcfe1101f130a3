"""valgrind --leak-check=full on a short deposit: no leak and no memory error from the package.

Run by `./ellipsoid-dep test --sanitize` (after the sanitizer tests) with the normal build's
plugin, or by hand: `./ellipsoid-dep python tests/python/valgrind_deposit.py [N]`.
Exits non-zero when a valgrind record (definitely, indirectly or possibly lost block, invalid
read/write, use of an uninitialised value, bad free) has a frame in the plugin. The host's
own records (Open MPI, LAMMPS) are counted and printed, not judged.
"""
import os
import re
import subprocess
import sys
import tempfile

PACKAGE_FRAME = re.compile(r"ellipsoiddepplugin\.so|ELLIPSOID_DEP/")
RECORD_START = re.compile(r"^==\d+== (\S.*)$")


def records(log):
    """valgrind's records: the blocks of '==pid==' lines separated by empty ones."""
    block = []
    for line in log.splitlines():
        m = RECORD_START.match(line)
        if m:
            block.append(m.group(1))
        elif block:
            yield block
            block = []
    if block:
        yield block


def main():
    # 40: the smallest N whose pour region (scaled with N by the input) holds its particles
    n = sys.argv[1] if len(sys.argv) > 1 else "40"
    root = os.environ["ELLIPSOID_DEP_ROOT"]
    with tempfile.TemporaryDirectory(prefix="valgrind_deposit_") as out:
        # keep-debuginfo: LAMMPS unloads the plugin before exit, and the frames of a leak
        # from an unloaded object would otherwise print as '???' with no file name
        cmd = ["valgrind", "--leak-check=full", "--show-leak-kinds=definite,indirect,possible",
               "--num-callers=40", "--keep-debuginfo=yes", f"--log-file={out}/valgrind.log",
               os.environ["ELLIPSOID_DEP_LMP"], "-in",
               os.path.join(root, "examples/deposit/in.deposit"), "-var", "N", n,
               "-var", "tangential", "history 2.0e3 0.5", "-var", "chunk", "2000",
               "-var", "maxchunks", "3", "-var", "image", "0", "-var", "out", out,
               "-log", f"{out}/log.lammps", "-nocite", "-screen", "none"]
        print("running:", " ".join(cmd), flush=True)
        run = subprocess.run(cmd, cwd=out, capture_output=True, text=True)
        with open(f"{out}/valgrind.log") as f:
            log = f.read()
        with open(os.path.join(root, "build", "valgrind_deposit.log"), "w") as f:
            f.write(log)
        finished = os.path.exists(f"{out}/packing.dat")
        if not finished:
            with open(f"{out}/log.lammps") as f:
                print(f.read()[-2000:])
    ours, host, anonymous = [], 0, 0
    for block in records(log):
        head = block[0]
        if not re.search(r"lost in loss record|Invalid (read|write|free)|uninitialised|"
                         r"Mismatched free|Syscall param", head):
            continue
        if any(PACKAGE_FRAME.search(l) for l in block):
            ours.append("\n  ".join(block))
        else:
            host += 1
        # a frame valgrind cannot place in any object: attribution would be blind there
        anonymous += sum(1 for l in block if re.search(r"\?\?\?$", l))
    summary = [l for l in log.splitlines() if re.search(r"(definitely|indirectly|possibly) "
                                                        r"lost:|ERROR SUMMARY", l)]
    print("\n".join(summary))
    print(f"valgrind_deposit: N {n}, exit {run.returncode}, packing.dat written: {finished}; "
          f"records with a package frame: {len(ours)}, host-only records: {host}, "
          f"frames in no object: {anonymous} (log: build/valgrind_deposit.log)")
    for r in ours:
        print("PACKAGE RECORD:\n  " + r)
    if run.returncode != 0 or not finished or ours or anonymous:
        sys.exit(1)


if __name__ == "__main__":
    main()
