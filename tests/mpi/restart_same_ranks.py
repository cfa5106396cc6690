#!/usr/bin/env python3
"""A distributed run continued from its per-rank checkpoints (issue 25).

On RANKS ranks: SCENE run to its end; the same run stopped after STOP steps
(each rank writes its checkpoint: rank 0's in checkpoint/, rank r's in
checkpoint.rank<r>/), then continued with --restart. Every CSV, the PVD and
every snapshot piece and index of the continued run must equal the
uninterrupted run's byte for byte. A restart on another rank count must be
refused with a message that says so.

  restart_same_ranks.py MFSD MPIEXEC RANKS SCENE STOP [--set k=v ...]
"""
import filecmp
import os
import subprocess
import sys
import tempfile


def main():
    mfsd, mpiexec, ranks, scene, stop = sys.argv[1:6]
    extra = sys.argv[6:]
    work = tempfile.mkdtemp(prefix="mfsd_restart_")
    whole, cut = os.path.join(work, "whole"), os.path.join(work, "cut")
    run = lambda n, args: subprocess.run([mpiexec, "-n", str(n), "--oversubscribe", mfsd, "run", scene, "-q",
                                          "--threads", "1"] + args + extra, capture_output=True, text=True,
                                         timeout=300)
    for args in (["-o", whole], ["-o", cut, "--max-steps", stop]):
        r = run(ranks, args)
        assert r.returncode == 0, "%s: exit %d\n%s" % (args, r.returncode, r.stderr)
    other = run(int(ranks) + 1, ["--restart", cut])  # refused before anything is touched
    assert other.returncode != 0 and "continue it on as many" in other.stderr, other.stderr
    r = run(ranks, ["--restart", cut])
    assert r.returncode == 0, "restart: exit %d\n%s" % (r.returncode, r.stderr)
    assert os.path.isdir(os.path.join(cut, "checkpoint")), "no checkpoint of rank 0"
    for k in range(1, int(ranks)):
        assert os.path.isdir(os.path.join(cut, "checkpoint.rank%d" % k)), "no checkpoint of rank %d" % k
    files = [f for f in os.listdir(whole) if f.endswith((".csv", ".pvd"))]
    files += [os.path.join("snapshots", f) for f in os.listdir(os.path.join(whole, "snapshots"))]
    differ = [f for f in files if not filecmp.cmp(os.path.join(whole, f), os.path.join(cut, f), shallow=False)]
    assert not differ, "the continued run differs in " + ", ".join(sorted(differ))
    print("%s ranks: stopped at step %s, continued: %d files identical to the uninterrupted run's" %
          (ranks, stop, len(files)))


if __name__ == "__main__":
    main()
