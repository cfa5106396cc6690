#!/usr/bin/env python3
"""ctest GpuCheck.Report: scripts/gpu_report.py on the fixture folder
tests/fixtures/gpu_report (a gtest XML with worst_difference_* properties, a
throughput JSON, a run's timing.json, the phases), and, where
GPU_CHECK_BUILD_DIR names a build folder, the CPU half of scripts/gpu_check.sh
(--dry-run exits 0; without --dry-run, on a machine whose nvidia-smi lists no
GPU, it exits 2 before building anything).

  python3 tests/scripts/test_gpu_report.py [-v]"""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

from script_test_prelude import ROOT, fixture

import gpu_report  # noqa: E402

FIXTURE = fixture("gpu_report")


class Report(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="gpu_report_")
        self.dir = os.path.join(self.tmp, "out")
        shutil.copytree(FIXTURE, self.dir)

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def write(self, *args):
        rc = gpu_report.main(["write", self.dir, *args])
        with open(os.path.join(self.dir, "report.json")) as f:
            rep = json.load(f)
        with open(os.path.join(self.dir, "report.md")) as f:
            md = f.read()
        return rc, rep, md

    def test_full_report(self):
        rc, rep, md = self.write()
        self.assertEqual(rc, 1)
        self.assertEqual(rep["verdict"], "FAIL")
        self.assertEqual(rep["host"], "gpu-host")
        dev = rep["device"]
        self.assertEqual(dev["name"], "NVIDIA H200")
        self.assertEqual(dev["memory"], "143771 MiB")
        self.assertEqual(dev["driver_version"], "580.159.04")
        self.assertEqual(dev["driver_cuda_version"], "13.0")
        self.assertEqual(dev["nvcc_version"], "13.0 (V13.0.88)")
        self.assertEqual(dev["mfsd_cuda_devices"], "1 (NVIDIA H200)")
        tests = {t["name"]: t for t in rep["tests"]}
        self.assertEqual(list(tests)[0], "CrossBackend.OscillatingPlateDouble")  # the planned order
        self.assertEqual(tests["CrossBackend.OscillatingPlateDouble"]["result"], "pass")
        w = tests["CrossBackend.OscillatingPlateDouble"]["worst_difference"]
        self.assertEqual((w["quantity"], w["value"], w["tolerance"]), ("velocity", 4e-11, 1e-9))
        self.assertEqual(len(tests["CrossBackend.OscillatingPlateDouble"]["differences"]), 2)
        self.assertEqual(tests["CrossBackend.TaylorBarsDouble"]["result"], "FAIL")
        self.assertAlmostEqual(tests["CrossBackend.TaylorBarsDouble"]["worst_difference"]["ratio"], 100.0)
        self.assertIn("1.2e-05", tests["CrossBackend.TaylorBarsDouble"]["failure"])
        # Properties as testcase attributes (older Google Tests).
        self.assertEqual(tests["CrossBackend.BendingColumnFloat"]["worst_difference"]["value"], 3e-5)
        self.assertEqual(tests["CrossBackend.RelaxationDouble"]["result"], "SKIPPED")
        # Text that does not parse is kept as it is.
        self.assertEqual(tests["CrossBackend.FractureDouble"]["worst_difference"]["text"], "something unexpected")
        # Listed but absent from the XML (the binary stopped).
        self.assertEqual(tests["CrossBackend.TwistingColumnDouble"]["result"], "no result")
        self.assertIsNone(tests["CrossBackend.TwistingColumnDouble"]["worst_difference"])
        self.assertEqual(rep["tests_passed"], 3)

        rows = rep["throughput"]
        self.assertEqual(len(rows), 3)
        self.assertEqual(rows[0]["round_trips_per_step"], 2)  # from the row
        self.assertEqual(rows[1]["round_trips_per_step"], 1.0)  # from throughput_timing/
        self.assertIsNone(rows[2]["round_trips_per_step"])
        self.assertAlmostEqual(rows[0]["stages"]["force"]["microseconds_per_step"], 6.5 * 10800 / 1e3)
        self.assertAlmostEqual(rep["in_budget_seconds"], 178.2)
        self.assertFalse(rep["over_budget"])

        self.assertIn("| CrossBackend.TaylorBarsDouble | FAIL | 12.50 | velocity 1e-05 (tolerance 1e-07, 100x) |", md)
        self.assertIn("| bending column 3D | 12 | 10800 | double | 50.59 | 0.213 | 2 |", md)
        self.assertIn("| oscillating plate 2D | 20 | 5792 | double | 52.22 | 0.111 | n/a |", md)
        self.assertIn("| case | H/dp | precision | stress | force | time_step |", md)
        self.assertIn("NVIDIA H200", md)
        self.assertIn("580.159.04 (CUDA 13.0)", md)
        self.assertIn("within budget", md)
        self.assertIn("| study_crack_branching | 300.0 | 0 | no |", md)
        self.assertIn("snapshot   1: velocity 7.00e-15", md)

    def test_over_budget(self):
        _, rep, md = self.write("--budget", "100")
        self.assertTrue(rep["over_budget"])
        self.assertIn("OVER BUDGET", md)

    def test_log_without_xml(self):
        os.remove(os.path.join(self.dir, "gpu_tests.xml"))
        _, rep, _ = self.write()
        tests = {t["name"]: t for t in rep["tests"]}
        self.assertEqual(rep["tests_source"], "log")
        self.assertEqual(tests["CrossBackend.FractureDouble"]["result"], "pass")
        self.assertEqual(tests["CrossBackend.FractureDouble"]["seconds"], 25.25)
        self.assertEqual(tests["CrossBackend.TaylorBarsDouble"]["result"], "FAIL")

    def test_pass_without_optional_files(self):
        for f in ("throughput_timing", "divergence.txt", "nvcc_version.txt", "build_info.txt", "nvidia_smi.txt"):
            p = os.path.join(self.dir, f)
            shutil.rmtree(p) if os.path.isdir(p) else os.remove(p)
        with open(os.path.join(self.dir, "tests_planned.txt"), "w") as f:
            f.write("CrossBackend.\n  OscillatingPlateDouble\n  BendingColumnFloat\n")
        with open(os.path.join(self.dir, "gpu_tests.xml"), "w") as f:
            f.write('<testsuites><testsuite name="CrossBackend">'
                    '<testcase name="OscillatingPlateDouble" status="run" result="completed" time="1" '
                    'classname="CrossBackend"/><testcase name="BendingColumnFloat" status="run" '
                    'result="completed" time="2" classname="CrossBackend"/></testsuite></testsuites>')
        with open(os.path.join(self.dir, "phases.tsv"), "w") as f:
            f.write("tests\t10.0\t0\t1\t\nthroughput\t20.0\t0\t1\t\n")
        rc, rep, md = self.write()
        self.assertEqual((rc, rep["verdict"]), (0, "PASS"))
        self.assertEqual(rep["device"]["driver_cuda_version"], "n/a")
        self.assertEqual(rep["throughput"][1]["round_trips_per_step"], None)
        self.assertNotIn("gpu_divergence", md)

    def test_no_gpu_and_dry_run(self):
        for f in ("gpu_tests.xml", "gpu_tests.log", "throughput.json"):
            os.remove(os.path.join(self.dir, f))
        with open(os.path.join(self.dir, "meta.env"), "a") as f:
            f.write("gpu=no\ngpu_reason=nvidia-smi not found\n")
        rc, rep, md = self.write()
        self.assertEqual((rc, rep["verdict"]), (2, "NO GPU"))
        rc, rep, md = self.write("--dry-run")
        self.assertEqual((rc, rep["verdict"]), (0, "DRY RUN"))
        self.assertTrue(all(t["result"] == "not run" for t in rep["tests"]))
        self.assertIn("6 planned", md)
        self.assertIn("| oscillating plate 2D | configs/oscillating_plate_2d.json | 20 | double |", md)

    def test_list_cases(self):
        quick = gpu_report.throughput_cases()
        full = gpu_report.throughput_cases(full=True)
        self.assertTrue(quick and len(full) > len(quick))
        self.assertIn(("bending column 3D", "configs/bending_column_3d.json", 12, "double"), quick)
        self.assertTrue(all(p in ("double", "float") for *_, p in full))


@unittest.skipUnless(os.environ.get("GPU_CHECK_BUILD_DIR"), "GPU_CHECK_BUILD_DIR not set")
class CheckScript(unittest.TestCase):
    """The CPU half of scripts/gpu_check.sh on an existing build folder."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="gpu_check_")
        self.build = os.environ["GPU_CHECK_BUILD_DIR"]

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def test_dry_run(self):
        out = os.path.join(self.tmp, "dry")
        p = subprocess.run(["bash", os.path.join(ROOT, "scripts", "gpu_check.sh"), "--prebuilt", self.build,
                            "--dry-run", "--out", out], capture_output=True, text=True, timeout=120)
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(os.path.join(out, "report.json")) as f:
            rep = json.load(f)
        self.assertEqual(rep["verdict"], "DRY RUN")
        self.assertTrue(any(t["name"].startswith("CrossBackend.") for t in rep["tests"]))
        self.assertTrue(rep["throughput_planned"])

    def test_no_gpu_exits_2(self):
        # An nvidia-smi that finds no device, first on PATH: exits 2 before building.
        fake = os.path.join(self.tmp, "bin")
        os.makedirs(fake)
        with open(os.path.join(fake, "nvidia-smi"), "w") as f:
            f.write("#!/bin/sh\necho 'No devices were found'\nexit 6\n")
        os.chmod(os.path.join(fake, "nvidia-smi"), 0o755)
        env = dict(os.environ, PATH=fake + os.pathsep + os.environ.get("PATH", ""))
        out = os.path.join(self.tmp, "nogpu")
        p = subprocess.run(["bash", os.path.join(ROOT, "scripts", "gpu_check.sh"), "--prebuilt", self.build,
                            "--out", out], capture_output=True, text=True, timeout=120, env=env)
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("no usable GPU", p.stderr)
        with open(os.path.join(out, "report.json")) as f:
            self.assertEqual(json.load(f)["verdict"], "NO GPU")


if __name__ == "__main__":
    unittest.main()
