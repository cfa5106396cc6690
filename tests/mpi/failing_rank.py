#!/usr/bin/env python3
"""A rank that fails ends every rank with its message (issue 25).

Runs SCENE (with the --set options given) alone and on RANKS ranks; the
single-process run must stop with a numerical failure (exit 3). The
distributed run must end, exit non-zero, and print the failing rank's message
naming the same step, particle (by its id in the whole scene) and cause.

  failing_rank.py MFSD MPIEXEC RANKS SCENE [--set k=v ...]
"""
import re
import subprocess
import sys
import tempfile


def main():
    mfsd, mpiexec, ranks, scene = sys.argv[1:5]
    extra = sys.argv[5:]
    work = tempfile.mkdtemp(prefix="mfsd_fail_")
    one = subprocess.run([mfsd, "run", scene, "-q", "--threads", "1", "-o", work + "/serial"] + extra,
                         capture_output=True, text=True, timeout=120)
    assert one.returncode == 3, "the single-process run should fail (exit 3), got %d: %s" % (one.returncode, one.stderr)
    expected = re.search(r"run stopped: (.*)", one.stderr).group(1).strip()
    many = subprocess.run([mpiexec, "-n", ranks, "--oversubscribe", mfsd, "run", scene, "-q", "--threads", "1", "-o",
                           work + "/ranks"] + extra, capture_output=True, text=True, timeout=120)
    assert many.returncode != 0, "the distributed run exited 0"
    found = re.search(r"mfsd: rank (\d+) of %s: run stopped: (.*)" % ranks, many.stderr)
    assert found, "no rank's message in:\n" + many.stderr
    assert found.group(2).strip() == expected, "rank %s said '%s', the single run '%s'" % (
        found.group(1), found.group(2).strip(), expected)
    print("rank %s of %s ended the run (exit %d): %s" % (found.group(1), ranks, many.returncode, expected))


if __name__ == "__main__":
    main()
