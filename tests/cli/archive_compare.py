"""Bit-for-bit comparison of HDF5 groups, apart from named timing fields.

Used by the study tests: a run's results must not depend on --jobs/--threads, on being
resumed, on being a shard, or on being run by `ballast study` rather than `ballast run`.
What legitimately differs is when and how fast it ran.
"""
import h5py
import numpy as np

# Attributes that say when, how fast or on how many threads a run ran.
TIMING_ATTRIBUTES = {"started", "finished", "wall_seconds", "seconds", "threads", "created"}
# The log holds wall-clock seconds per stage.
TIMING_DATASETS = {"log"}


def _same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind == "f":
        return np.array_equal(a, b, equal_nan=True)
    return np.array_equal(a, b)


def differences(a, b, path="", skip_attributes=(), skip_links=()):
    """Every difference between HDF5 objects a and b (groups or datasets), as text.

    Attributes in TIMING_ATTRIBUTES or skip_attributes and links in TIMING_DATASETS or
    skip_links are not compared (at any depth)."""
    out = []
    skip_a = TIMING_ATTRIBUTES | set(skip_attributes)
    skip_l = TIMING_DATASETS | set(skip_links)
    names_a = {k for k in a.attrs if k not in skip_a}
    names_b = {k for k in b.attrs if k not in skip_a}
    for k in sorted(names_a ^ names_b):
        out.append(f"{path or '/'}: attribute {k} only in {'first' if k in names_a else 'second'}")
    for k in sorted(names_a & names_b):
        if not _same_value(a.attrs[k], b.attrs[k]):
            out.append(f"{path or '/'}: attribute {k}: {a.attrs[k]!r} != {b.attrs[k]!r}")
    if isinstance(a, h5py.Dataset) or isinstance(b, h5py.Dataset):
        if not (isinstance(a, h5py.Dataset) and isinstance(b, h5py.Dataset)):
            return out + [f"{path}: a dataset and a group"]
        if not _same_value(a[()], b[()]):
            out.append(f"{path}: dataset values differ")
        return out
    links_a = {k for k in a.keys() if k not in skip_l}
    links_b = {k for k in b.keys() if k not in skip_l}
    for k in sorted(links_a ^ links_b):
        out.append(f"{path}/{k}: only in {'first' if k in links_a else 'second'}")
    for k in sorted(links_a & links_b):
        out += differences(a[k], b[k], f"{path}/{k}", skip_attributes, skip_links)
    return out


def run_differences(file_a, file_b):
    """Differences between the /runs of two study archives."""
    with h5py.File(file_a, "r") as a, h5py.File(file_b, "r") as b:
        return differences(a["runs"], b["runs"], "/runs")
