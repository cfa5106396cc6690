#!/usr/bin/env python3
"""ctest FloatKernels.PtxChecker: scripts/check_float_ptx.py on the fixtures in
tests/fixtures/float_ptx (clean: f32 arithmetic, libdevice's trig slow path and
an allowed set-up kernel; violation: a double floor, a double device function
and a trig look-alike), and, where FLOAT_PTX names the folders where nvcc
kept the PTX of a CUDA build's float variants (FloatKernels.NoDoubleInStepKernels),
on every .ptx in them (one per architecture).

  python3 tests/scripts/test_check_float_ptx.py [-v]"""
import glob
import os
import unittest

from script_test_prelude import ROOT, fixture

import check_float_ptx  # noqa: E402

FIXTURE = fixture("float_ptx")


class Checker(unittest.TestCase):
    def test_clean_passes_and_excuses_the_set_up_kernel(self):
        violations, scanned, excused = check_float_ptx.check([os.path.join(FIXTURE, "clean.ptx")])
        self.assertEqual(violations, [])
        self.assertEqual(scanned, 2)
        self.assertEqual(len(excused), 1)
        self.assertIn("CellKeyFunctor<3>", excused[0][1])

    def test_violations_are_named_with_their_instructions(self):
        violations, scanned, _ = check_float_ptx.check([os.path.join(FIXTURE, "violation.ptx")])
        self.assertEqual(scanned, 2)
        names = {v[1]: v[2] for v in violations}
        self.assertEqual(len(names), 2)
        kernel = [n for n in names if "ContactKeyFunctor<3, float>" in n]
        self.assertEqual(len(kernel), 1)
        lines = names[kernel[0]]
        self.assertTrue(any(s.startswith("cvt.rmi.f64.f64") for s in lines))
        # the look-alike of the trig slow path (another constant) is not excused
        self.assertTrue(any("0d3FF0000000000000" in s for s in lines))
        self.assertTrue(any("add_step_force" in n for n in names))

    def test_exit_codes(self):
        self.assertEqual(check_float_ptx.main([os.path.join(FIXTURE, "clean.ptx")]), 0)
        self.assertEqual(check_float_ptx.main([os.path.join(FIXTURE, "violation.ptx")]), 1)
        self.assertEqual(check_float_ptx.main([os.path.join(ROOT, "README.md")]), 2)
        self.assertEqual(check_float_ptx.main([]), 2)


@unittest.skipUnless(os.environ.get("FLOAT_PTX"), "FLOAT_PTX unset (no CUDA build)")
class Build(unittest.TestCase):
    def test_no_double_in_step_kernels(self):
        paths = []
        for folder in os.environ["FLOAT_PTX"].split(";"):
            found = sorted(glob.glob(os.path.join(folder, "*.ptx")))
            self.assertTrue(found, f"{folder}: no .ptx (nvcc --keep of the float variants, CMakeLists.txt)")
            paths += found
        violations, scanned, _ = check_float_ptx.check(paths)
        self.assertGreater(scanned, 100)  # every kernel of the solver, not an empty file
        self.assertEqual([f"{v[1]}: {v[2][:3]}" for v in violations], [])


if __name__ == "__main__":
    unittest.main()
