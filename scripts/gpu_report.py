#!/usr/bin/env python3
"""The report of scripts/gpu_check.sh: one report.md and a report.json with the
same data, from the files the check leaves in its output folder (standard
library only, so it runs on a bare GPU machine and in CI).

  python3 scripts/gpu_report.py write DIR [--dry-run] [--budget 480]
  python3 scripts/gpu_report.py list-cases [--full]

`write` reads, in DIR (every file optional; what is missing reads "n/a"):
  meta.env              key=value lines written by gpu_check.sh (date, host,
                        cores, command, binaries, gpu=yes|no, gpu_reason)
  nvidia_smi_query.csv  nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm
  nvidia_smi.txt        plain nvidia-smi (its header names the driver's CUDA version)
  mfsd_version.txt      mfsd --version;  nvcc_version.txt  nvcc --version (this machine)
  build_info.txt        how the binaries were built (gpu_pack.sh; or the CMake cache)
  tests_planned.txt     mfsd_gpu_tests --gtest_list_tests
  gpu_tests.xml         --gtest_output=xml (results; properties worst_difference_*,
                        value "<quantity>=<value> tolerance=<value>")
  gpu_tests.log         the test binary's output (results when the XML is missing)
  throughput_planned.tsv  `list-cases` output;  throughput.json  bench/run.py throughput
  throughput_timing/<scene>_<H/dp>_<precision>_<threads>.json   the runs' timing.json
                        (round_trips_per_step, when the run's row does not carry it)
  phases.tsv            name, seconds, exit status, in-budget (1/0), note
  divergence.txt        scripts/gpu_divergence.py output (after failing tests)
and writes DIR/report.md and DIR/report.json. Exit status: 0 pass (or a dry
run), 1 fail, 2 no usable GPU.

`list-cases` prints the throughput suite's cases (tab-separated: case, scene,
H/dp, precision) from bench/suites/throughput.py without importing it (which
would need numpy and matplotlib)."""
import argparse
import ast
import datetime
import json
import os
import re
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
BUDGET = 480
NA = "n/a"


# ---------------------------------------------------------------- throughput cases

def _literal_assignments(path, names, namespace):
    """Evaluates the module-level assignments `names` of a Python file in
    `namespace` (literals, attribute references to namespace objects,
    comprehensions), without importing the module."""
    tree = ast.parse(open(path).read(), path)
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name) \
                and node.targets[0].id in names:
            code = compile(ast.Expression(node.value), path, "eval")
            namespace[node.targets[0].id] = eval(code, {"__builtins__": {}}, namespace)  # noqa: S307 (our file)
    return namespace, tree


def throughput_cases(full=False):
    """[(case, scene, H/dp, precision)] of the throughput suite (quick unless full)."""
    bench = os.path.join(ROOT, "bench")
    consts, _ = _literal_assignments(os.path.join(bench, "bench_lib.py"),
                                     {"BENDING", "PLATE", "PLATE_ULSPH", "PLATE_RKPM", "TWISTING"}, {})

    class B:  # stands for `import bench_lib as b`
        pass
    for k, v in consts.items():
        setattr(B, k, v)
    ns, tree = _literal_assignments(os.path.join(bench, "suites", "throughput.py"), {"CASES", "QUICK"}, {"b": B})
    precisions = ("double", "float")
    for node in ast.walk(tree):
        if isinstance(node, ast.For) and isinstance(node.target, ast.Name) and node.target.id == "precision":
            try:
                precisions = tuple(ast.literal_eval(node.iter))
            except ValueError:
                pass
    cases = ns["CASES"] if full else ns["QUICK"]
    return [(label, scene, res, p) for label, scene, res in cases for p in precisions]


# ---------------------------------------------------------------- readers

def _read(path):
    try:
        with open(path, errors="replace") as f:
            return f.read()
    except OSError:
        return None


def _read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def read_meta(d):
    meta = {}
    for line in (_read(os.path.join(d, "meta.env")) or "").splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            meta[k.strip()] = v.strip()
    return meta


def read_device(d):
    """Device name, memory, driver, max SM clock, the driver's CUDA version,
    nvcc here, the binaries' build and the binary's own view of the devices."""
    dev = {"name": NA, "memory": NA, "driver_version": NA, "max_sm_clock": NA, "driver_cuda_version": NA,
           "nvcc_version": NA, "build": NA, "mfsd_version": [], "mfsd_cuda_devices": NA}
    query = (_read(os.path.join(d, "nvidia_smi_query.csv")) or "").strip().splitlines()
    if query:
        fields = [f.strip() for f in query[0].split(",")]
        for key, value in zip(("name", "memory", "driver_version", "max_sm_clock"), fields):
            dev[key] = value
        if len(query) > 1:
            dev["other_devices"] = len(query) - 1
    smi = _read(os.path.join(d, "nvidia_smi.txt")) or ""
    m = re.search(r"CUDA Version:\s*([0-9.]+)", smi)
    if m:
        dev["driver_cuda_version"] = m.group(1)
    nvcc = _read(os.path.join(d, "nvcc_version.txt")) or ""
    m = re.search(r"release ([0-9.]+), (V[0-9.]+)", nvcc)
    if m:
        dev["nvcc_version"] = f"{m.group(1)} ({m.group(2)})"
    build = [ln.strip() for ln in (_read(os.path.join(d, "build_info.txt")) or "").splitlines() if ln.strip()]
    if build:
        dev["build"] = "; ".join(build)
    version = [ln.strip() for ln in (_read(os.path.join(d, "mfsd_version.txt")) or "").splitlines() if ln.strip()]
    dev["mfsd_version"] = version
    for ln in version:
        if ln.startswith("cuda devices:"):
            dev["mfsd_cuda_devices"] = ln.split(":", 1)[1].strip()
    return dev


def planned_tests(d):
    """Full names from --gtest_list_tests ("Suite." lines, then indented names)."""
    names, suite = [], ""
    for line in (_read(os.path.join(d, "tests_planned.txt")) or "").splitlines():
        if not line.strip() or line.startswith("Running main()") or line.startswith("Note:"):
            continue
        text = line.split("#")[0].rstrip()
        if not line.startswith(" "):
            suite = text.strip()
        elif suite:
            names.append(suite + text.strip())
    return names


_DIFF = re.compile(r"^\s*(?P<quantity>[^=\s]+)\s*=\s*(?P<value>\S+)\s+tolerance\s*=\s*(?P<tolerance>\S+)")


def parse_difference(name, value):
    """A worst_difference_* property: {quantity, value, tolerance, ratio} (the
    unparsed text when it does not follow "<quantity>=<value> tolerance=<value>")."""
    m = _DIFF.match(value)
    out = {"property": name, "text": value}
    if m:
        out["quantity"] = m.group("quantity")
        for k in ("value", "tolerance"):
            try:
                out[k] = float(m.group(k))
            except ValueError:
                out[k] = m.group(k)
        if isinstance(out["value"], float) and isinstance(out["tolerance"], float) and out["tolerance"] > 0:
            out["ratio"] = out["value"] / out["tolerance"]
    else:
        out["quantity"] = name[len("worst_difference_"):]
    return out


def test_results(d):
    """{full name: {result, seconds, failure, differences}} from the XML, else the log."""
    results = {}
    xml = os.path.join(d, "gpu_tests.xml")
    try:
        tree = ET.parse(xml)
    except (OSError, ET.ParseError):
        tree = None
    if tree is not None:
        for case in tree.iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            failure = case.find("failure")
            if failure is None:
                failure = case.find("error")
            if case.get("status") == "notrun":
                result = "not run"
            elif failure is not None:
                result = "FAIL"
            elif case.get("result") == "skipped" or case.find("skipped") is not None:
                result = "SKIPPED"
            else:
                result = "pass"
            props = {}
            for p in case.iter("property"):
                props[p.get("name", "")] = p.get("value", "")
            for k, v in case.attrib.items():  # older Google Tests: properties as attributes
                if k.startswith("worst_difference_"):
                    props.setdefault(k, v)
            diffs = [parse_difference(k, v) for k, v in sorted(props.items()) if k.startswith("worst_difference_")]
            message = None
            if failure is not None:
                message = (failure.get("message") or failure.text or "").strip()
            try:
                seconds = float(case.get("time", "nan"))
            except ValueError:
                seconds = None
            results[name] = {"result": result, "seconds": seconds, "failure": message, "differences": diffs,
                             "properties": props}
        return results, "xml"
    log = _read(os.path.join(d, "gpu_tests.log"))
    if log is None:
        return results, None
    for m in re.finditer(r"^\[\s*(OK|FAILED|SKIPPED)\s*\] (\S+\.\S+) \((\d+) ms\)", log, re.M):
        result = {"OK": "pass", "FAILED": "FAIL", "SKIPPED": "SKIPPED"}[m.group(1)]
        results[m.group(2)] = {"result": result, "seconds": int(m.group(3)) / 1e3, "failure": None,
                               "differences": [], "properties": {}}
    return results, "log"


def worst(diffs):
    """The difference closest to (or furthest past) its tolerance."""
    rated = [x for x in diffs if "ratio" in x]
    if rated:
        return max(rated, key=lambda x: x["ratio"])
    return diffs[0] if diffs else None


def format_difference(x):
    if x is None:
        return NA
    if "ratio" not in x:
        return x["text"]
    return f"{x['quantity']} {x['value']:.3g} (tolerance {x['tolerance']:.3g}, {x['ratio']:.3g}x)"


def read_phases(d):
    phases = []
    for line in (_read(os.path.join(d, "phases.tsv")) or "").splitlines():
        parts = line.rstrip("\n").split("\t")
        if len(parts) < 4:
            continue
        try:
            seconds = float(parts[1])
        except ValueError:
            seconds = None
        try:
            status = int(parts[2])
        except ValueError:
            status = None
        phases.append({"phase": parts[0], "seconds": seconds, "status": status, "in_budget": parts[3] == "1",
                       "note": parts[4] if len(parts) > 4 else ""})
    return phases


def planned_cases(d):
    cases = []
    for line in (_read(os.path.join(d, "throughput_planned.tsv")) or "").splitlines():
        parts = line.split("\t")
        if len(parts) == 4:
            cases.append({"case": parts[0], "scene": parts[1], "H_over_dp": _number(parts[2]),
                          "precision": parts[3]})
    return cases


def _number(text):
    try:
        f = float(text)
        return int(f) if f.is_integer() else f
    except ValueError:
        return text


def run_name(scene, res, precision, threads):
    """The run folder bench/suites/throughput.py gives a case (out/bench/throughput/<this>)."""
    return f"{os.path.basename(scene)[:-5]}_{res}_{precision}_{threads}"


def throughput_rows(d):
    data = _read_json(os.path.join(d, "throughput.json"))
    if not data:
        return None, []
    rows = []
    for r in data.get("rows", []):
        timing = _read_json(os.path.join(d, "throughput_timing",
                                         run_name(r.get("scene", "x.json"), r.get("H_over_dp"), r.get("precision"),
                                                  r.get("threads", 0)) + ".json")) or {}
        trips = r.get("round_trips_per_step", timing.get("round_trips_per_step"))
        particles = r.get("particles")
        stages = {}
        for name, s in (r.get("stages") or {}).items():
            ns = s.get("ns_per_particle_step")
            stages[name] = {"share": s.get("share"), "ns_per_particle_step": ns,
                            "microseconds_per_step": ns * particles / 1e3 if ns is not None and particles else None}
        rows.append({"case": r.get("case"), "scene": r.get("scene"), "H_over_dp": r.get("H_over_dp"),
                     "precision": r.get("precision"), "threads": r.get("threads"), "particles": particles,
                     "particle_steps_per_second": r.get("particle_steps_per_second"),
                     "microseconds_per_step": r.get("microseconds_per_step"), "round_trips_per_step": trips,
                     "stages": stages})
    return data, rows


# ---------------------------------------------------------------- the report

def _fmt(x, spec, scale=1.0):
    return NA if x is None else format(x * scale, spec)


def build(d, dry_run=False, budget=BUDGET):
    meta = read_meta(d)
    device = read_device(d)
    planned = planned_tests(d)
    results, source = test_results(d)
    tests = []
    for name in planned + [n for n in results if n not in planned]:
        r = results.get(name)
        if r is None:
            r = {"result": "not run" if dry_run or source is None else "no result", "seconds": None,
                 "failure": None, "differences": [], "properties": {}}
        tests.append({"name": name, **r, "worst_difference": worst(r["differences"])})
    bench, rows = throughput_rows(d)
    cases = planned_cases(d)
    phases = read_phases(d)
    in_budget = sum(p["seconds"] or 0 for p in phases if p["in_budget"])
    divergence = _read(os.path.join(d, "divergence.txt"))

    gpu = meta.get("gpu", "no" if dry_run else NA)
    reasons = []
    if dry_run:
        verdict = "DRY RUN"
        reasons.append(f"CPU half only: {len(planned)} cross-backend tests and {len(cases)} throughput runs "
                       f"would run; GPU here: {gpu} ({meta.get('gpu_reason', NA)})")
    elif gpu == "no":
        verdict = "NO GPU"
        reasons.append(meta.get("gpu_reason", "no usable CUDA device"))
    else:
        bad = [t["name"] for t in tests if t["result"] != "pass"]
        if not tests:
            reasons.append("no cross-backend test ran")
        if bad:
            reasons.append(f"{len(bad)} of {len(tests)} cross-backend tests did not pass: {', '.join(bad)}")
        for p in phases:
            if p["phase"] in ("tests", "throughput", "full_suite") and p["status"] not in (0, None):
                reasons.append(f"phase {p['phase']} exited {p['status']}")
        if bench is None:
            reasons.append("no throughput results")
        verdict = "FAIL" if reasons else "PASS"
    report = {
        "verdict": verdict, "reasons": reasons,
        "date": meta.get("date", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")),
        "host": meta.get("host", NA), "cores": meta.get("cores", NA), "command": meta.get("command", NA),
        "binaries": meta.get("binaries", NA), "gpu": gpu, "gpu_reason": meta.get("gpu_reason", NA),
        "device": device,
        "budget_seconds": budget, "in_budget_seconds": round(in_budget, 1), "over_budget": in_budget > budget,
        "phases": phases,
        "tests_source": source, "tests": tests,
        "tests_passed": sum(t["result"] == "pass" for t in tests),
        "throughput_command": (bench or {}).get("command"), "throughput": rows,
        "throughput_planned": cases,
        "divergence": divergence,
    }
    return report


def markdown(rep):
    dev = rep["device"]
    out = [f"# GPU check, {rep['date']}", "",
           f"**{rep['verdict']}**" + (": " + "; ".join(rep["reasons"]) if rep["reasons"] else ""), "",
           f"Command: `{rep['command']}`  ", f"Binaries: {rep['binaries']}", "",
           "## Machine", "",
           "| | |", "|---|---|",
           f"| host | {rep['host']}, {rep['cores']} cores |",
           f"| device | {dev['name']}" + (f" (+{dev['other_devices']} more)" if dev.get("other_devices") else "") + " |",
           f"| memory | {dev['memory']} |",
           f"| driver | {dev['driver_version']} (CUDA {dev['driver_cuda_version']}) |",
           f"| max SM clock | {dev['max_sm_clock']} |",
           f"| nvcc on this machine | {dev['nvcc_version']} |",
           f"| binaries built with | {dev['build']} |",
           f"| mfsd | {' / '.join(dev['mfsd_version']) or NA} |",
           f"| usable GPU | {rep['gpu']} ({rep['gpu_reason']}) |", ""]

    out += [f"## Phases (budget {rep['budget_seconds']} s)", "",
            "| phase | wall [s] | exit | in budget | note |", "|---|---|---|---|---|"]
    for p in rep["phases"]:
        out.append(f"| {p['phase']} | {_fmt(p['seconds'], '.1f')} | {NA if p['status'] is None else p['status']} | "
                   f"{'yes' if p['in_budget'] else 'no'} | {p['note']} |")
    flag = "**OVER BUDGET** (warning)" if rep["over_budget"] else "within budget"
    out += ["", f"Phases in the budget: {rep['in_budget_seconds']:.1f} s of {rep['budget_seconds']} s, {flag}.", ""]

    n = len(rep["tests"])
    count = f"{n} planned" if rep["verdict"] in ("DRY RUN", "NO GPU") else f"{rep['tests_passed']} of {n} pass"
    out += [f"## Cross-backend tests ({count}; MFSD_REQUIRE_GPU=1)", "",
            "| test | result | time [s] | worst difference |", "|---|---|---|---|"]
    for t in rep["tests"]:
        out.append(f"| {t['name']} | {t['result']} | {_fmt(t['seconds'], '.2f')} | "
                   f"{format_difference(t['worst_difference'])} |")
    failures = [t for t in rep["tests"] if t.get("failure")]
    if failures:
        out += ["", "First failure of each failing test:", ""]
        for t in failures:
            first = " ".join(t["failure"].splitlines()[:4])
            out.append(f"- {t['name']}: {first[:400]}")
    multi = [t for t in rep["tests"] if len(t["differences"]) > 1]
    if multi:
        out += ["", "All recorded differences:", ""]
        for t in multi:
            out.append(f"- {t['name']}: " + "; ".join(format_difference(x) for x in t["differences"]))
    out.append("")

    out += ["## Throughput (cuda)", ""]
    if rep["throughput_command"]:
        out += [f"Suite command: `{rep['throughput_command']}`", ""]
    rows = rep["throughput"]
    if rows:
        out += ["| case | H/dp | particles | precision | M particle-steps/s | ms/step | round trips/step |",
                "|---|---|---|---|---|---|---|"]
        for r in rows:
            trips = r["round_trips_per_step"]
            out.append(f"| {r['case']} | {r['H_over_dp']} | {r['particles']} | {r['precision']} | "
                       f"{_fmt(r['particle_steps_per_second'], '.2f', 1e-6)} | "
                       f"{_fmt(r['microseconds_per_step'], '.3f', 1e-3)} | "
                       f"{NA if trips is None else format(trips, '.3g')} |")
        names = []
        for r in rows:
            names += [s for s in r["stages"] if s not in names]
        out += ["", "Time per stage, microseconds per step (share of the step):", "",
                "| case | H/dp | precision | " + " | ".join(names) + " |", "|---|---|---|" + "---|" * len(names)]
        for r in rows:
            cells = []
            for s in names:
                st = r["stages"].get(s)
                if not st:
                    cells.append(NA)
                else:
                    cells.append(f"{_fmt(st['microseconds_per_step'], '.1f')} "
                                 f"({_fmt(st['share'], '.0f', 100)} %)")
            out.append(f"| {r['case']} | {r['H_over_dp']} | {r['precision']} | " + " | ".join(cells) + " |")
    elif rep["throughput_planned"]:
        out += ["Not run; the cases:", "", "| case | scene | H/dp | precision |", "|---|---|---|---|"]
        for c in rep["throughput_planned"]:
            out.append(f"| {c['case']} | {c['scene']} | {c['H_over_dp']} | {c['precision']} |")
    else:
        out.append(NA)
    out.append("")
    if rep["divergence"]:
        lines = rep["divergence"].splitlines()
        out += ["## Where the backends part (scripts/gpu_divergence.py)", "", "```"] + lines[:80]
        if len(lines) > 80:
            out.append(f"... ({len(lines) - 80} more lines in divergence.txt)")
        out += ["```", ""]
    return "\n".join(out) + "\n"


def write(d, dry_run=False, budget=BUDGET):
    rep = build(d, dry_run, budget)
    with open(os.path.join(d, "report.json"), "w") as f:
        json.dump(rep, f, indent=1)
        f.write("\n")
    with open(os.path.join(d, "report.md"), "w") as f:
        f.write(markdown(rep))
    return rep


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    w = sub.add_parser("write", help="write DIR/report.md and DIR/report.json")
    w.add_argument("dir")
    w.add_argument("--dry-run", action="store_true")
    w.add_argument("--budget", type=float, default=BUDGET, help="seconds (default 480)")
    c = sub.add_parser("list-cases", help="the throughput suite's cases, tab-separated")
    c.add_argument("--full", action="store_true", help="all sizes (default: --quick's)")
    args = ap.parse_args(argv)
    if args.command == "list-cases":
        for case in throughput_cases(args.full):
            print("\t".join(str(x) for x in case))
        return 0
    budget = int(args.budget) if float(args.budget).is_integer() else args.budget
    rep = write(args.dir, args.dry_run, budget)
    print(f"[gpu_report] {rep['verdict']}" + (": " + "; ".join(rep["reasons"]) if rep["reasons"] else "")
          + f" ({os.path.join(args.dir, 'report.md')})", file=sys.stderr)
    return {"PASS": 0, "DRY RUN": 0, "NO GPU": 2}.get(rep["verdict"], 1)


if __name__ == "__main__":
    sys.exit(main())
