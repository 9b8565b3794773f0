"""Packing files in Python, for the peer generators (the format: cases/packing_file.hpp).

    x y z r          spheres, one body per line
    body x y z r     clumps: consecutive lines with the same body id form one clump

SI units, '#' comments. Written by `ballast run --export-packing` with 17 significant
digits; this reader keeps them as Python floats (IEEE doubles, parsed exactly) and the
generators write them back with repr(), which is also exact.
"""


class PackingError(ValueError):
    pass


class Packing:
    """Balls (centre, radius) grouped into bodies: bodies[k] is a list of ball indices."""

    def __init__(self, source, clumps, centres, radii, bodies):
        self.source = source
        self.clumps = clumps
        self.centres = centres
        self.radii = radii
        self.bodies = bodies

    @property
    def balls(self):
        return len(self.radii)

    def mean_radius(self):
        return sum(self.radii) / len(self.radii)

    def max_radius(self):
        return max(self.radii)

    def body_extent(self):
        """Largest distance from a body's mean ball centre to the far side of a ball, m."""
        extent = 0.0
        for members in self.bodies:
            n = len(members)
            mean = [sum(self.centres[k][d] for k in members) / n for d in range(3)]
            for k in members:
                dist = sum((self.centres[k][d] - mean[d]) ** 2 for d in range(3)) ** 0.5
                extent = max(extent, dist + self.radii[k])
        return extent


def read_packing(path):
    centres, radii, bodies = [], [], []
    columns, current, closed = None, None, {}
    with open(path) as f:
        for number, text in enumerate(f, start=1):
            fields = text.split("#", 1)[0].split()
            if not fields:
                continue
            where = f"{path}:{number}"
            if columns is None:
                if len(fields) not in (4, 5):
                    raise PackingError(f"{where}: {len(fields)} columns (allowed: 4 or 5)")
                columns = len(fields)
            elif len(fields) != columns:
                raise PackingError(f"{where}: {len(fields)} columns, the file started with {columns}")
            try:
                x, y, z, r = (float(v) for v in fields[-4:])
            except ValueError:
                raise PackingError(f"{where}: not a number in {fields}") from None
            if not r > 0.0:
                raise PackingError(f"{where}: radius {r} (allowed: > 0 m)")
            if columns == 5:
                body = int(fields[0])
                if body != current:
                    if body in closed:
                        raise PackingError(f"{where}: body {body} reappears (started on line "
                                           f"{closed[body]})")
                    closed[body] = number
                    current = body
                    bodies.append([])
                bodies[-1].append(len(radii))
            else:
                bodies.append([len(radii)])
            centres.append((x, y, z))
            radii.append(r)
    if not radii:
        raise PackingError(f"{path}: no particles")
    return Packing(path, columns == 5, centres, radii, bodies)
