#!/usr/bin/env python3
"""A distributed run that must stop with a given message (issue 25): what is
not distributed yet is refused, or stopped when the run reaches it, on every
rank, with a message that says what and why.

  expect_refusal.py MFSD MPIEXEC RANKS SCENE "TEXT" [--set k=v ...]
"""
import subprocess
import sys
import tempfile


def main():
    mfsd, mpiexec, ranks, scene, text = sys.argv[1:6]
    out = tempfile.mkdtemp(prefix="mfsd_refusal_")
    r = subprocess.run([mpiexec, "-n", ranks, "--oversubscribe", mfsd, "run", scene, "-q", "--threads", "1", "-o",
                        out + "/run"] + sys.argv[6:], capture_output=True, text=True, timeout=300)
    assert r.returncode != 0, "the run exited 0"
    assert text in r.stderr, "expected '%s' in:\n%s" % (text, r.stderr)
    line = next(l for l in r.stderr.splitlines() if text in l)
    print("exit %d: %s" % (r.returncode, line.strip()))


if __name__ == "__main__":
    main()
