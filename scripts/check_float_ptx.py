#!/usr/bin/env python3
"""Float means float (issue 20, docs/floating-point.md): reads the PTX that
nvcc keeps for the float solver variants (build/generated/ptx/*_float/*.ptx,
CMakeLists.txt) and fails if a kernel or device function that may run every
step has a double-precision instruction (.f64).

Kernels allowed to use double are listed below with the reason: the set-up
neighbour search (reference positions in double, pairs cast to Real once),
and the energy sums taken at output times. One instruction sequence is
allowed everywhere: the slow path of CUDA's float sin/cos/tan argument
reduction (libdevice), which converts the quadrant count to double and
multiplies it by pi/2 * 2^-64 once, for |x| > 105615 only.

  scripts/check_float_ptx.py FILE.ptx [...]   exit 0 clean, 1 violations, 2 bad input
"""
import re
import subprocess
import sys

# (pattern in the demangled name, why double is right there)
ALLOWED = [
    (r"mfsd::CellKeyFunctor<", "set-up neighbour search: cell keys of the reference positions (double)"),
    (r"mfsd::NeighborCountFunctor<", "set-up neighbour search: pair counts in double"),
    (r"mfsd::ReferencePairFillFunctor<", "set-up: reference pairs computed in double, cast to Real once"),
    (r"mfsd::CellGrid<", "set-up: the cell grid of the reference neighbour search"),
    (r"mfsd::Notch<", "set-up: notches cut reference pairs (computed in double)"),
    (r"mfsd::Vec<[23], double>", "set-up: reference positions in double for the neighbour search"),
    (r"mfsd::EnergySums", "output time: energy sums accumulate in double (energies.csv balance)"),
    (r"mfsd::ulsph::EnergySums", "output time: ULSPH energy sums accumulate in double (energies.csv)"),
    (r"mfsd::ReadScalar<", "output time: the mean hourglass indicator, summed in double"),
    (r"policy_hub<double, ", "second pass of an output-time double sum (its first pass names its functor)"),
]

# The libdevice trig slow path: quadrant (s64) -> f64, * pi/2 2^-64, -> f32.
TRIG_REDUCTION = re.compile(
    r"cvt\.rn\.f64\.s64\s+(%fd\d+),\s*%rd\d+;\s*"
    r"mul\.f64\s+(%fd\d+),\s*\1,\s*0d3BF921FB54442D19;\s*"
    r"cvt\.rn\.f32\.f64\s+%f\d+,\s*\2;")

FUNCTION = re.compile(r"^(?:\.visible\s+|\.weak\s+|\.extern\s+)*\.(entry|func)\s+(?:\([^)]*\)\s*)?([\w$]+)", re.M)


def demangle(names):
    """c++filt for many names at once; the names themselves without it."""
    try:
        out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True, text=True, check=True).stdout
        lines = out.split("\n")
        if len(lines) >= len(names):
            return lines[:len(names)]
    except (OSError, subprocess.CalledProcessError):
        pass
    return list(names)


def functions(text):
    """(kind, mangled name, body) for every .entry and .func defined."""
    starts = list(FUNCTION.finditer(text))
    for k, m in enumerate(starts):
        end = starts[k + 1].start() if k + 1 < len(starts) else len(text)
        yield m.group(1), m.group(2), text[m.start():end]


def double_instructions(body):
    """The lines of `body` that use .f64, less register declarations and the trig slow path."""
    body = TRIG_REDUCTION.sub("", body)
    out = []
    for line in body.split("\n"):
        s = line.strip()
        if ".f64" in s and not s.startswith(".reg"):
            out.append(s)
    return out


def allowed(name):
    for pattern, reason in ALLOWED:
        if re.search(pattern, name):
            return reason
    return None


def check(paths, verbose=False):
    """Returns (violations, scanned, allowed_with_double); a violation is (file, name, lines)."""
    violations, scanned, excused = [], 0, []
    for path in paths:
        with open(path) as f:
            text = f.read()
        found = list(functions(text))
        if not found:
            raise ValueError(f"{path}: no .entry or .func in it (not PTX?)")
        names = demangle([m for _, m, _ in found])
        for (kind, mangled, body), name in zip(found, names):
            scanned += 1
            lines = double_instructions(body)
            if not lines:
                continue
            reason = allowed(name)
            if reason:
                excused.append((path, name, reason))
            else:
                violations.append((path, f"{kind} {name}", lines))
    return violations, scanned, excused


def short(name, width=240):
    name = re.sub(r"(THRUST|CUB)_\d+_SM_\d+(_NS)?::|cuda::std::__\d+::", "", name)
    return name if len(name) <= width else name[:width] + " ..."


def main(argv):
    verbose = "-v" in argv
    paths = [a for a in argv if a != "-v"]
    if not paths:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    try:
        violations, scanned, excused = check(paths)
    except (OSError, ValueError) as e:
        print(f"check_float_ptx: {e}", file=sys.stderr)
        return 2
    print(f"check_float_ptx: {scanned} kernels and device functions in {len(paths)} file(s); "
          f"{len(excused)} allowed double (set-up, output time), {len(violations)} violations")
    if verbose:
        for path, name, reason in excused:
            print(f"  allowed: {short(name, 160)}\n           ({reason})")
    for path, name, lines in violations:
        print(f"\nDOUBLE in a float kernel ({path}):\n  {short(name)}", file=sys.stderr)
        for s in lines[:8]:
            print(f"    {s}", file=sys.stderr)
        if len(lines) > 8:
            print(f"    ... {len(lines) - 8} more", file=sys.stderr)
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
