"""Helpers for validation scripts: run the mfsd binary with --set overrides,
read its CSV outputs, and measure oscillation periods."""
import csv
import json
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# $MFSD_BINARY, else build/mfsd (scripts/build.sh), else build-cpu/mfsd (a CPU-only build).
BINARY = os.environ.get("MFSD_BINARY") or next(
    (p for p in (os.path.join(ROOT, d, "mfsd") for d in ("build", "build-cpu")) if os.path.exists(p)),
    os.path.join(ROOT, "build", "mfsd"))
PYTHON_PACKAGES = {"numpy": "numpy", "matplotlib": "matplotlib"}


def ensure_python_packages():
    """Installs the plotting/analysis packages with pip when they are missing,
    so a fresh machine runs the studies without manual set-up."""
    import importlib.util
    missing = [pkg for mod, pkg in PYTHON_PACKAGES.items() if importlib.util.find_spec(mod) is None]
    if not missing:
        return
    print("[mfsd] installing Python packages: " + " ".join(missing), file=sys.stderr, flush=True)
    rc = subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", *missing]).returncode
    if rc != 0:
        sys.exit(f"[mfsd] pip could not install {' '.join(missing)}; run: "
                 f"{sys.executable} -m pip install {' '.join(missing)}")


ensure_python_packages()


def run(config, sets, outdir, extra=(), quiet=True):
    """Runs `mfsd run config --set k=v ... -o outdir`; returns the exit code."""
    cmd = [BINARY, "run", os.path.join(ROOT, config), "-o", outdir]
    for k, v in sets.items():
        cmd += ["--set", f"{k}={json.dumps(v) if isinstance(v, (dict, list)) else v}"]
    cmd += list(extra)
    if quiet:
        cmd.append("-q")
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd).returncode


def run_and_read(config, sets, outdir, threads=0, reuse=False, allow_failure=False):
    """Runs a scene (unless `reuse` and outdir already holds a finished run)
    and returns (probes.csv, energies.csv, timing.json) of it; timing gets
    the commit of the binary that made the run (from run.json). A failed run
    ends the study, unless allow_failure: then the rows written before the
    failure are returned and timing is {"failed_with_exit_code": rc}."""
    failed = os.path.join(outdir, "failed_with_exit_code")
    if not (reuse and (os.path.exists(os.path.join(outdir, "timing.json")) or os.path.exists(failed))):
        if os.path.exists(failed):
            os.remove(failed)
        rc = run(config, sets, outdir, ["--threads", str(threads)] if threads else [])
        if rc != 0 and not allow_failure:
            sys.exit(f"[mfsd] run {outdir} failed with exit code {rc}")
        if rc != 0:
            with open(failed, "w") as f:
                f.write(f"{rc}\n")
    if os.path.exists(failed):
        with open(failed) as f:
            rc = int(f.read())
        return (read_csv(os.path.join(outdir, "probes.csv")), read_csv(os.path.join(outdir, "energies.csv")),
                {"failed_with_exit_code": rc})
    timing = read_json(os.path.join(outdir, "timing.json"))
    timing["mfsd_commit_of_the_run"] = read_json(os.path.join(outdir, "run.json")).get("git_commit")
    return read_csv(os.path.join(outdir, "probes.csv")), read_csv(os.path.join(outdir, "energies.csv")), timing


def study_arguments(doc, res_help=None, out_help=None, extra=None):
    """The command line of a study script: --threads, --reuse and, with
    res_help, --res (a list of resolutions), with out_help, --out (the stem of
    the result files in docs/validation); extra(parser) adds the script's own."""
    import argparse
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    if extra:
        extra(ap)
    if res_help:
        ap.add_argument("--res", type=int, nargs="*", help=res_help)
    if out_help:
        ap.add_argument("--out", help=out_help)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--reuse", action="store_true", help="analyse finished runs again")
    return ap.parse_args()


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0].keys()} if rows else {}


def read_json(path):
    with open(path) as f:
        return json.load(f)


def crossings(t, y):
    """Times where y(t) crosses y(0), by linear interpolation; t(0) first."""
    y0 = y[0]
    out = [t[0]]
    for i in range(2, len(t)):
        a, b = y[i - 1] - y0, y[i] - y0
        if a != 0 and a * b <= 0:
            out.append(t[i - 1] + (t[i] - t[i - 1]) * a / (a - b))
    return out


def period(t, y):
    """Least-squares fit t_k = t_0 + k T/2 over all crossings of y(0)."""
    c = crossings(t, y)
    n = len(c)
    if n < 3:
        return float("nan")
    k = list(range(n))
    sk, st = sum(k), sum(c)
    skk = sum(i * i for i in k)
    skt = sum(i * ti for i, ti in zip(k, c))
    return 2 * (n * skt - sk * st) / (n * skk - sk * sk)


def plate_run(config, sets, outdir, threads=0, reuse=False):
    """One run of an oscillating plate (the TLSPH, ULSPH and RKPM plate
    studies): its tip's y history, the period fitted to it, the range of the
    kinetic + strain energy relative to its start, and timing.json."""
    probes, energies, timing = run_and_read(config, sets, outdir, threads, reuse)
    t, y = probes["time"], probes["tip.position.y"]
    e = [k + s for k, s in zip(energies["kinetic"], energies["strain"])]
    return {"t": t, "y": y, "period": period(t, y), "energy_range": [min(e) / e[0] - 1, max(e) / e[0] - 1],
            "timing": timing}


def first_period(t, y):
    """Time of the second crossing after the start (one full oscillation)."""
    c = crossings(t, y)
    return c[2] - c[0] if len(c) > 2 else float("nan")


def write_study(stem, result, fig):
    """Writes a study's result as stem.json and its figure as stem.png."""
    os.makedirs(os.path.dirname(stem), exist_ok=True)
    with open(stem + ".json", "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    fig.savefig(stem + ".png", dpi=110)
    print(f"wrote {os.path.relpath(stem, ROOT)}.json/.png")


def machine():
    """Where a study ran: CPU model, cores, load (stated in every result file)."""
    info = {"cpu": "unknown", "cores": os.cpu_count()}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
        info["load_average"] = list(os.getloadavg())
    except OSError:
        pass
    try:
        info["git_commit"] = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                                            capture_output=True, text=True).stdout.strip()
    except OSError:
        pass
    return info
