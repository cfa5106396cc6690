"""Shared pieces of the benchmark suites: running mfsd (with its peak memory),
medians over repeats, the machine description, and writing a suite's
results (JSON + markdown table + PNG plots) to bench/results/."""
import datetime
import json
import os
import statistics
import subprocess
import sys

BENCH = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(BENCH, "..", "scripts", "validation"))
import mfsd_runs as m  # noqa: E402  (installs numpy/matplotlib when missing)

ROOT = m.ROOT
BUILD = os.path.dirname(m.BINARY)
TRIAD = os.environ.get("MFSD_TRIAD", os.path.join(BUILD, "mfsd_triad"))
FMA_PEAK = os.path.join(BUILD, "mfsd_fma_peak")
OUT = os.path.join(ROOT, "out", "bench")
RESULTS = os.path.join(BENCH, "results")
BENDING = "configs/bending_column_3d.json"
PLATE = "configs/oscillating_plate_2d.json"
PLATE_ULSPH = "configs/oscillating_plate_ulsph_2d.json"
PLATE_RKPM = "configs/oscillating_plate_rkpm_2d.json"
TWISTING = "configs/twisting_column_3d.json"
QUIET_OUTPUT = {"output.vtu": "false", "output.interval": 1e9, "output.probe_interval": 1e9}


# Extra mfsd run options for every run of a suite (bench/run.py --mfsd-args,
# e.g. --pair-layout sliced), and the tag its results' file names then carry.
EXTRA_ARGS = []
RESULT_TAG = ""


def run(config, sets, outdir, threads=None, precision=None, backend="cpu", max_steps=None, warmup=0, extra=()):
    """One mfsd run; returns (timing.json, run.json, peak resident memory in bytes)."""
    cmd = [m.BINARY, "run", os.path.join(ROOT, config), "-o", outdir, "-q", "--backend", backend] + EXTRA_ARGS
    cmd += list(extra)
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    if threads and backend == "cpu":
        cmd += ["--threads", str(threads)]
    if precision:
        cmd += ["--precision", precision]
    if max_steps:
        cmd += ["--max-steps", str(max_steps)]
    if warmup:
        cmd += ["--warmup-steps", str(warmup)]
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    proc = subprocess.Popen(cmd)
    _, status, usage = os.wait4(proc.pid, 0)
    rc = os.waitstatus_to_exitcode(status)
    if rc != 0:
        raise SystemExit(f"mfsd exited with {rc}: {' '.join(cmd)}")
    timing = m.read_json(os.path.join(outdir, "timing.json"))
    info = m.read_json(os.path.join(outdir, "run.json"))
    return timing, info, usage.ru_maxrss * 1024  # ru_maxrss is in KiB on Linux


def median_run(repeats, *args, **kwargs):
    """Runs `repeats` times; returns the run with the median particle-steps/s
    and the list of all rates."""
    runs = [run(*args, **kwargs) for _ in range(repeats)]
    rates = [t["particle_steps_per_second"] for t, _, _ in runs]
    med = statistics.median(rates)
    best = min(runs, key=lambda r: abs(r[0]["particle_steps_per_second"] - med))
    return best, rates


def stage_table(timing):
    return {s["name"]: {"share": s["share"], "ns_per_particle_step": s["nanoseconds_per_particle_step"]}
            for s in timing["stages"]}


def machine(backend="cpu"):
    info = m.machine()
    info["date"] = datetime.date.today().isoformat()
    info["backend"] = backend
    try:
        info["mfsd_version"] = subprocess.run([m.BINARY, "--version"], capture_output=True,
                                              text=True).stdout.strip().splitlines()
    except OSError:
        pass
    try:
        with open("/proc/meminfo") as f:
            info["memory_kib"] = int(f.readline().split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return info


def triad(threads, repeats=20):
    """STREAM-like triad bandwidth on `threads` threads (bench/triad.cpp)."""
    out = subprocess.run([TRIAD, "--threads", str(threads), "--repeats", str(repeats)], capture_output=True,
                         text=True, check=True).stdout
    return json.loads(out)


def fma_peak():
    """Compute roof of one core (bench/fma_peak.cpp): 4-wide FMA rate and clock; None where not built (non-x86, or MFSD_NATIVE=OFF)."""
    if not os.path.exists(FMA_PEAK):
        return None
    return json.loads(subprocess.run([FMA_PEAK], capture_output=True, text=True, check=True).stdout)


def result_stem(suite):
    os.makedirs(RESULTS, exist_ok=True)
    tag = f"-{RESULT_TAG}" if RESULT_TAG else ""
    return os.path.join(RESULTS, f"{suite}-{datetime.date.today().isoformat()}{tag}")


def write_results(suite, payload, markdown, command):
    """bench/results/<suite>-<date>.json and .md; the machine heads both."""
    stem = result_stem(suite)
    payload = {"suite": suite, "command": command, **payload}
    with open(stem + ".json", "w") as f:
        json.dump(payload, f, indent=1)
        f.write("\n")
    mach = payload["machine"]
    head = (f"# Benchmark `{suite}`, {mach['date']}\n\n"
            f"Command: `{command}`  \n"
            f"Machine: {mach.get('cpu')}, {mach.get('cores')} cores, load average before the suite "
            f"{', '.join(f'{x:.2f}' for x in mach.get('load_average', []))}, backend {mach['backend']}, "
            f"mfsd commit {mach.get('git_commit')}\n\n")
    with open(stem + ".md", "w") as f:
        f.write(head + markdown)
    print(f"[bench] wrote {os.path.relpath(stem, ROOT)}.json/.md", file=sys.stderr)
    return stem


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    return pyplot


def mega(x):
    return x / 1e6
