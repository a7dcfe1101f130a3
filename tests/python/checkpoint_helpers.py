"""Kill a deposit (runner or workflow) with SIGKILL once it has written a checkpoint."""
import os
import signal
import subprocess
import time

import deposit_run


def kill_after_first_checkpoint(cmd, folder, env, cwd=None, timeout=300):
    """Start cmd in its own process group, SIGKILL the whole group as soon as the run folder
    holds a complete checkpoint; returns that checkpoint's step."""
    proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.time() + timeout
    try:
        while deposit_run.newest_checkpoint(folder)[0] is None:
            assert proc.poll() is None, "the run ended before its first checkpoint"
            assert time.time() < deadline, "no checkpoint within %d s" % timeout
            time.sleep(0.05)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    time.sleep(0.2)
    return deposit_run.newest_checkpoint(folder)[1]
