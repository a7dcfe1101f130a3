"""in.deposit's Cundall damping across a checkpoint and at maxchunks.

A restart file holds no script variables, so in.deposit keeps the damping's switch steps in
${out}/cundall.steps and a resumed run takes the phase from its checkpoint's step:
- resumed after the switch-off, the damping stays off (it is not switched on again at the
  next landed chunk), and the deposit comes to rest on undamped samples;
- resumed while it was on, the damping is on from the first resumed step and is switched off
  when the criterion holds, as in the uninterrupted run;
- a run whose maxchunks run out while the damping is on switches it off, says so and ends
  (not at rest) instead of running on.
The deposit is small (60 ellipsoids, chunks of 500 steps, a checkpoint after every chunk).
"""
import re
import shutil

import pytest

import ed_helpers_pour as h
from deposit_checkpoint import checkpoint_step

CHUNK = 500
VARS = {"N": "60", "cundall": "0.7", "chunk": str(CHUNK), "image": "0", "window": "0",
        "width": "5", "checkpoint": str(CHUNK)}


def messages(out):
    """{event: step} of the deposit's damping and rest messages in out/log.lammps"""
    log = (out / "log.lammps").read_text()
    patterns = {"landed": r"^ELLIPSOID_DEP: landed after (\d+) steps; Cundall damping",
                "resumed on": r"^ELLIPSOID_DEP: resumed with Cundall damping \S+ on \(since step (\d+)\)",
                "off": r"^ELLIPSOID_DEP: settled under Cundall damping after (\d+) steps",
                "rest": r"^ELLIPSOID_DEP: at rest after (\d+) steps",
                "ran out": r"^WARNING: ELLIPSOID_DEP maxchunks ran out with Cundall damping on()",
                "not at rest": r"^WARNING: ELLIPSOID_DEP deposit NOT at rest after (\d+) steps"}
    found = {}
    for event, pattern in patterns.items():
        hits = re.findall(pattern, log, re.M)
        assert len(hits) <= 1, (event, hits)
        if hits:
            found[event] = int(hits[0]) if hits[0] else True
    return found


def deposit(out, **extra):
    """in.deposit run in the folder out (created if new), resumed with resume=CHECKPOINT"""
    out.mkdir(exist_ok=True)
    lmp = h.deposit_lammps(out, dict(VARS, out=str(out), **extra))
    lmp.close()
    return messages(out)


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    out = tmp_path_factory.mktemp("cundall") / "whole"
    events = deposit(out)
    assert {"landed", "off", "rest"} <= set(events), events
    assert events["landed"] + CHUNK < events["off"], "no checkpoint between on and off"
    return out, events


def test_switch_steps_are_recorded(uninterrupted):
    out, events = uninterrupted
    recorded = dict(re.findall(r"^variable cundall_(on|off)_at index (\d+)$",
                               (out / "cundall.steps").read_text(), re.M))
    assert recorded == {"on": str(events["landed"]), "off": str(events["off"])}


def cut_short(uninterrupted_events, folder, stop):
    """the deposit run again until maxchunks stops it at step stop: its messages and the
    checkpoint written at that step"""
    cut = deposit(folder, maxchunks=str(stop // CHUNK))
    assert cut["landed"] == uninterrupted_events["landed"] and cut["not at rest"] == stop, cut
    checkpoint = next(p for p in folder.glob("checkpoint.?") if checkpoint_step(str(p)) == stop)
    (folder / "log.lammps").unlink()
    return cut, str(checkpoint)


def test_resumed_after_the_switch_off_stays_undamped(uninterrupted, tmp_path):
    _, events = uninterrupted
    # one chunk after the switch-off: the bed still moves (the uninterrupted run needed more
    # chunks to rest), and a run that forgot the switch would find it landed and damp it again
    stop = events["off"] + CHUNK
    assert events["rest"] > stop + CHUNK
    cut, checkpoint = cut_short(events, tmp_path / "cut", stop)
    assert cut["off"] == events["off"] and "ran out" not in cut, cut
    resumed = deposit(tmp_path / "cut", resume=checkpoint)
    assert "landed" not in resumed and "resumed on" not in resumed and "off" not in resumed, resumed
    assert resumed["rest"] >= events["off"] + 2 * CHUNK, resumed


def test_resumed_while_damped_stays_damped(uninterrupted, tmp_path):
    _, events = uninterrupted
    stop = events["landed"] + CHUNK
    cut, checkpoint = cut_short(events, tmp_path / "cut", stop)
    assert cut["ran out"] and "off" not in cut, cut
    resumed = deposit(tmp_path / "cut", resume=checkpoint)
    assert resumed.get("resumed on") == events["landed"] and "landed" not in resumed, resumed
    assert resumed["off"] > stop and resumed["rest"] >= resumed["off"] + 2 * CHUNK, resumed
