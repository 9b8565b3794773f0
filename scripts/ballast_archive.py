"""Reading Ballast's box-test archives with h5py: single runs and studies.

Two kinds, told apart by the root attribute `format`:
  "ballast-run"    `ballast run SCENE.json -o RUN.h5`: one run under /run and the
                   scene (after --set overrides) as root attribute scene_json
                   (layout: study/archive/run_archive.hpp)
  "ballast-study"  `ballast study STUDY.json -o ARCHIVE.h5`: one group /runs/<id> per
                   run with the same content as /run, plus attributes status ("ok" or
                   "failed"), message, sample, params (JSON text), a clumps/ group with
                   the clump templates of clump runs (dataset names of
                   study/archive/clump_archive.hpp) and particles/displacement_{peak,end}
                   (docs/ARCHIVE.md)

    with open_archive("results/default.h5") as archive:
        for run in archive.select():          # runs with status ok, in study order
            run.id, run.label, run.shape, run.is_clumps, run.attrs, run.params
            run.data("series/sleeper_force")  # a numpy array, SI units
            run.displacement("peak")          # [N, 3] m, from the start of loading

Every problem is an ArchiveError whose message names the file, the run and the path.
"""
import json
import sys

import h5py

FORMATS = {"ballast-run": "run", "ballast-study": "study"}

# Study parameter keys that change a clump preset (docs/STUDY.md, "Parameter keys").
CLUMP_KEYS = ("directions", "p", "n", "balls_per_direction", "c", "d3", "edge_balls",
              "virtual_sphere_factor", "adjacency")

# The zones of the top layer (group zones/, newer archives): particles whose centre lies
# under the sleeper's footprint, and the others.
ZONES = ("beneath", "beside")

# Scene defaults for the values the figures need (docs/BOX_TEST.md): a scene file may
# leave any key out, and then runs with these.
SCENE_DEFAULTS = {
    ("box", "length"): 0.7, ("box", "width"): 0.3, ("box", "height"): 0.45,
    ("sleeper", "length"): 0.25, ("sleeper", "height"): 0.1,
    ("sleeper", "preload"): 3000.0, ("sleeper", "peak_load"): 40000.0,
    ("particles", "shape"): "spheres", ("particles", "diameter"): 0.03625,
}


class ArchiveError(Exception):
    """An archive that cannot be read as a ballast archive, or lacks what was asked."""


def _plain(value):
    """An HDF5 attribute as a Python value (strings decoded, numpy scalars unwrapped)."""
    if isinstance(value, bytes):
        return value.decode()
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    return value


def _attributes(obj):
    return {k: _plain(v) for k, v in obj.attrs.items()}


def _json_attribute(attrs, name, where):
    if name not in attrs or attrs[name] == "":
        return None
    try:
        return json.loads(attrs[name])
    except json.JSONDecodeError as e:
        raise ArchiveError(f"{where}: attribute {name} is not valid JSON ({e})") from None


def safe_name(text):
    """Text as a file-name fragment: letters, digits and . _ + - (as run ids are)."""
    return "".join(ch if ch.isalnum() or ch in "._+-" else "_" for ch in text)


class Run:
    """One box-test run: a /run or /runs/<id> group and what describes it."""

    def __init__(self, archive, run_id, group):
        self.archive = archive
        self.group = group
        self.where = f"{archive.path}: run '{run_id}'"
        self.attrs = _attributes(group)
        self.status = str(self.attrs.get("status", "ok"))
        self.message = str(self.attrs.get("message", ""))
        self.sample = str(self.attrs.get("sample", ""))
        self.params = _json_attribute(self.attrs, "params", self.where) or {}
        # The run's own scene if it carries one, else the archive's (base) scene.
        self.scene = _json_attribute(self.attrs, "scene_json", self.where) or archive.scene
        self.shape = self._shape()
        # A preset with changed clump parameters is no longer the paper's sample.
        self.clump_overrides = (any(k in self.params for k in CLUMP_KEYS)
                                or bool((self.scene or {}).get("particles", {}).get("clump")))
        self.is_clumps = (self.shape != "spheres"
                          or int(self.attrs.get("balls", 0)) > int(self.attrs.get("bodies", 0)))
        if archive.kind == "study":
            self.id = run_id
        else:  # a single run is named after its scene and shape: smoke-table2_sample1
            self.id = safe_name(f"{self.attrs.get('scene', 'run')}-{self.shape}")
        shown = safe_name(self.shape) in self.id or (self.sample and self.sample in self.id)
        self.label = self.id if shown else f"{self.id} ({self.shape})"

    def _shape(self):
        if "shape" in self.params:
            return str(self.params["shape"])
        if any(k in self.params for k in CLUMP_KEYS):
            return "clumps"  # clump parameters without a preset: ClumpParams' defaults
        if "shape" in self.attrs:
            return str(self.attrs["shape"])
        return str(self.scene_value("particles", "shape"))

    def scene_value(self, section, key):
        """A scene setting: the run's attribute `<section>_<key>` if it has one, else
        the scene JSON, else the scene default."""
        name = f"{section}_{key}"
        if name in self.attrs:
            return self.attrs[name]
        if self.scene is not None and key in self.scene.get(section, {}):
            return self.scene[section][key]
        return SCENE_DEFAULTS[(section, key)]

    @property
    def loaded(self):
        return bool(int(self.attrs.get("loaded", 0)))

    def has(self, path):
        return path in self.group

    def data(self, path):
        """The dataset at `path` inside the run, as a numpy array."""
        if path not in self.group:
            raise ArchiveError(f"{self.where} has no dataset {path}")
        obj = self.group[path]
        if not isinstance(obj, h5py.Dataset):
            raise ArchiveError(f"{self.where}: {path} is a group, not a dataset")
        return obj[()]

    def attribute(self, name, path=""):
        """Attribute `name` of the run (or of the group at `path` inside it)."""
        if path and path not in self.group:
            raise ArchiveError(f"{self.where} has no group {path}")
        obj = self.group[path] if path else self.group
        if name not in obj.attrs:
            raise ArchiveError(f"{self.where} has no attribute {name}"
                               + (f" on {path}" if path else ""))
        return _plain(obj.attrs[name])

    def optional(self, name, path=""):
        """Attribute `name` of the run (or of the group at `path`), or None where the
        archive lacks it: for fields that newer archives add and older ones do not have."""
        if path and path not in self.group:
            return None
        obj = self.group[path] if path else self.group
        return _plain(obj.attrs[name]) if name in obj.attrs else None

    def zone(self, zone):
        """The attributes of zones/<zone> (newer archives) with their means left out when
        the zone holds no particle (they are undefined then); None without the group."""
        path = f"zones/{zone}"
        if path not in self.group:
            return None
        attrs = _attributes(self.group[path])
        if "count" in attrs and int(attrs["count"]) == 0:
            return {"count": 0}
        return attrs

    def displacement(self, stage):
        """Per-particle displacement [N, 3] (m) from the start of loading to `stage`,
        "peak" or "end": the study's dataset, else positions subtracted."""
        if stage not in ("peak", "end"):
            raise ValueError(f"stage {stage!r} (allowed: 'peak', 'end')")
        if self.has(f"particles/displacement_{stage}"):
            return self.data(f"particles/displacement_{stage}")
        return self.data(f"particles/position_{stage}") - self.data("particles/position_start")

    def clump_templates(self):
        """The run's clump templates as a clump_render sample, or None when the archive
        holds none (single-run files, sphere runs)."""
        if "clumps" not in self.group:
            return None
        c = self.group["clumps"]
        try:
            return {
                "attrs": _attributes(c),
                "radius": c["balls/radius"][()],
                "offset": c["balls/offset"][()],
                "first": c["clumps/first_ball"][()],
                "count": c["clumps/ball_count"][()],
                "sphericity": c["shape/sphericity"][()] if "shape/sphericity" in c else None,
            }
        except KeyError as e:
            raise ArchiveError(f"{self.where}: clumps/ lacks a template dataset ({e})") from None


class Archive:
    """An open archive of either kind; use as a context manager or call close()."""

    def __init__(self, path):
        self.path = path
        try:
            self.file = h5py.File(path, "r")
        except FileNotFoundError:
            raise ArchiveError(f"{path}: no such file") from None
        except OSError as e:
            raise ArchiveError(f"{path}: not a ballast archive: not an HDF5 file ({e})") from None
        self.attrs = _attributes(self.file)
        fmt = self.attrs.get("format")
        if fmt not in FORMATS:
            self.file.close()
            raise ArchiveError(
                f"{path}: not a ballast archive: root attribute format = {fmt!r} (allowed: "
                "'ballast-run' from `ballast run -o`, 'ballast-study' from `ballast study -o`)")
        self.kind = FORMATS[fmt]
        self.scene = _json_attribute(self.attrs, "scene_json", path)
        holder = "run" if self.kind == "run" else "runs"
        if holder not in self.file or not isinstance(self.file[holder], h5py.Group):
            self.file.close()
            raise ArchiveError(f"{path}: a {fmt} archive without its /{holder} group "
                               "(damaged or unfinished)")
        if self.kind == "run":
            self._runs = [Run(self, "run", self.file["run"])]
        else:
            groups = self.file["runs"]
            names = sorted(groups, key=lambda n: (int(groups[n].attrs.get("index", 0)), n))
            self._runs = [Run(self, n, groups[n]) for n in names]

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.file.close()

    def runs(self):
        """Every run, failed ones included, in study order."""
        return list(self._runs)

    def run(self, run_id):
        for r in self._runs:
            if r.id == run_id:
                return r
        raise ArchiveError(f"{self.path}: no run '{run_id}' (runs: "
                           f"{', '.join(r.id for r in self._runs) or 'none'})")

    def select(self, ids=None, log=sys.stderr):
        """The runs with status ok, all or those named in `ids` (in that order); a run
        not ok is left out with a line on `log`."""
        chosen = self.runs() if ids is None else [self.run(i) for i in ids]
        ok = []
        for r in chosen:
            if r.status == "ok":
                ok.append(r)
            elif log is not None:
                print(f"{self.path}: skipping run '{r.id}': status {r.status}"
                      + (f" ({r.message})" if r.message else ""), file=log)
        return ok


def open_archive(path):
    return Archive(path)


def add_run_arguments(parser):
    """The arguments of every script that reads an archive: ARCHIVE and --runs."""
    parser.add_argument("archive", help="a ballast study or run archive (HDF5)")
    parser.add_argument("--runs", help="comma-separated run ids (default: every run)")


def chosen_runs(archive, runs_option, purpose):
    """The ok runs named by a --runs value (all when None); an ArchiveError when none."""
    ids = [i for i in runs_option.split(",") if i] if runs_option else None
    runs = archive.select(ids)
    if not runs:
        raise ArchiveError(f"{archive.path}: no run with status ok to {purpose}")
    return runs
