"""Drawing one clump as shaded spheres, for galleries like Fig. 7 of Lu & McDowell (2007).

Shared by scripts/clump_gallery.py (clump archives, `ballast clump -o`) and
scripts/figures.py (the clump templates of a study archive's runs). A *sample* is a
dict of the clump archive's datasets (study/archive/clump_archive.hpp):

    radius [N], offset [N, 3] (m, principal frame), first [M], count [M],
    sphericity [M] or None, attrs (the archive's attributes, may be empty)
"""
import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

LIGHT = np.array([0.4, -0.5, 0.8]) / np.linalg.norm([0.4, -0.5, 0.8])
BASE_COLOUR = np.array([0.62, 0.60, 0.55])  # grey-brown, like granite ballast

# Attributes that describe the generator's parameters (ClumpParams), for the caption.
PARAMETER_KEYS = ("directions", "p", "c", "d3", "edge_balls", "adjacency")


def typical_clump(sample):
    """The clump whose ball count is nearest the sample mean and, among those, whose
    sphericity is nearest the sample's mean sphericity (the first such clump when the
    sample has no shape statistics)."""
    counts = sample["count"].astype(float)
    nearest = np.abs(counts - counts.mean())
    candidates = np.flatnonzero(nearest == nearest.min())
    sph = sample.get("sphericity")
    if sph is None:
        return int(candidates[0])
    return int(candidates[np.argmin(np.abs(sph[candidates] - sph.mean()))])


def sphere_polygons(centres, radii, n_lat=18, n_lon=32):
    """Quads of every ball's surface, minus those hidden inside another ball, shaded."""
    lat = np.linspace(0.0, np.pi, n_lat + 1)
    lon = np.linspace(0.0, 2.0 * np.pi, n_lon + 1)
    polys, colours = [], []
    for i, (c, r) in enumerate(zip(centres, radii)):
        for a in range(n_lat):
            for b in range(n_lon):
                corners = []
                for t, p in ((lat[a], lon[b]), (lat[a], lon[b + 1]), (lat[a + 1], lon[b + 1]),
                             (lat[a + 1], lon[b])):
                    corners.append(c + r * np.array([np.sin(t) * np.cos(p),
                                                     np.sin(t) * np.sin(p), np.cos(t)]))
                corners = np.array(corners)
                mid = corners.mean(axis=0)
                # Drop a quad only when all its corners are inside one other ball: it can
                # never be seen. Partly covered quads stay (the depth sort hides them).
                inside = np.linalg.norm(centres[None, :, :] - corners[:, None, :], axis=2)
                inside = np.all(inside < radii[None, :] * 0.999, axis=0)
                inside[i] = False
                if np.any(inside):
                    continue
                normal = (mid - c) / np.linalg.norm(mid - c)
                shade = 0.45 + 0.55 * max(0.0, float(normal @ LIGHT))
                polys.append(corners)
                colours.append(np.append(BASE_COLOUR * shade, 1.0))
    return polys, colours


def parameter_caption(attrs):
    """One line of generator parameters, or None when the attributes do not hold them."""
    if not all(k in attrs for k in PARAMETER_KEYS):
        return None
    return (f"{int(attrs['directions'])} dirs, p {float(attrs['p']):.1f}, "
            f"c {float(attrs['c']):.1f}R, D3 {float(attrs['d3']):.1f}R, "
            f"{int(attrs['edge_balls'])} edge ball(s), {attrs['adjacency']}")


def draw_clump(ax, sample, index, title, caption=None):
    """Draws clump `index` of `sample` on a 3-D axis, in mm, seen from a fixed angle."""
    first, n = int(sample["first"][index]), int(sample["count"][index])
    centres = sample["offset"][first:first + n] * 1e3  # mm
    radii = sample["radius"][first:first + n] * 1e3
    polys, colours = sphere_polygons(centres, radii)
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="none"))
    if "virtual_radius" in sample["attrs"]:
        half = 0.8 * float(sample["attrs"]["virtual_radius"]) * 1e3
    else:  # the clump's own extent
        half = 1.05 * float(np.max(np.linalg.norm(centres, axis=1) + radii))
    for axis in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        axis(-half, half)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=22, azim=35)
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)
    if caption:
        ax.text2D(0.5, -0.02, caption, transform=ax.transAxes, ha="center", fontsize=7)
