#!/usr/bin/env python3
"""Seeded mutation fuzzer of mfsd's scene input (issue 19).

Mutates the shipped scenes (configs/*.json, tests/regression/scenes/*.json)
and the expression language, then runs `mfsd check SCENE` and, when that
succeeds, `mfsd run SCENE --max-steps 2 -q -o OUT --threads 1`. Every case
must end with exit code 0, 2 or 3 (no signal, no timeout, never 1 "internal
error"); every exit-2 message must name where the problem is (a JSON path, the
file with line:column, or the --set option); an exit-2 run must leave no
output folder.

    scripts/fuzz.py --binary build/mfsd --count 500 --time-limit 150 --seed 1
    scripts/fuzz.py --seed 1 --only 17 --keep /tmp/repro     # one case, kept

The case list depends only on --seed (case k is the same whatever --count,
--jobs or --time-limit are). Exit status: 0 when every case passed, 1 on any
failure, 2 on a usage problem. Standard library only.
"""

import argparse
import concurrent.futures
import copy
import json
import os
import random
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Scenes whose unmutated 2-step run takes over a second on one thread (millions
# of particles or heavy set-up): left out so that every case stays quick.
HEAVY = {"cantilever_plate_3d.json", "four_point_bending_3d.json", "twisting_column_seed001_3d.json"}

# Numbers a mutation puts in place of a number. Each is either harmless or so
# far out of range that a correct mfsd refuses it at once (no legitimately big
# and slow scene).
EXTREME_NUMBERS = [0, -1, 1e308, -1e308, 5e-324, 1e-300, 1e300, 10**30, -(10**30), 2**63, 2**64, -(2**63) - 1,
                   1.7976931348623157e308, -0.0]


class Raw:
    """JSON text written as is (literals Python's json cannot produce)."""

    def __init__(self, text):
        self.text = text


class Dup:
    """An object written with a key repeated: pairs [(key, value), ...]."""

    def __init__(self, pairs):
        self.pairs = pairs


class Deep:
    """`inner` wrapped `depth` times in `open`...`close` (written iteratively)."""

    def __init__(self, open_text, close_text, depth, inner):
        self.open_text, self.close_text, self.depth, self.inner = open_text, close_text, depth, inner


def dump(value, out):
    """Writes value as JSON text into the list `out` (Raw, Dup and Deep included)."""
    if isinstance(value, Raw):
        out.append(value.text)
    elif isinstance(value, Deep):
        out.append(value.open_text * value.depth)
        dump(value.inner, out)
        out.append(value.close_text * value.depth)
    elif isinstance(value, Dup):
        out.append("{")
        for k, (key, v) in enumerate(value.pairs):
            out.append((", " if k else "") + json.dumps(key) + ": ")
            dump(v, out)
        out.append("}")
    elif isinstance(value, dict):
        out.append("{")
        for k, (key, v) in enumerate(value.items()):
            out.append((", " if k else "") + json.dumps(key) + ": ")
            dump(v, out)
        out.append("}")
    elif isinstance(value, list):
        out.append("[")
        for k, v in enumerate(value):
            if k:
                out.append(", ")
            dump(v, out)
        out.append("]")
    elif isinstance(value, float) and value != value:
        out.append("NaN")
    elif isinstance(value, float) and value in (float("inf"), float("-inf")):
        out.append("Infinity" if value > 0 else "-Infinity")
    else:
        out.append(json.dumps(value))


def to_text(doc):
    out = []
    dump(doc, out)
    return "".join(out)


# ---------------------------------------------------------------- locations


def locations(doc):
    """(container, key, path) of every value under the root, depth first."""
    found = []
    stack = [(doc, "")]
    while stack:
        node, path = stack.pop()
        items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else []
        for key, value in items:
            p = path + "/" + str(key)
            found.append((node, key, p))
            if isinstance(value, (dict, list)):
                stack.append((value, p))
    found.sort(key=lambda f: f[2])  # independent of dict iteration details
    return found


def pick(rng, doc, want=None):
    locs = [loc for loc in locations(doc) if want is None or want(loc[0][loc[1]], loc)]
    return rng.choice(locs) if locs else None


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


# Keys whose strings are expressions (besides numbers given as strings).
EXPRESSION_KEYS = {"x", "y", "z", "where", "value"}


def is_expression_location(v, loc):
    if not isinstance(v, str):
        return False
    path = loc[2]
    return "/constants/" in path or path.rsplit("/", 1)[-1] in EXPRESSION_KEYS or re.search(r"[A-Za-z_(]", v) is None \
        or any(c in v for c in "+-*/()")


BAD_EXPRESSIONS = [
    "tan(pi/2)", "1/0", "sqrt(-1)", "1e308*10", "exp(1000)", "log(0)", "0/0", "ln(-1)", "asin(2)", "pow(-1, 0.5)",
    "pow(0, -1)", "cot(0)", "coth(0)", "-1e308*10", "1e999", "9" * 400, "1e-999", "(", ")", "((1)", "(1))", "1 +",
    "* 2", "1 2", "", " ", "foo", "foo(1)", "sin", "sin(1, 2)", "pow(1)", "if(1, 2)", "if(x0 > 0, skip, 1)", "skip",
    "Skip", "t", "x0 +", "x", "dt", "1 & 2", "1 | 2", "a = 1", "1 == = 2", "\u03c0", "1\u00a0+1", "$", "#", "\\",
    "(" * 300 + "1" + ")" * 300, "-" * 1000 + "1", "1" + "*1" * 20000, "1" + "+1" * 40000, "sin(" * 250 + "1" +
    ")" * 250, "1..2",
    "1e", "1e+", ".", "..", "1.e5", "e5", "_", "__init__", "nan", "inf", "NaN", "Infinity", "if(0, 1/0, 1)",
    "0 and 1/0", "1 or 1/0", "pi/0", "10^400", "2^-2000", "min(1)", "max(1,2,3)", "atan2(0, 0)", "floor(1e308)",
]

BAD_CONSTANT_NAMES = ["bad$name", "", "1abc", "sin", "if", "pi", "x", "a b", "\u00e9t\u00e9", "and", "skip", "t",
                      "rho0", "a-b", "a.b", "_", "_ok", "E", "dp", "log", "x" * 300, "\u0000", "h"]


def random_expression(rng):
    tokens = ["1", "0", "-", "+", "*", "/", "^", "(", ")", ",", "x0", "y0", "t", "pi", "sin", "if", "skip", "and",
              "or", "<", "==", "1e308", "dp", "H", "L", "unknown", ";", "=", " "]
    return "".join(rng.choice(tokens) for _ in range(rng.randint(1, 12)))


def long_string(rng):
    n = rng.choice([300, 1000, 5000, 100000])
    return rng.choice(["a", "x_", "-", "\u00e9", "/", "."]) * (n // 2 + 1)


def deep_value(rng, original):
    depth = rng.choice([100, 250, 257, 300, 1000, 10000, 100000])
    kind = rng.choice(["array", "object", "union", "transform", "difference"])
    leaf = original if isinstance(original, dict) else {"box": {"min": [0, 0], "max": [1, 1]}}
    if kind == "array":
        return Deep("[", "]", depth, 1)
    if kind == "object":
        return Deep('{"a": ', "}", depth, 1)
    if kind == "union":
        return Deep('{"union": [', "]}", depth, leaf)
    if kind == "difference":
        return Deep('{"difference": [', ', {"box": {"min": [9, 9], "max": [10, 10]}}]}', depth, leaf)
    return Deep('{"transform": {"shape": ', "}}", depth, leaf)


def swap_value(rng, v):
    options = ["text", 1e300, 0, [1, 2], [], {"a": 1}, {}, None, True, False, [[1, 2], [3, 4]], "1e999", "H/0"]
    options = [o for o in options if type(o) is not type(v)] or options
    return copy.deepcopy(rng.choice(options))


# ---------------------------------------------------------------- mutations
# Each takes (rng, doc, case) and changes doc in place; case.sets collects
# --set arguments and case.text_edits text-level changes applied after dump.


# Where -1 could make a body legitimately bigger (and slow), not refused.
GEOMETRY = re.compile(r"/(geometry|region|shape|bounds|box|circle|sphere|cylinder|polygon|extrude|points)/")


def m_number(rng, doc, case):
    loc = pick(rng, doc, lambda v, l: is_number(v))
    if loc:
        container, key, path = loc
        numbers = [x for x in EXTREME_NUMBERS if not (GEOMETRY.search(path + "/") and x == -1)]
        container[key] = rng.choice(numbers + [Raw("1e999"), Raw("-1e999"), Raw("1e-999"), Raw("-0e0")])


def m_type_swap(rng, doc, case):
    loc = pick(rng, doc)
    if loc:
        container, key, _ = loc
        container[key] = swap_value(rng, container[key])


def m_delete(rng, doc, case):
    loc = pick(rng, doc, lambda v, l: isinstance(l[0], dict))
    if loc:
        del loc[0][loc[1]]


def m_rename(rng, doc, case):
    loc = pick(rng, doc, lambda v, l: isinstance(l[0], dict))
    if loc:
        container, key, _ = loc
        new = rng.choice([key + "_", key.upper(), "", " " + key, key[:-1], "bad key", "\u00e9", key * 40])
        if new not in container:
            items = [(new if k == key else k, v) for k, v in container.items()]
            container.clear()
            container.update(items)


def m_duplicate(rng, doc, case):
    loc = pick(rng, doc, lambda v, l: isinstance(v, dict) and len(v) > 0)
    if loc:
        container, key, _ = loc
        pairs = list(container[key].items())
        k, v = rng.choice(pairs)
        pairs.insert(rng.randint(0, len(pairs)), (k, swap_value(rng, v) if rng.random() < 0.5 else copy.deepcopy(v)))
        container[key] = Dup(pairs)


def m_long_string(rng, doc, case):
    if rng.random() < 0.4:
        doc["name"] = rng.choice(["n", "n_", "a-b."]) * rng.choice([100, 150, 300, 1000])
        return
    loc = pick(rng, doc, lambda v, l: isinstance(v, str))
    if loc:
        loc[0][loc[1]] = long_string(rng)


def m_deep(rng, doc, case):
    if rng.random() < 0.5 and doc.get("bodies") and isinstance(doc["bodies"], list) and \
            isinstance(doc["bodies"][0], dict):
        target = rng.choice(["geometry"] + (["region"] if doc.get("clamps") else []))
        if target == "geometry":
            doc["bodies"][0]["geometry"] = deep_value(rng, doc["bodies"][0].get("geometry"))
        else:
            doc["clamps"][0]["region"] = deep_value(rng, doc["clamps"][0].get("region"))
        return
    loc = pick(rng, doc)
    if loc:
        loc[0][loc[1]] = deep_value(rng, loc[0][loc[1]])


def m_huge_array(rng, doc, case):
    n = rng.choice([10000, 100000])
    what = rng.choice(["clamps", "probes", "constants", "fields", "bodies", "polygon", "generic"])
    if what in ("clamps", "probes", "polygon"):  # each clamp, probe or vertex costs a pass over the particles
        n //= 10
    bodies = doc.get("bodies") if isinstance(doc.get("bodies"), list) else []
    body0 = bodies[0] if bodies and isinstance(bodies[0], dict) else {}
    if what == "clamps" and body0.get("geometry") is not None:
        clamp = {"body": body0.get("name", "b"), "region": copy.deepcopy(body0["geometry"])}
        doc["clamps"] = [clamp] * n
        if rng.random() < 0.5:
            doc["clamps"][rng.randrange(n)] = {"body": clamp["body"], "region": deep_value(rng, clamp["region"])}
    elif what == "probes" and isinstance(doc.get("probes"), list) and doc["probes"]:
        p = doc["probes"][0]
        doc["probes"] = [dict(p, name="p%d" % k) if isinstance(p, dict) else p for k in range(n)]
    elif what == "constants":
        doc["constants"] = dict(doc.get("constants") or {}) if isinstance(doc.get("constants"), dict) else {}
        doc["constants"].update({"c%d" % k: ("c%d + 1" % (k - 1) if k else 1) for k in range(n)})
    elif what == "fields" and isinstance(doc.get("probes"), list) and doc["probes"]:
        if isinstance(doc["probes"][0], dict):
            doc["probes"][0]["fields"] = ["position"] * n
    elif what == "bodies" and body0:  # one name: refused (distinct copies would overlap: legitimately slow)
        doc["bodies"] = [body0] * (n // 10)
    elif what == "polygon":
        import math
        pts = [[math.cos(2 * math.pi * k / n) * 0.01, math.sin(2 * math.pi * k / n) * 0.01] for k in range(n)]
        if body0:
            body0["geometry"] = {"polygon": {"points": pts}}
    else:
        loc = pick(rng, doc)
        if loc:
            loc[0][loc[1]] = [copy.deepcopy(loc[0][loc[1]])] * n


def m_expression(rng, doc, case):
    loc = pick(rng, doc, is_expression_location)
    bad = rng.choice(BAD_EXPRESSIONS) if rng.random() < 0.7 else random_expression(rng)
    if loc:
        container, key, _ = loc
        container[key] = rng.choice([bad, bad, str(container[key]) + rng.choice([")", "(", " +", "*", " x9"])])


def m_constant(rng, doc, case):
    if not isinstance(doc.get("constants"), dict):
        doc["constants"] = {}
    name = rng.choice(BAD_CONSTANT_NAMES + ["ok_name"])
    value = rng.choice([1, 0, 1e308, "1", rng.choice(BAD_EXPRESSIONS), "ok_name", name, None, [1], True])
    items = list(doc["constants"].items())
    items.insert(rng.randint(0, len(items)), (name, value))
    doc["constants"] = dict(items)
    # Existing constants: one of them becomes a dangerous expression.
    if doc["constants"] and rng.random() < 0.5:
        k = rng.choice(sorted(doc["constants"]))
        doc["constants"][k] = rng.choice(["tan(pi/2)", "exp(700)", "1e308*10", "1/(1-1)", "1e-320", "-1e308"])


def set_path(rng, doc):
    loc = pick(rng, doc)
    return ".".join(loc[2].strip("/").split("/")) if loc else "name"


def m_set(rng, doc, case):
    path = rng.choice([set_path(rng, doc), "constants.bad$name", "constants.vf", "solver.end_time", "nonexistent.a.b",
                       "bodies.99.name", "a..b", "", "bodies.0.spacing", "output.interval", "name", "constants.",
                       "bodies.0.geometry", "solver.relaxation.seed"])
    value = rng.choice(["1", "-1", "1e999", "-1e999", '"tan(pi/2)"', '"1/0"', "null", "[]", "{}", "true", "text",
                        "5e-324", "1e308", "[" * 300 + "]" * 300, "[" * 100 + "]" * 100, '"' + "a" * 300 + '"',
                        '{"a":', "0x10", "NaN", '"bad$name"', "a" * 300, '{"union": []}'])
    case.sets.append(path + "=" + value if rng.random() < 0.95 else path)


def m_text(rng, doc, case):
    case.text_edits.append(rng.choice(["truncate", "byte", "delete", "garbage", "comment", "bom", "nan", "overflow",
                                       "unterminated", "utf8", "empty", "swap_bracket"]))


def m_mild(rng, doc, case):
    """A plausible edit that keeps most scenes valid, so that runs are reached:
    a material or solver number scaled, or another choice of an option."""
    choices = {"hourglass": ["none", "laplacian", "genog"], "precision": ["float", "double"],
               "model": ["neo_hookean", "saint_venant_kirchhoff", "j2", "j2_mandel"], "sound_speed": ["bulk", "p_wave"],
               "form": ["vector", "dyadic", "isotropic", "split"], "limiter": ["paper", "capped"]}
    loc = pick(rng, doc, lambda v, l: (isinstance(v, str) and l[1] in choices) or (
        is_number(v) and re.search(r"/(material|solver|initial_velocity|output|fracture|contact)/", l[2] + "/")
        and not re.search(r"spacing|interval", l[2])))
    if loc:
        container, key, _ = loc
        v = container[key]
        container[key] = rng.choice(choices[key]) if isinstance(v, str) else v * rng.choice([0.5, 2, -1, 10, 0.1, 0])


def m_output(rng, doc, case):
    out = doc.setdefault("output", {}) if isinstance(doc.get("output", {}), dict) else {}
    key = rng.choice(["interval", "probe_interval", "checkpoint_interval", "vtu"])
    out[key] = rng.choice([5e-324, 1e-300, 1e-320, 1e-12, 0, -1, 1e308, True, "end_time"])


MUTATIONS = [(m_number, 12), (m_type_swap, 10), (m_delete, 8), (m_rename, 5), (m_duplicate, 4), (m_long_string, 5),
             (m_deep, 7), (m_huge_array, 3), (m_expression, 14), (m_constant, 10), (m_set, 8), (m_text, 6),
             (m_mild, 20), (m_output, 4)]


def apply_text_edit(rng, text, edit):
    if not text:
        return text
    k = rng.randrange(len(text))
    if edit == "truncate":
        return text[:k]
    if edit == "byte":
        return text[:k] + rng.choice(["\x00", "\x7f", "{", "]", ",", ":", '"', "\\", "\t"]) + text[k:]
    if edit == "delete":
        return text[:k] + text[k + 1:]
    if edit == "garbage":
        return text + rng.choice(["x", "{}", "]", " // end", "/* open", ",", "\x00"])
    if edit == "comment":
        return text[:k] + rng.choice(["/* c */", "//\n", "/*"]) + text[k:]
    if edit == "bom":
        return "\ufeff" + text
    if edit == "nan":
        return re.sub(r"(?<=[:\[,] )-?\d+(\.\d+)?([eE][-+]?\d+)?", rng.choice(["NaN", "Infinity", "-Infinity"]), text,
                      count=1)
    if edit == "overflow":  # a number literal beyond the double range somewhere in the text
        numbers = list(re.finditer(r"(?<=[:\[,] )-?\d+(\.\d+)?([eE][-+]?\d+)?", text))
        if numbers:
            m = rng.choice(numbers)
            return text[:m.start()] + rng.choice(["-1e999", "1e999", "1" * 400, "1e-99999"]) + text[m.end():]
        return text
    if edit == "unterminated":
        return text[:k] + '"' + text[k:]
    if edit == "utf8":
        return text[:k] + "\udcff" + text[k:]  # written with surrogateescape: a lone invalid byte
    if edit == "empty":
        return rng.choice(["", " ", "null", "[]", "1", '"scene"', "{}"])
    if edit == "swap_bracket":
        return text.replace("{", "[", 1)
    return text


# ---------------------------------------------------------------- cases


class Case:
    def __init__(self, index, base, doc):
        self.index, self.base, self.doc = index, base, doc
        self.mutations, self.sets, self.text_edits = [], [], []


def base_scenes():
    names = []
    for folder in ("configs", os.path.join("tests", "regression", "scenes")):
        d = os.path.join(ROOT, folder)
        if os.path.isdir(d):
            names += [os.path.join(folder, f) for f in sorted(os.listdir(d)) if f.endswith(".json") and f not in HEAVY]
    return names


def make_case(seed, index, bases, loaded):
    rng = random.Random("%s:%d" % (seed, index))
    base = rng.choice(bases)
    case = Case(index, base, copy.deepcopy(loaded[base]))
    weights = [w for _, w in MUTATIONS]
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        mutate = rng.choices([m for m, _ in MUTATIONS], weights)[0]
        case.mutations.append(mutate.__name__[2:])
        mutate(rng, case.doc, case)
    case.text = to_text(case.doc)
    for edit in case.text_edits:
        case.text = apply_text_edit(rng, case.text, edit)
    return case


# ---------------------------------------------------------------- checks

# An exit-2 message names where the problem is: a JSON path (/bodies/0/...),
# the scene file with line:column (syntax), the scene file alone (not an
# object, a number beyond range), or the --set option it came from.
ERROR_LINE = re.compile(r"^mfsd: error: (.*)$", re.M)


def located(message, scene_file):
    if message.startswith("/"):
        return True
    if message.startswith(scene_file + ":"):
        rest = message[len(scene_file) + 1:]
        return re.match(r"\d+:\d+: ", rest) is not None or rest.startswith(" ")
    if message.startswith("--set "):
        return True
    return False


def run_binary(args, timeout):
    start = time.monotonic()
    try:
        p = subprocess.run(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=timeout, start_new_session=True)
        return p.returncode, p.stderr.decode("utf-8", "replace"), time.monotonic() - start
    except subprocess.TimeoutExpired as e:
        return None, (e.stderr or b"").decode("utf-8", "replace"), time.monotonic() - start
    except OSError as e:  # e.g. the binary is being relinked
        return "not started", str(e), time.monotonic() - start


def check_outcome(command, rc, stderr, scene_file):
    """Problems with one command's outcome (empty when fine)."""
    if rc is None:
        return ["%s: timed out (hang)" % command]
    if isinstance(rc, str):
        return ["%s: %s (%s)" % (command, rc, stderr)]
    problems = []
    if rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = str(-rc)
        problems.append("%s: killed by signal %s" % (command, name))
    elif rc not in (0, 2, 3):
        problems.append("%s: exit code %d" % (command, rc))
    if "internal error" in stderr:
        problems.append("%s: 'internal error' in stderr" % command)
    if rc == 2:
        errors = ERROR_LINE.findall(stderr)
        if not errors:
            problems.append("%s: exit 2 without an 'mfsd: error:' line" % command)
        for message in errors:
            if not located(message, scene_file):
                problems.append("%s: exit-2 message names no JSON path: %s" % (command, message[:200]))
    return problems


def run_case(case, binary, workdir, timeout):
    folder = os.path.join(workdir, "case%05d" % case.index)
    os.makedirs(folder, exist_ok=True)
    scene = os.path.join(folder, "scene.json")
    with open(scene, "w", encoding="utf-8", errors="surrogateescape") as f:
        f.write(case.text)
    sets = []
    for s in case.sets:
        sets += ["--set", s]
    out = os.path.join(folder, "out")
    result = {"case": case, "folder": folder, "problems": [], "codes": [], "seconds": 0.0}
    rc, err, secs = run_binary([binary, "check", scene] + sets, timeout)
    result["codes"].append(("check", rc))
    result["seconds"] += secs
    result["problems"] += check_outcome("check", rc, err, scene)
    result["stderr"] = err
    if rc == 0:
        rc, err, secs = run_binary([binary, "run", scene] + sets + ["--max-steps", "2", "-q", "-o", out,
                                                                    "--threads", "1"], timeout)
        result["codes"].append(("run", rc))
        result["seconds"] += secs
        result["problems"] += check_outcome("run", rc, err, scene)
        result["stderr"] = err
        if rc == 2 and os.path.exists(out):
            result["problems"].append("run: exit 2 left the output folder behind")
    return result


def reproduction(case, binary, path):
    sets = "".join(" --set " + shlex.quote(s) for s in case.sets)
    return "%s check %s%s  # then: run ... --max-steps 2 -q -o OUT --threads 1" % (binary, path, sets)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mfsd"))
    ap.add_argument("--count", type=int, default=500, help="number of cases (default 500)")
    ap.add_argument("--time-limit", type=float, default=170, help="start no case after this many seconds")
    ap.add_argument("--seed", default="1", help="seed of the case list (default 1)")
    ap.add_argument("--timeout", type=float, default=30, help="seconds one mfsd process may take (default 30)")
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1), help="cases in parallel (default 2)")
    ap.add_argument("--min-cases", type=int, default=0,
                    help="fail when fewer cases than this ran (the time limit cut the rest)")
    ap.add_argument("--keep", help="copy failing cases (scene, --set arguments, stderr) into this folder")
    ap.add_argument("--only", type=int, action="append", help="run only case K (repeatable)")
    ap.add_argument("--list", action="store_true", help="print the cases' mutations and exit")
    ap.add_argument("-v", "--verbose", action="store_true", help="one line per case")
    args = ap.parse_args()
    binary = os.path.abspath(args.binary)
    if not args.list and not os.access(binary, os.X_OK):
        print("fuzz: no executable mfsd at %s (give --binary)" % binary, file=sys.stderr)
        return 2
    bases = base_scenes()
    loaded = {}
    for b in bases:
        with open(os.path.join(ROOT, b), encoding="utf-8") as f:
            loaded[b] = json.load(f)
    indices = args.only if args.only else list(range(args.count))
    if args.list:
        for k in indices:
            c = make_case(args.seed, k, bases, loaded)
            print("case %d: %s %s %s %s" % (k, c.base, c.mutations, c.text_edits, c.sets))
        return 0

    start = time.monotonic()
    workdir = tempfile.mkdtemp(prefix="mfsd_fuzz_")
    results = []
    lock = threading.Lock()
    skipped = 0

    def one(k):
        case = make_case(args.seed, k, bases, loaded)
        r = run_case(case, binary, workdir, args.timeout)
        if r["problems"] and args.keep:
            dest = os.path.join(args.keep, "seed%s_case%05d" % (args.seed, k))
            shutil.rmtree(dest, ignore_errors=True)
            os.makedirs(dest)
            shutil.copy(os.path.join(r["folder"], "scene.json"), dest)
            with open(os.path.join(dest, "README.txt"), "w", encoding="utf-8") as f:
                f.write("base %s, mutations %s, text edits %s\n" % (case.base, case.mutations, case.text_edits))
                f.write("problems:\n  " + "\n  ".join(r["problems"]) + "\n")
                f.write("reproduce: " + reproduction(case, binary, os.path.join(dest, "scene.json")) + "\n")
                f.write("stderr (last command):\n" + r["stderr"][-4000:])
        shutil.rmtree(r["folder"], ignore_errors=True)
        r.pop("folder")
        r["stderr_tail"] = r.pop("stderr")[-300:]
        case.doc = None  # free the (possibly huge) scene
        if args.verbose:
            with lock:
                print("case %d %.2fs %s %s %s" % (k, r["seconds"], r["codes"], case.mutations,
                                                  "FAIL" if r["problems"] else ""), flush=True)
        return r

    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            pending = set()
            queue = list(indices)
            while queue or pending:
                while queue and len(pending) < max(1, args.jobs):
                    if time.monotonic() - start > args.time_limit:
                        skipped += len(queue)
                        queue = []
                        break
                    pending.add(pool.submit(one, queue.pop(0)))
                if not pending:
                    break
                done, pending = concurrent.futures.wait(pending, return_when=concurrent.futures.FIRST_COMPLETED)
                results += [d.result() for d in done]
    finally:
        shutil.rmtree(workdir, ignore_errors=True)

    elapsed = time.monotonic() - start
    results.sort(key=lambda r: r["case"].index)
    counts = {}
    for r in results:
        for command, rc in r["codes"]:
            key = "%s %s" % (command, "timeout" if rc is None else rc)
            counts[key] = counts.get(key, 0) + 1
    failures = [r for r in results if r["problems"]]
    print("fuzz: seed %s, %d case(s) in %.1f s (%d not started: time limit %.0f s), binary %s" %
          (args.seed, len(results), elapsed, skipped, args.time_limit, binary))
    print("exit codes: " + ", ".join("%s: %d" % (k, counts[k]) for k in sorted(counts)))
    slow = sorted(results, key=lambda r: -r["seconds"])[:3]
    print("slowest: " + ", ".join("case %d %.1f s" % (r["case"].index, r["seconds"]) for r in slow))
    for r in failures:
        c = r["case"]
        print("FAIL case %d (%s; %s%s): %s" % (c.index, c.base, "+".join(c.mutations),
                                              (" " + "+".join(c.text_edits)) if c.text_edits else "",
                                              "; ".join(r["problems"])))
        print("  reproduce: %s --seed %s --only %d --keep DIR --binary %s" %
              (os.path.relpath(os.path.abspath(__file__)), args.seed, c.index, binary))
        print("  stderr: " + r["stderr_tail"].strip().replace("\n", " | ")[-200:])
    print("fuzz: %s" % ("%d failure(s)" % len(failures) if failures else "all cases passed"))
    if len(results) < args.min_cases:
        print("fuzz: only %d case(s) ran before the time limit, fewer than --min-cases %d: a fuzz that "
              "tries little passes without meaning it" % (len(results), args.min_cases))
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
