"""The checkpoints of tools/deposit/deposit_run.py: LAMMPS restart files written alternately to
checkpoint.a and checkpoint.b in the run folder; the newer complete one is resumed from. A
resumed run's cost counts its earlier segments from their LAMMPS logs."""
import glob
import os
import re
import struct

CHECKPOINTS = ("checkpoint.a", "checkpoint.b")
RESTART_MAGIC = b"LammpS RestartT\0"
# flags of the restart header (enum in LAMMPS lmprestart.h) up to the time step: strings
# (VERSION, UNITS), ints (SMALLINT, TAGINT, IMAGEINT), the size of a bigint, NTIMESTEP
LOOP_TIME = re.compile(r"^Loop time of ([0-9.eE+-]+) on ")    # a run command's wall time
RESTART_STRING_FLAGS, RESTART_INT_FLAGS, RESTART_BIGINT_SIZE, RESTART_NTIMESTEP = \
    (0, 4), (1, 2, 48), 3, 5


def checkpoint_step(path):
    """Time step of a complete LAMMPS restart file (its magic string at both ends), else None."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096)
            f.seek(0, os.SEEK_END)
            if f.tell() < 2 * len(RESTART_MAGIC):
                return None
            f.seek(-len(RESTART_MAGIC), os.SEEK_END)
            tail = f.read()
    except OSError:
        return None
    if not head.startswith(RESTART_MAGIC) or tail != RESTART_MAGIC:
        return None
    pos, bigint = len(RESTART_MAGIC) + 8, 8    # after the endian flag and format revision
    try:
        while True:
            (flag,) = struct.unpack_from("i", head, pos)
            pos += 4
            if flag in RESTART_STRING_FLAGS:
                (n,) = struct.unpack_from("i", head, pos)
                pos += 4 + n
            elif flag in RESTART_INT_FLAGS or flag == RESTART_BIGINT_SIZE:
                (value,) = struct.unpack_from("i", head, pos)
                pos += 4
                if flag == RESTART_BIGINT_SIZE:
                    bigint = value
            elif flag == RESTART_NTIMESTEP:
                return struct.unpack_from("q" if bigint == 8 else "i", head, pos)[0]
            else:
                return None
    except struct.error:
        return None


def newest_checkpoint(out):
    """(path, step) of the newer complete checkpoint in the run folder, or (None, None)."""
    found = [(checkpoint_step(os.path.join(out, name)), os.path.join(out, name))
             for name in CHECKPOINTS]
    found = [(step, path) for step, path in found if step is not None]
    if not found:
        return None, None
    step, path = max(found)
    return path, step


def resume_log(out, step):
    """the LAMMPS log name of a segment resumed from step: log.resume-STEP.lammps, numbered on
    (log.resume-STEP-2.lammps, ...) when an earlier segment resumed from the same checkpoint"""
    name, k = "log.resume-%d.lammps" % step, 1
    while os.path.exists(os.path.join(out, name)):
        k += 1
        name = "log.resume-%d-%d.lammps" % (step, k)
    return name


def segment_logs(out):
    """the LAMMPS logs of every segment of the run in out"""
    return [p for p in [os.path.join(out, "log.lammps")]
            + glob.glob(os.path.join(out, "log.resume-*.lammps")) if os.path.exists(p)]


def earlier_segments_seconds(out, current_log):
    """wall seconds of a resumed run's earlier segments: the loop times of the run commands in
    their LAMMPS logs (all but current_log); None when no earlier log is left. A run command a
    kill interrupted wrote no loop time; the completed ones after the last checkpoint count,
    since they were computed, and again after it."""
    earlier = [p for p in segment_logs(out) if os.path.basename(p) != current_log]
    if not earlier:
        return None
    seconds = 0.0
    for path in earlier:
        with open(path, errors="replace") as f:
            seconds += sum(float(m.group(1)) for m in map(LOOP_TIME.match, f) if m)
    return seconds
