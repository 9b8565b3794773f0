"""Synthetic ballast-study archives written with h5py, for testing the scripts in
scripts/ without the C++ build or a simulation: every attribute and dataset that
compare.py and figures.py read (docs/ARCHIVE.md), with made-up numbers, in the older
layout or with the fields newer archives add (percentiles of the contact forces, the
sleeper's contacts, near contacts before loading, zones/).

    write_study(path, [run(...), run(...)], scene=SMOKE, new_fields=True)
    write_single(path, run(...), scene=SMOKE, new_fields=True)   # `ballast run -o`

A run is a dict from run(): its id, sample, shape, replicate, bodies and any of the
run attributes or zone values to set (SI, as in an archive); everything else is drawn
from a generator seeded by the run's index, so an archive is the same every time.
"""
import json

import h5py
import numpy as np

SMOKE = {"name": "smoke", "particles": {"shape": "spheres", "count": 40, "diameter": 0.03625},
         "box": {"length": 0.35, "width": 0.15, "height": 0.3},
         "sleeper": {"length": 0.125, "height": 0.05, "preload": 750, "peak_load": 10000}}
FULL = {"name": "spheres", "particles": {"shape": "spheres", "count": 1936, "diameter": 0.03625},
        "box": {"length": 0.7, "width": 0.3, "height": 0.45},
        "sleeper": {"length": 0.25, "height": 0.1, "preload": 3000, "peak_load": 40000}}

PARTICLES = 40  # datasets per run, whatever `bodies` says
GAPS = (0.0, 1e-6, 1e-4, 1e-3)  # near_gap, m


def run(run_id, sample, shape, replicate=1, bodies=PARTICLES, balls=None, zones=None,
        seating="equilibrium", cycles=None, **attrs):
    """A run to write. zones: {"beneath": (dz_peak, dz_end), "beside": (...)} in m;
    seating: how its preload stage ended; cycles: (trough, resilient), each settlement's
    array over the load cycles in m, for a cycles/ group (runs of several cycles)."""
    return {"id": run_id, "sample": sample, "shape": shape, "replicate": replicate,
            "seating": seating, "cycles": cycles,
            "bodies": bodies, "balls": balls or (bodies if shape == "spheres" else 10 * bodies),
            "zones": zones or {"beneath": (-2e-4, -1e-4), "beside": (1e-4, 2e-4)},
            "attrs": attrs}


def _dataset(group, name, value, units):
    group[name] = value
    group[name].attrs["units"] = units


def _contacts(group, rng, position, stage, new_fields, spec):
    """contacts/<stage>: 60 ball-ball contacts between random particles."""
    c = group.create_group(f"contacts/{stage}")
    i, j = rng.integers(0, len(position), 60), rng.integers(0, len(position), 60)
    force = rng.uniform(1.0, 100.0 if stage != "peak" else 1000.0, 60)
    _dataset(c, "from", position[i], "m")
    _dataset(c, "to", position[j], "m")
    _dataset(c, "force", force, "N")
    c.attrs.update({"ball_contacts": 60, "wall_contacts": 12, "coordination": 3.5,
                    "max_force": force.max(), "mean_force": force.mean()})
    if not new_fields:
        return
    c.attrs.update({"force_p50": np.percentile(force, 50), "force_p90": np.percentile(force, 90),
                    "force_p99": np.percentile(force, 99), "sleeper_contacts": 9,
                    "sleeper_bodies": 7, "sleeper_force_max": 900.0, "sleeper_force_p50": 300.0,
                    "sleeper_force_total": 3000.0})
    if stage == "before":
        _dataset(c, "near_gap", np.array(GAPS), "m")
        c["near_pairs"] = np.array([60, 64, 80, 120], dtype=np.int64)
        c["near_wall"] = np.array([12, 12, 14, 20], dtype=np.int64)
        c.attrs["intra_clump_pairs"] = 0 if spec["shape"] == "spheres" else 16 * spec["balls"]


def _zones(group, spec, surface):
    z = group.create_group("zones")
    z.attrs.update({"surface": surface, "layer_depth": 0.05})
    for name, (peak, end) in spec["zones"].items():
        g = z.create_group(name)
        g.attrs.update({"count": 12, "dz_peak": peak, "dz_end": end,
                        "rotation_loading_deg": 0.5, "rotation_unloading_deg": 0.2,
                        "rotation_cycle_deg": 0.6})


def _cycles(group, spec):
    """cycles/ as the box test writes it (docs/ARCHIVE.md), with the slope the C++
    fit gives: least squares of the trough on log10 N."""
    trough, resilient = (np.asarray(x, dtype=float) for x in spec["cycles"])
    n = np.arange(1, len(trough) + 1)
    c = group.create_group("cycles")
    slope = np.polyfit(np.log10(n), trough, 1)[0] if len(n) >= 2 else 0.0
    c.attrs.update({"count": len(trough), "settlement_log_slope": slope})
    for name, value, units in (("cycle", n.astype(np.int32), "1"),
                               ("settlement_trough", trough, "m"),
                               ("settlement_peak", trough + resilient, "m"),
                               ("resilient_settlement", resilient, "m")):
        _dataset(c, name, value, units)
    group.attrs["permanent_settlement"] = trough[-1]
    group.attrs["resilient_settlement"] = resilient[-1]


def _run_group(parent, name, index, spec, scene, new_fields):
    rng = np.random.default_rng(index + 1)
    g = parent.create_group(name)
    box = scene["box"]
    start = rng.uniform((0.02, 0.02, 0.02), (box["length"] - 0.02, box["width"] - 0.02, 0.15),
                        (PARTICLES, 3))
    shift = rng.normal(0.0, 2e-4, (PARTICLES, 3))
    g.attrs.update({"id": spec["id"], "index": index, "sample": spec["sample"],
                    "replicate": spec["replicate"],
                    "params": json.dumps({"shape": spec["shape"]}, separators=(",", ":")),
                    "seed": np.uint64(1000 + index), "status": "ok", "message": "",
                    "scene_json": json.dumps(scene), "scene": scene["name"],
                    "bodies": spec["bodies"], "balls": spec["balls"], "dt": 2e-7,
                    "dt_critical": 3e-7, "loaded": 1, "porosity_grid": rng.uniform(0.38, 0.45),
                    "bed_height": 0.16, "settlement_peak": 1e-3, "permanent_settlement": 5e-4,
                    "resilient_settlement": 5e-4, "max_force_error": 10.0,
                    "rms_force_error": 5.0, "max_displacement_peak": 2e-3,
                    "max_displacement_after": 2.5e-3, "wall_seconds": 12.0, "threads": 1})
    for phase in ("loading", "unloading", "cycle"):
        g.attrs[f"rotation_{phase}_mean_deg"] = 0.5
        g.attrs[f"rotation_{phase}_max_deg"] = 5.0
    g.attrs.update(spec["attrs"])
    p = g.create_group("particles")
    for name, value in (("position_start", start), ("position_peak", start + shift),
                        ("position_end", start + 1.2 * shift), ("displacement_peak", shift),
                        ("displacement_end", 1.2 * shift)):
        _dataset(p, name, value, "m")
    for phase in ("loading", "unloading", "cycle"):
        _dataset(p, f"rotation_{phase}", rng.uniform(0.0, 5.0, PARTICLES), "deg")
    p["shape_index"] = np.arange(PARTICLES, dtype=np.int64)
    for stage in ("before", "peak", "after"):
        _contacts(g, rng, start, stage, new_fields, spec)
    t = np.linspace(0.0, 0.03, 50)
    force = scene["sleeper"]["peak_load"] * np.sin(np.pi * t / 0.03) + 300.0
    for name, value, units in (("time", t, "s"), ("target_force", force, "N"),
                               ("sleeper_force", force, "N"),
                               ("settlement", 1e-3 * np.sin(np.pi * t / 0.03), "m")):
        _dataset(g.require_group("series"), name, value, units)
    for k, (stage, ended, ratio) in enumerate((("compact", "equilibrium", 4e-3),
                                               ("preload", spec["seating"], 4.5e-3))):
        st = g.require_group("stages").create_group(f"{k + 1:02d}_{stage}")
        st.attrs.update({"ended_by": ended, "unbalanced": ratio, "steps": 1000})
    if new_fields:
        _zones(g, spec, 0.16)
    if spec["cycles"] is not None:
        _cycles(g, spec)


def write_study(path, runs, scene=SMOKE, new_fields=True, failed=()):
    """A ballast-study archive at `path` with the runs (from run()), all ok, and the
    ids in `failed` recorded as failed runs."""
    with h5py.File(path, "w") as f:
        f.attrs.update({"format": "ballast-study", "format_version": 1, "study_name": "synthetic",
                        "scene_json": json.dumps(scene)})
        groups = f.create_group("runs")
        for index, spec in enumerate(runs):
            _run_group(groups, spec["id"], index, spec, scene, new_fields)
        for k, run_id in enumerate(failed):
            g = groups.create_group(run_id)
            g.attrs.update({"id": run_id, "index": len(runs) + k, "sample": "broken",
                            "status": "failed", "message": "blew up", "params": "{}"})
    return path


def write_single(path, spec, scene=SMOKE, new_fields=True):
    """A ballast-run archive (`ballast run -o`) at `path`: the run under /run, without the
    attributes only a study's runs carry, and the scene (with the run's shape) at the root."""
    scene = dict(scene, particles=dict(scene["particles"], shape=spec["shape"]))
    with h5py.File(path, "w") as f:
        f.attrs.update({"format": "ballast-run", "scene_json": json.dumps(scene)})
        _run_group(f, "run", 0, spec, scene, new_fields)
        for name in ("id", "index", "sample", "replicate", "params", "status", "message",
                     "scene_json"):
            del f["run"].attrs[name]
    return path
