#!/usr/bin/python3
"""Bad input to `ballast study --dry-run`, field by field (issue 29): every way a user
might get a scene or a study file wrong is accepted or refused with a message, never
a crash, a hang or a file written.

Run by ctest with the path of the ballast binary as the only argument:
    /usr/bin/python3 tests/cli/test_input_mutations.py build/study/ballast
"""
import json
import os
import tempfile
import unittest

import binary
from binary import ballast

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "cases", "box_test", "smoke.json")
MIXED = os.path.join(HERE, "..", "data", "study", "mixed.json")


class EveryFieldMutated(unittest.TestCase):
    """Each leaf of the smoke scene and of mixed.json made wrong as a user might (another
    type, negative, zero, huge, missing), each object given an unknown key, and each
    file cut short: `ballast study --dry-run` accepts (exit 0) or refuses (exit 2,
    naming the key), never crashes or hangs, and writes nothing."""

    MISSING = object()
    MUTATIONS = (
        ("another type", lambda v: 12.5 if isinstance(v, str) else "text"),
        ("negative", lambda v: -abs(v) - 1 if isinstance(v, (int, float)) else None),
        ("zero", lambda v: 0 if isinstance(v, (int, float)) else None),
        ("huge", lambda v: 1e308 if isinstance(v, (int, float)) else None),
        ("missing", lambda v: EveryFieldMutated.MISSING),
    )

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    @staticmethod
    def leaves(node, path=()):
        if isinstance(node, dict):
            for k, v in node.items():
                yield from EveryFieldMutated.leaves(v, path + (k,))
        elif isinstance(node, list):
            for i, v in enumerate(node):
                yield from EveryFieldMutated.leaves(v, path + (i,))
        else:
            yield path, node

    @staticmethod
    def objects(node, path=()):
        if isinstance(node, dict):
            yield path
            for k, v in node.items():
                yield from EveryFieldMutated.objects(v, path + (k,))
        elif isinstance(node, list):
            for i, v in enumerate(node):
                yield from EveryFieldMutated.objects(v, path + (i,))

    @staticmethod
    def changed(doc, path, value):
        out = json.loads(json.dumps(doc))
        parent = out
        for k in path[:-1]:
            parent = parent[k]
        if value is EveryFieldMutated.MISSING:
            del parent[path[-1]]
        else:
            parent[path[-1]] = value
        return out

    def dry_run(self, scene_text, study_text, what, key):
        folder = tempfile.mkdtemp(dir=self.tmp.name)
        with open(os.path.join(folder, "s.json"), "w") as f:
            f.write(scene_text)
        with open(os.path.join(folder, "study.json"), "w") as f:
            f.write(study_text)
        out = os.path.join(folder, "out.h5")
        r = ballast("study", os.path.join(folder, "study.json"), "--dry-run", "-o", out,
                    timeout=60)
        self.assertIn(r.returncode, (0, 2), f"{what}: {r.stderr}")
        if r.returncode == 2:
            self.assertIn("error:", r.stderr, what)
            if key is not None:
                self.assertIn(str(key), r.stderr, what)
        self.assertEqual(sorted(os.listdir(folder)), ["s.json", "study.json"], what)
        return r.returncode

    def test_every_field_of_the_scene_and_the_study(self):
        with open(SCENE) as f:
            scene = json.load(f)
        with open(MIXED) as f:
            plan = json.load(f)
        plan["scene"] = "s.json"
        docs = {"scene": scene, "study": plan}
        refused = 0
        for which, doc in docs.items():
            def texts(variant):
                other = {**docs, which: variant}
                return json.dumps(other["scene"]), json.dumps(other["study"])
            for path, value in self.leaves(doc):
                for name, mutate in self.MUTATIONS:
                    new = mutate(value)
                    if new is None:
                        continue
                    what = f"{which} /{'/'.join(map(str, path))} {name}"
                    # The message names the key (or, for a list entry, its list); a
                    # missing key may be refused for what its absence makes of the
                    # rest (two samples alike), which the message names instead.
                    key = (None if name == "missing" else
                           next(k for k in reversed(path) if isinstance(k, str)))
                    refused += self.dry_run(*texts(self.changed(doc, path, new)), what,
                                            key) == 2
            for path in self.objects(doc):
                what = f"{which} /{'/'.join(map(str, path))} unknown key"
                self.assertEqual(self.dry_run(*texts(self.changed(doc, path + ("bogus",), 1)),
                                              what, "bogus"), 2, what)
            cut = json.dumps(doc)[: len(json.dumps(doc)) // 2]
            scene_text, study_text = texts(doc)
            if which == "scene":
                scene_text = cut
            else:
                study_text = cut
            self.assertEqual(self.dry_run(scene_text, study_text, f"{which} cut short", None), 2)
        # 108 of the 138 field mutations are refused. Accepted: a missing key that has a
        # default, a zero seed, and a huge box or sleeper height (runs take them: the
        # lid and the sleeper's top are positions only; test_faults.py runs one). The
        # count guards against checks that go missing.
        self.assertGreaterEqual(refused, 108)



if __name__ == "__main__":
    binary.main()
