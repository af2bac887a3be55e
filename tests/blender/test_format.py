"""Unit tests of the add-on's pure-Python modules (no Blender): the schema table, the
scene reader and writer, the Y-up/Z-up mapping, the cache readers and the process
runner, against the softsub binary.

python3 test_format.py --softsub SOFTSUB --source REPO --work DIR"""
import argparse
import glob
import math
import os
import random
import shutil
import struct
import subprocess
import sys
import time
import unittest

parser = argparse.ArgumentParser()
parser.add_argument("--softsub", required=True)
parser.add_argument("--source", required=True)
parser.add_argument("--work", required=True)
ARGS, rest = parser.parse_known_args()
shutil.rmtree(ARGS.work, ignore_errors=True)
os.makedirs(ARGS.work)
sys.path.insert(0, os.path.join(ARGS.source, "blender"))
sys.path.insert(0, os.path.join(ARGS.source, "blender", "tools"))

from softsub_blender import axes, caches, runner, schema, scenefile  # noqa: E402
from softsub_blender.schema_table import SCHEMA  # noqa: E402
import gen_schema  # noqa: E402


def softsub(*argv):
    return subprocess.run([ARGS.softsub, *argv], capture_output=True, text=True)


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


class SchemaTest(unittest.TestCase):
    def test_table_is_what_the_binary_prints(self):
        printed = gen_schema.parse_schema(softsub("schema").stdout)
        self.assertEqual({k: [tuple(r) for r in v] for k, v in printed.items()}, SCHEMA,
                         "schema_table.py is stale: python3 blender/tools/gen_schema.py SOFTSUB > "
                         "blender/softsub_blender/schema_table.py")

    def test_defaults_and_ranges(self):
        self.assertEqual(schema.default("Simulation", "Gravity"), (0.0, -9.81, 0.0))
        self.assertEqual(schema.default("Object", "IsDynamic"), True)
        self.assertEqual(schema.default("Fluid", "Viscosity"), 1.0)
        self.assertEqual(schema.bounds("Simulation", "FramesPerSecond"), (0.001, True, 1000.0, True))
        self.assertEqual(schema.bounds("Simulation", "Substeps"), (1.0, True, 10000.0, True))
        self.assertEqual(schema.bounds("Fluid", "ParticleSize"), (0.0, False, None, False))
        self.assertEqual(schema.bounds("Object", "NormalAttenuation"), (0.0, True, 1.0, True))
        self.assertIsNone(schema.check_range("Fluid", "Viscosity", 0.0))
        self.assertIn("allowed: > 0", schema.check_range("Fluid", "ParticleSize", 0.0))
        self.assertIn("allowed: [0.001, 1000]", schema.check_range("Simulation", "FramesPerSecond", 1001.0))
        self.assertEqual(schema.enum_items("Simulation", "Integrator"),
                         ["explicit-euler", "symplectic-euler", "velocity-verlet"])

    def test_numbers_are_the_shortest_single_precision_text(self):
        for v, text in ((f32(0.1), "0.1"), (f32(-9.81), "-9.81"), (12.0, "12"), (f32(1e-7), "1e-7"),
                        (f32(1 / 3), "0.33333334"), (-0.0, "0"),
                        (40.0000001, "40"), (-29.9999999, "-30")):  # integers once single: "4e1" was written
            self.assertEqual(schema.format_number(v), text)
        rnd = random.Random(5)
        for _ in range(2000):
            v = f32(rnd.uniform(-1e4, 1e4) * 10 ** rnd.randint(-6, 3))
            self.assertEqual(f32(float(schema.format_number(v))), v)


class SceneFileTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(os.path.join(ARGS.work, "scenes"), ignore_errors=True)

    def scenes(self):
        return sorted(glob.glob(os.path.join(ARGS.source, "examples", "*.scene")) +
                      glob.glob(os.path.join(ARGS.source, "tests", "data", "scenes", "good", "*.scene")))

    def test_written_scenes_read_back_equal_in_softsub_and_here(self):
        for path in self.scenes():
            with self.subTest(scene=os.path.basename(path)):
                model = scenefile.read_scene_file(path)
                text = scenefile.write_scene_text(model, num=schema.format_double)
                self.assertEqual(scenefile.read_scene_text(text), model)
                # beside a copy of the scene's folder (mesh paths are relative to it)
                copy = os.path.join(ARGS.work, "scenes", os.path.basename(os.path.dirname(path)))
                if not os.path.isdir(copy):
                    shutil.copytree(os.path.dirname(path), copy, ignore=shutil.ignore_patterns("*Sim"))
                out = os.path.join(copy, "written.scene")
                with open(out, "w") as f:
                    f.write(text)
                a, b = softsub("info", path), softsub("info", out)
                self.assertEqual(b.returncode, 0, b.stderr)
                self.assertEqual(a.stdout.splitlines()[1:], b.stdout.splitlines()[1:])

    def test_defaults_fill_in(self):
        m = scenefile.read_scene_text('<Scene><Fluid><Name>a</Name><Particles>1 2 3</Particles></Fluid>'
                                      '<Object><Shape>sphere</Shape><Size>2</Size></Object></Scene>')
        self.assertEqual(m["Simulation"]["Frames"], 120)
        self.assertIsNone(m["Environment"])
        self.assertEqual(m["fluids"][0]["Particles"], [(1.0, 2.0, 3.0)])
        self.assertEqual(m["fluids"][0]["Amplitude"], 30.0)
        self.assertEqual(m["objects"][0]["Name"], "object1")
        self.assertEqual(m["objects"][0]["Mass"], 1.0)
        self.assertEqual(m["FluidObject"]["params"]["Cutoff"], 1.5)
        self.assertEqual(m["FluidObject"]["RelativeVelocity"], 2.0)

    def test_errors_name_the_element(self):
        cases = [
            ('<Scene><Fluid><Name>a</Name><Viscocity>1</Viscocity></Fluid></Scene>', "unknown element <Viscocity>"),
            ('<Scene><Fluid><Name>a</Name><Viscosity>-1</Viscosity></Fluid></Scene>', "Viscosity: -1 is out of range"),
            ('<Scene><Simulation><Substeps>2.5</Substeps></Simulation></Scene>', "Substeps: '2.5' is not an integer"),
            ('<Scene><Fluid><Name>a b</Name></Fluid></Scene>', "Name: 'a b'"),
            ('<Scene><Fluid><Name>a</Name><NumberOfParticles>2</NumberOfParticles><Particles>0 0 0</Particles>'
             '</Fluid></Scene>', "NumberOfParticles: 2 but 1 positions"),
            ('<Scene><Interactions><FluidFluid><Linear/><Curve><Points>0 1 1 0</Points></Curve></FluidFluid>'
             '</Interactions></Scene>', "exactly one function"),
            ('<Scene><Simulation/><Simulation/></Scene>', "given twice"),
            ('<Scene><Fluid>', "XML"),
        ]
        for text, want in cases:
            with self.subTest(want=want):
                with self.assertRaises(scenefile.SceneError) as e:
                    scenefile.read_scene_text(text, "t.scene")
                self.assertIn(want, str(e.exception))

    def test_bad_fluid_name_is_refused_on_write(self):
        m = scenefile.new_scene()
        m["fluids"].append(scenefile.new_fluid("Sphere.001"))
        with self.assertRaises(scenefile.SceneError):
            scenefile.write_scene_text(m)


class AxesTest(unittest.TestCase):
    def test_vectors(self):
        self.assertEqual(axes.to_softsub((0.0, 0.0, -9.81)), (0.0, -9.81, 0.0))  # gravity
        self.assertEqual(axes.to_softsub((1.0, 2.0, 3.0)), (1.0, 3.0, -2.0))
        rnd = random.Random(1)
        for _ in range(100):
            v = tuple(rnd.uniform(-10, 10) for _ in range(3))
            self.assertEqual(axes.to_blender(axes.to_softsub(v)), v)

    def test_mapping_is_a_rotation(self):
        # M: columns are the images of Blender's X, Y, Z; det 1, not a mirror
        m = [axes.to_softsub(e) for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
        det = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
               + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
        self.assertEqual(det, 1)

    def test_rotations_map_like_the_points_they_move(self):
        rnd = random.Random(2)
        for _ in range(200):
            deg = tuple(rnd.uniform(-180, 180) for _ in range(3))
            r_b = axes.euler_xyz_to_matrix(deg)
            q_s = axes.quat_to_softsub(axes.matrix_to_quat(r_b))
            r_s = axes.quat_to_matrix(q_s)
            p = tuple(rnd.uniform(-5, 5) for _ in range(3))
            moved_b = tuple(sum(r_b[i][j] * p[j] for j in range(3)) for i in range(3))
            ps = axes.to_softsub(p)
            moved_s = tuple(sum(r_s[i][j] * ps[j] for j in range(3)) for i in range(3))
            for a, b in zip(axes.to_softsub(moved_b), moved_s):
                self.assertAlmostEqual(a, b, places=9)
            # Euler XYZ (softsub's InitialRotation) back to the same matrix
            e = axes.blender_matrix_to_softsub_euler(r_b)
            for row_a, row_b in zip(axes.euler_xyz_to_matrix(e), r_s):
                for a, b in zip(row_a, row_b):
                    self.assertAlmostEqual(a, b, places=9)

    def test_xzy_euler_is_softsubs_xyz(self):
        rnd = random.Random(3)
        for _ in range(200):
            deg = tuple(rnd.uniform(-180, 180) for _ in range(3))
            rad = axes.softsub_euler_to_blender_xzy(deg)
            # Blender's mode XZY: R = Ry(y) Rz(z) Rx(x)
            r_b = axes.matmul(axes._rot(1, math.degrees(rad[1])),
                              axes.matmul(axes._rot(2, math.degrees(rad[2])), axes._rot(0, math.degrees(rad[0]))))
            q = axes.quat_to_softsub(axes.matrix_to_quat(r_b))
            for row_a, row_b in zip(axes.quat_to_matrix(q), axes.euler_xyz_to_matrix(deg)):
                for a, b in zip(row_a, row_b):
                    self.assertAlmostEqual(a, b, places=9)
            back = axes.blender_xzy_to_softsub_euler(rad)
            for a, b in zip(back, deg):
                self.assertAlmostEqual(a, b, places=9)


class CacheTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(ARGS.work, "interactionsSim")
        p = softsub("run", os.path.join(ARGS.source, "examples", "interactions.scene"), "--frames", "3",
                    "--out", cls.out)
        assert p.returncode == 0, p.stderr

    def test_sim_and_ply_agree(self):
        scan = caches.scan_sim_folder(self.out)
        self.assertEqual((scan["scene"], scan["frames"], sorted(scan["ply"])), ("interactions", [0, 1, 2, 3], [0, 1, 2, 3]))
        for f in scan["frames"]:
            sim = caches.read_sim(scan["sim"][f])
            ply = caches.read_ply(scan["ply"][f])
            self.assertEqual(sim["frame"], f)
            self.assertEqual([o["Name"] for o in sim["objects"]], ["table", "ball", "box"])
            self.assertEqual(sim["objects"][0]["Position"], (-4.0, 4.0, 0.0))  # static
            self.assertAlmostEqual(sum(x * x for x in sim["objects"][2]["Rotation"]), 1.0, places=9)
            self.assertEqual(ply["fluids"], ["honey", "oil"])
            c, k = ply["columns"], 0
            for fl in sim["fluids"]:
                p = fl["positions"]
                n = len(p) // 3
                self.assertEqual(list(p[0::3]), list(c["x"][k:k + n]))
                self.assertEqual(list(p[1::3]), list(c["y"][k:k + n]))
                self.assertEqual(list(p[2::3]), list(c["z"][k:k + n]))
                k += n
            self.assertEqual(k, ply["count"])
        verts, faces = caches.read_obj(os.path.join(self.out, "interactionsGeo", "box.obj"))
        xs = [v[0] for v in verts]
        self.assertAlmostEqual(max(xs) - min(xs), 3.0)  # Size 3 2 3

    def test_gaps_and_junk_are_refused(self):
        d = os.path.join(ARGS.work, "gap")
        shutil.rmtree(d, ignore_errors=True)
        shutil.copytree(self.out, d)
        os.remove(os.path.join(d, "interactions.0001.sim"))
        # softsub's manifests: frame 1 lacks a file it lists, so frames 0..0 are complete
        self.assertEqual(caches.scan_sim_folder(d)["frames"], [0])
        shutil.rmtree(os.path.join(d, "manifest"))  # without them, a gap is an error
        with self.assertRaisesRegex(caches.CacheError, r"not complete \(missing \[1\]\)"):
            caches.scan_sim_folder(d)
        bad = os.path.join(d, "interactions.0002.sim")
        with open(bad, "w") as f:
            f.write("<Simulation frame='2' time='0'><Fluid><Name>a</Name><ParticleNumber>2</ParticleNumber>"
                    "<Particles>0 0 0</Particles></Fluid></Simulation>")
        with self.assertRaisesRegex(caches.CacheError, "ParticleNumber 2 but 1 positions"):
            caches.read_sim(bad)
        with self.assertRaisesRegex(caches.CacheError, "no .sim frames"):
            caches.scan_sim_folder(ARGS.work)


    def test_stale_frames_of_an_earlier_run_are_not_frames(self):
        d = os.path.join(ARGS.work, "rerunSim")
        scene = os.path.join(ARGS.source, "examples", "interactions.scene")
        self.assertEqual(softsub("run", scene, "--frames", "5", "--out", d).returncode, 0)
        self.assertEqual(softsub("run", scene, "--frames", "2", "--out", d).returncode, 0)
        # the fresh run removed the first run's frames; a frame no manifest lists (an
        # older softsub's, a copy) is not one either
        self.assertFalse(os.path.exists(os.path.join(d, "interactions.0004.sim")))
        shutil.copyfile(os.path.join(d, "interactions.0001.sim"), os.path.join(d, "interactions.0004.sim"))
        scan = caches.scan_sim_folder(d)
        self.assertEqual(scan["frames"], [0, 1, 2])
        self.assertEqual(sorted(scan["ply"]), [0, 1, 2])
        # a frame whose listed file lost bytes is not complete
        with open(os.path.join(d, "ply", "interactions.0002.ply"), "ab") as f:
            f.write(b"x")
        self.assertEqual(caches.scan_sim_folder(d)["frames"], [0, 1])


class RunnerTest(unittest.TestCase):
    def test_progress_and_stop(self):
        out = os.path.join(ARGS.work, "stopSim")
        scene = os.path.join(ARGS.source, "examples", "softsub-demo.scene")
        r = runner.Runner(runner.run_command(ARGS.softsub, scene, out, "sim"), 48)
        deadline = time.time() + 60
        while r.poll() < 1 and time.time() < deadline and r.done() is None:
            time.sleep(0.01)
        self.assertGreaterEqual(r.frame, 1, "no progress line from --stats")
        self.assertGreater(r.progress(), 0.0)
        r.cancel()
        self.assertEqual(r.wait(60), 130)
        last = r.frame
        self.assertLess(last, 48, "the run was not stopped")
        self.assertEqual(r.message(), f"softsub: stopped; frames 0..{last} are complete")
        self.assertEqual(caches.scan_sim_folder(out)["frames"], list(range(last + 1)))

    def test_errors_carry_the_simulators_message(self):
        bad = os.path.join(ARGS.work, "bad.scene")
        with open(bad, "w") as f:
            f.write("<Scene><Fluid><Name>x</Name><Viscosity>-1</Viscosity><Particles>0 0 0</Particles></Fluid></Scene>")
        r = runner.Runner(runner.run_command(ARGS.softsub, bad, os.path.join(ARGS.work, "badSim")), 1)
        self.assertEqual(r.wait(60), 2)
        self.assertRegex(r.message(), r"^softsub: error: .*bad.scene:1: Fluid 'x'/Viscosity: -1 is out of range")
        with self.assertRaisesRegex(runner.RunnerError, "cannot start '/nonexistent/softsub'"):
            runner.Runner(["/nonexistent/softsub", "run"], 1)

    def test_warnings_reach_the_user(self):
        # An unstable setting: softsub warns and runs; the message says so.
        scene = os.path.join(ARGS.work, "warn.scene")
        with open(scene, "w") as f:
            f.write("<Scene><Simulation><Substeps>1</Substeps><Frames>1</Frames></Simulation><Fluid><Name>x</Name>"
                    "<Amplitude>100000</Amplitude><MaximumForce>1000000</MaximumForce>"
                    "<Particles>0 1 0 1.1 1 0</Particles></Fluid></Scene>")
        r = runner.Runner(runner.run_command(ARGS.softsub, scene, os.path.join(ARGS.work, "warnSim"), "sim"), 1)
        self.assertEqual(r.wait(60), 0)
        self.assertEqual(len(r.warnings()), 1, r.stderr_lines)
        self.assertRegex(r.message(), r"^softsub: done, frames 0\.\.1; 1 warning: warning: .*x / x unstable at 1 substeps")


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
