"""What a new user trips over, from Python (issue "No surprises"): misspelled
long options in switch strings, exponents in switch numbers, settings with no
effect as warnings, and quality() with the command line's --stats=json keys.
Every mesh produced goes through deltamesh.validate."""
import json
import os
import subprocess
import sys
import unittest
import warnings

import deltamesh

SQUARE = dict(vertices=[[0, 0], [1, 0], [1, 1], [0, 1]], segments=[[0, 1], [1, 2], [2, 3], [3, 0]])


class SwitchStrings(unittest.TestCase):
    def test_misspelled_long_option_is_unknown_with_a_suggestion(self):
        with self.assertRaisesRegex(ValueError, r"unknown option --cdtt \(did you mean --cdt\?\)"):
            deltamesh.triangulate(SQUARE, "p --cdtt=ct")
        with self.assertRaisesRegex(ValueError, r"unknown option --time-limt \(did you mean --time-limit\?\)"):
            deltamesh.triangulate(SQUARE, "pq --time-limt=5")
        # A command-line option about files is not a misspelling.
        with self.assertRaisesRegex(ValueError, "--output .* not available in deltamesh.triangulate"):
            deltamesh.triangulate(SQUARE, "p --output=x.msh")

    def test_exponent_is_explained_with_the_number_to_type(self):
        with self.assertRaisesRegex(ValueError, "no exponent.*type -a0.001"):
            deltamesh.triangulate(SQUARE, "pa1e-3")


class NoSilentNoOps(unittest.TestCase):
    def test_settings_without_effect_warn_once(self):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh = deltamesh.triangulate(SQUARE, "pY --steiner=circumcenter")
        deltamesh.validate(mesh)
        texts = [str(w.message) for w in caught]
        self.assertEqual(sum("-Y has no effect" in t for t in texts), 1, texts)
        self.assertEqual(sum("--steiner has no effect" in t for t in texts), 1, texts)
        # With refinement -Y means something: no such warning.
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            deltamesh.validate(deltamesh.triangulate(SQUARE, "pq30a0.1Y"))
        self.assertFalse([w for w in caught if "has no effect" in str(w.message)])


class QualityKeys(unittest.TestCase):
    def test_quality_is_the_stats_json_object(self):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            mesh = deltamesh.triangulate(SQUARE, "pq30a0.05")
        deltamesh.validate(mesh)
        q = deltamesh.quality(mesh, min_angle=30, max_area=0.05)
        self.assertEqual(q["schema"], "deltamesh-stats")
        self.assertEqual(q["schema_version"], 1)
        self.assertGreaterEqual(q["min_angle_deg"], 30)
        self.assertEqual(q["below_angle"], 0)
        self.assertEqual(sum(q["angle_histogram_deg10"]), 3 * len(mesh["triangles"]))
        # The names before the schema still work.
        self.assertEqual(q["min_angle"], q["min_angle_deg"])
        self.assertEqual(q["angle_histogram"], q["angle_histogram_deg10"])

    @unittest.skipUnless(os.environ.get("DELTAMESH_CLI"), "DELTAMESH_CLI not set")
    def test_same_keys_as_the_command_line(self):
        import tempfile
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "sq.poly"), "w") as f:
                f.write("4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n")
            out = subprocess.run([os.environ["DELTAMESH_CLI"], "-pq30a0.05", "--stats=json", "sq"], cwd=d,
                                 capture_output=True, text=True, check=True).stdout
            cli = json.loads(out)
            mesh = deltamesh.read(os.path.join(d, "sq.1.node"))
        deltamesh.validate(mesh)
        q = deltamesh.quality(mesh, min_angle=30, max_area=0.05)
        self.assertEqual(set(cli) - {"refine"}, set(q) - {"min_angle", "max_angle", "angle_histogram"})
        self.assertEqual(cli["triangles"], q["triangles"])
        self.assertAlmostEqual(cli["min_angle_deg"], q["min_angle_deg"], places=9)


if __name__ == "__main__":
    unittest.main()
