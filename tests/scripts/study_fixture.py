"""A small study archive assembled with h5py from single-run files, for testing the
scripts in scripts/ against the study layout (docs/ARCHIVE.md) without `ballast study`:
each run's /run group is copied to /runs/<id>, with the attributes a study run carries
(status, message, sample, params, index), the clump templates of a `ballast clump -o`
archive under clumps/, and particles/displacement_{peak,end}.
"""
import json

import h5py


def add_templates(run_group, templates_path):
    """Copies a clump archive's balls/, clumps/ and shape/ groups and its attributes
    into run_group/clumps."""
    clumps = run_group.create_group("clumps")
    with h5py.File(templates_path, "r") as src:
        for name in ("balls", "clumps", "shape"):
            src.copy(src[name], clumps, name=name)
        for k, v in src.attrs.items():
            clumps.attrs[k] = v


def make_study(path, base_scene_json, runs, failed=()):
    """Writes a ballast-study archive at `path`.

    runs:   dicts with id, run_file (a `ballast run -o` file), sample, params (dict),
            and optionally templates (a `ballast clump -o` file)
    failed: dicts with id, sample, params, message: runs recorded as failed, no data
    """
    with h5py.File(path, "w") as out:
        out.attrs["format"] = "ballast-study"
        out.attrs["version"] = 1
        out.attrs["scene_json"] = base_scene_json
        groups = out.create_group("runs")
        index = 0
        for spec in runs:
            with h5py.File(spec["run_file"], "r") as src:
                src.copy(src["run"], groups, name=spec["id"])
            g = groups[spec["id"]]
            p = g["particles"]
            # Run files now carry displacements and clump templates themselves; the
            # fixture adds them only to files that lack them.
            start = p["position_start"][()]
            for name, at in (("displacement_peak", "position_peak"), ("displacement_end", "position_end")):
                if name not in p:
                    p[name] = p[at][()] - start
            if spec.get("templates") and "clumps" not in g:
                add_templates(g, spec["templates"])
            _describe(g, index, "ok", "", spec)
            index += 1
        for spec in failed:
            _describe(groups.create_group(spec["id"]), index, "failed", spec["message"], spec)
            index += 1


def _describe(group, index, status, message, spec):
    group.attrs["index"] = index
    group.attrs["status"] = status
    group.attrs["message"] = message
    group.attrs["sample"] = spec["sample"]
    group.attrs["params"] = json.dumps(spec["params"], sort_keys=True, separators=(",", ":"))
