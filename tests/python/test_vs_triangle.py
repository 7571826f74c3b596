#!/usr/bin/env python3
"""Quality triangulation of planar straight-line graphs, delmesh against Shewchuk's Triangle.

delmesh is called through its C API (ctypes on target/release/libdelmesh.so, or the library
named by DELMESH_LIB); Triangle through the PyPI package `triangle` (a test-only dependency:
the test skips, saying so, when it is missing). Cases: a capital A with its counter as a hole,
a thin rhombus, a square with a square hole, and the .poly / .edg files of the shared 2D data
directory when present (DELMESH_DATA_2D, default ../shared/data/2d beside the repository).

For each case and angle bound (25 and 30 degrees), on delmesh's output:
- every triangle counter-clockwise and with an empty circumcircle among its neighbours
  (every interior edge locally Delaunay), every sub-segment strongly Delaunay (some circle
  through its ends has every other vertex of the mesh strictly outside: it is in every
  Delaunay triangulation of the vertices);
- delmesh's triangle count at most Triangle's + 15% (Triangle's default constrained Delaunay
  mode, switches -pq), on each generated case and over all cases together; Triangle's
  conforming Delaunay mode (-pDq, every triangle Delaunay, as delmesh's are) is printed beside;
- delmesh leaves no more triangles below the bound away from small input angles than
  Triangle does (a triangle is at a small input angle when its shortest edge joins two points
  on two segments that meet at an angle below 60 degrees).
Counts and smallest angles are printed for both. Exit status 0 when every check passes (or
the test is skipped), 1 otherwise.

Run: python3 tests/python/test_vs_triangle.py   (after cargo build --release)
"""
import ctypes
import math
import os
import sys
from fractions import Fraction

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BOUNDS = (25.0, 30.0)
SLACK = 1.15


class Options2d(ctypes.Structure):
    _fields_ = [
        ("mode", ctypes.c_int),
        ("min_angle_degrees", ctypes.c_double),
        ("max_area", ctypes.c_double),
        ("holes", ctypes.POINTER(ctypes.c_double)),
        ("n_holes", ctypes.c_size_t),
        ("regions", ctypes.POINTER(ctypes.c_double)),
        ("n_regions", ctypes.c_size_t),
        ("split_crossing_segments", ctypes.c_int),
    ]


MODE_QUALITY = 2


def load_delmesh():
    path = os.environ.get("DELMESH_LIB", os.path.join(ROOT, "target", "release", "libdelmesh.so"))
    lib = ctypes.CDLL(path)
    vp = ctypes.c_void_p
    lib.delmesh_triangulate_2d.argtypes = [
        ctypes.POINTER(ctypes.c_double), ctypes.c_size_t, ctypes.POINTER(ctypes.c_uint32),
        ctypes.c_size_t, ctypes.POINTER(Options2d), ctypes.POINTER(vp)]
    lib.delmesh_triangulate_2d.restype = ctypes.c_int
    for name, res in [("delmesh_mesh_vertex_count", ctypes.c_size_t),
                      ("delmesh_mesh_triangle_count", ctypes.c_size_t),
                      ("delmesh_mesh_edge_count", ctypes.c_size_t),
                      ("delmesh_mesh_vertices", ctypes.POINTER(ctypes.c_double)),
                      ("delmesh_mesh_triangles", ctypes.POINTER(ctypes.c_uint32)),
                      ("delmesh_mesh_edges", ctypes.POINTER(ctypes.c_uint32))]:
        getattr(lib, name).argtypes = [vp]
        getattr(lib, name).restype = res
    lib.delmesh_mesh_free.argtypes = [vp]
    lib.delmesh_mesh_free.restype = None
    lib.delmesh_last_error_message.argtypes = []
    lib.delmesh_last_error_message.restype = ctypes.c_char_p
    return lib


def delmesh_quality(lib, points, segments, holes, angle):
    """(vertices, triangles, sub-segments) of delmesh's quality triangulation."""
    xy = (ctypes.c_double * (2 * len(points)))(*[c for p in points for c in p])
    seg = (ctypes.c_uint32 * max(1, 2 * len(segments)))(*[i for s in segments for i in s])
    hole_array = (ctypes.c_double * max(1, 2 * len(holes)))(*[c for h in holes for c in h])
    options = Options2d(MODE_QUALITY, angle, 0.0, hole_array, len(holes), None, 0)
    mesh = ctypes.c_void_p()
    status = lib.delmesh_triangulate_2d(xy, len(points), seg, len(segments), ctypes.byref(options),
                                        ctypes.byref(mesh))
    if status != 0:
        raise RuntimeError(f"delmesh_triangulate_2d: status {status}: "
                           f"{lib.delmesh_last_error_message().decode()}")
    try:
        nv = lib.delmesh_mesh_vertex_count(mesh)
        nt = lib.delmesh_mesh_triangle_count(mesh)
        ne = lib.delmesh_mesh_edge_count(mesh)
        v, t, e = (lib.delmesh_mesh_vertices(mesh), lib.delmesh_mesh_triangles(mesh),
                   lib.delmesh_mesh_edges(mesh))
        vertices = [(v[3 * i], v[3 * i + 1]) for i in range(nv)]
        triangles = [(t[3 * i], t[3 * i + 1], t[3 * i + 2]) for i in range(nt)]
        edges = [(e[2 * i], e[2 * i + 1]) for i in range(ne)]
    finally:
        lib.delmesh_mesh_free(mesh)
    return vertices, triangles, edges


def triangle_quality(tr, points, segments, holes, angle, switches):
    data = {"vertices": points, "segments": segments}
    if holes:
        data["holes"] = holes
    out = tr.triangulate(data, f"{switches}q{angle:g}")
    triangles = out["triangles"].tolist() if "triangles" in out else []
    return [tuple(p) for p in out["vertices"].tolist()], [tuple(t) for t in triangles]


# ---------------------------------------------------------------- geometry

def smallest_angle(v, t):
    """Smallest angle of triangle t (degrees) and its shortest edge."""
    p = [v[i] for i in t]
    sq = lambda a, b: (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2
    lengths = [sq(p[1], p[2]), sq(p[2], p[0]), sq(p[0], p[1])]
    k = min(range(3), key=lambda i: lengths[i])
    x, y = lengths[(k + 1) % 3], lengths[(k + 2) % 3]
    c = max(-1.0, min(1.0, (x + y - lengths[k]) / (2.0 * math.sqrt(x * y))))
    return math.degrees(math.acos(c)), (p[(k + 1) % 3], p[(k + 2) % 3])


def on_segment(p, a, b):
    len2 = (b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2
    t = ((p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1])) / len2
    h = abs((p[0] - a[0]) * (b[1] - a[1]) - (p[1] - a[1]) * (b[0] - a[0])) / len2
    return -1e-12 <= t <= 1 + 1e-12 and h < 1e-9


def small_angle_pairs(points, segments):
    """(apex, far end 1, far end 2) of every two segments meeting below 60 degrees."""
    out = []
    for i, s in enumerate(segments):
        for r in segments[i + 1:]:
            common = set(s) & set(r)
            if len(common) != 1:
                continue
            z = common.pop()
            f1, f2 = (s[0] if s[1] == z else s[1]), (r[0] if r[1] == z else r[1])
            pz, p1, p2 = points[z], points[f1], points[f2]
            u, w = (p1[0] - pz[0], p1[1] - pz[1]), (p2[0] - pz[0], p2[1] - pz[1])
            c = (u[0] * w[0] + u[1] * w[1]) / (math.hypot(*u) * math.hypot(*w))
            if c > 0.5:
                out.append((pz, p1, p2))
    return out


def at_small_input_angle(edge, pairs):
    p, q = edge
    for z, a, b in pairs:
        on = lambda x, g: x == z or on_segment(x, z, g)
        if (on(p, a) and on(q, b)) or (on(p, b) and on(q, a)):
            return True
    return False


def summary(v, tris, bound, pairs):
    """(count, smallest angle, bad triangles away from small input angles, bad at them)."""
    worst, away, near = 180.0, 0, 0
    for t in tris:
        angle, edge = smallest_angle(v, t)
        worst = min(worst, angle)
        if angle < bound:
            if at_small_input_angle(edge, pairs):
                near += 1
            else:
                away += 1
    return len(tris), worst, away, near


def orient(a, b, c):
    """Exact sign of the orientation of a, b, c."""
    a, b, c = [(Fraction(p[0]), Fraction(p[1])) for p in (a, b, c)]
    d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (d > 0) - (d < 0)


def incircle(a, b, c, d):
    """Exact sign: d inside the circle of the counter-clockwise a, b, c."""
    rows = []
    for p in (a, b, c):
        x, y = Fraction(p[0]) - Fraction(d[0]), Fraction(p[1]) - Fraction(d[1])
        rows.append((x, y, x * x + y * y))
    (a0, a1, a2), (b0, b1, b2), (c0, c1, c2) = rows
    det = a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0)
    return (det > 0) - (det < 0)


def strongly_delaunay(v, a, b, used):
    """Whether some circle through v[a] and v[b] has every other used vertex strictly outside
    (then [a b] is in every Delaunay triangulation): with c the vertex left of (a, b) seeing it
    under the widest angle, no vertex right of it is inside or on the circle (a, b, c)."""
    pa, pb = v[a], v[b]
    left, right = [], []
    for q in used:
        if q in (a, b):
            continue
        side = orient(pa, pb, v[q])
        (left if side > 0 else right if side < 0 else []).append(q)
    if not left or not right:
        return True
    best = left[0]
    for q in left[1:]:
        if incircle(pa, pb, v[best], v[q]) > 0:
            best = q
    return all(incircle(pa, pb, v[best], v[q]) < 0 for q in right)


def check_delmesh(v, tris, edges):
    """Why delmesh's output is invalid, or None."""
    opposite = {}
    for t in tris:
        if orient(v[t[0]], v[t[1]], v[t[2]]) <= 0:
            return f"triangle {t} is not counter-clockwise"
        for k in range(3):
            opposite[(t[k], t[(k + 1) % 3])] = t[(k + 2) % 3]
    for (a, b), c in opposite.items():
        d = opposite.get((b, a))
        if d is not None and incircle(v[a], v[b], v[c], v[d]) > 0:
            return f"edge ({a}, {b}) is not locally Delaunay"
    used = sorted({i for t in tris for i in t} | {i for e in edges for i in e})
    for a, b in edges:
        if not strongly_delaunay(v, a, b, used):
            return f"sub-segment ({a}, {b}) is not strongly Delaunay (in every Delaunay triangulation)"
    return None


# ---------------------------------------------------------------- cases

def letter_a():
    """A capital A with serifs, its counter a hole."""
    outer = [(0.0, 0.0), (1.4, 0.0), (1.4, 0.25), (1.05, 0.3), (1.5, 1.5), (3.5, 1.5),
             (3.95, 0.3), (3.6, 0.25), (3.6, 0.0), (5.0, 0.0), (5.0, 0.25), (4.7, 0.35),
             (2.95, 6.0), (2.05, 6.0), (0.3, 0.35), (0.0, 0.25)]
    counter = [(1.75, 2.1), (3.25, 2.1), (2.5, 4.5)]
    n = len(outer)
    segments = [(i, (i + 1) % n) for i in range(n)]
    segments += [(n, n + 1), (n + 1, n + 2), (n + 2, n)]
    return "letter A", outer + counter, segments, [(2.5, 3.0)]


def thin_rhombus():
    return "thin rhombus", [(0.0, 0.0), (4.0, 0.6), (8.0, 0.0), (4.0, -0.6)], \
        [(0, 1), (1, 2), (2, 3), (3, 0)], []


def square_with_hole():
    points = [(0, 0), (4, 0), (4, 4), (0, 4), (1.5, 1.5), (2.5, 1.5), (2.5, 2.5), (1.5, 2.5)]
    segments = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4)]
    return "square with a hole", [tuple(map(float, p)) for p in points], segments, [(2.0, 2.0)]


def read_poly(path):
    """Triangle .poly: points, segments (0-based), holes."""
    lines = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].split()
            if line:
                lines.append(line)
    n = int(lines[0][0])
    first = int(lines[1][0])
    points = [(float(l[1]), float(l[2])) for l in lines[1:1 + n]]
    m = int(lines[1 + n][0])
    segments = [(int(l[1]) - first, int(l[2]) - first) for l in lines[2 + n:2 + n + m]]
    rest = lines[2 + n + m:]
    holes = []
    if rest:
        h = int(rest[0][0])
        holes = [(float(l[1]), float(l[2])) for l in rest[1:1 + h]]
    return points, segments, holes


def read_edg(path):
    """CGAL .edg: a count, then one segment per line as x1 y1 x2 y2; points merged."""
    with open(path) as f:
        numbers = f.read().split()
    n = int(numbers[0])
    index, points, segments = {}, [], []
    for k in range(n):
        x1, y1, x2, y2 = map(float, numbers[1 + 4 * k:5 + 4 * k])
        ends = []
        for p in ((x1, y1), (x2, y2)):
            if p not in index:
                index[p] = len(points)
                points.append(p)
            ends.append(index[p])
        if ends[0] != ends[1] and (ends[0], ends[1]) not in segments and (ends[1], ends[0]) not in segments:
            segments.append(tuple(ends))
    return points, segments, []


def data_cases():
    directory = os.environ.get("DELMESH_DATA_2D", os.path.join(os.path.dirname(ROOT), "shared", "data", "2d"))
    if not os.path.isdir(directory):
        print(f"SKIP  data cases: no directory {directory}")
        return []
    cases = []
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if name.endswith(".poly"):
            cases.append((name,) + read_poly(path))
        elif name.endswith(".edg"):
            cases.append((name,) + read_edg(path))
    return cases


def main():
    try:
        import triangle as tr
    except ImportError:
        print("SKIP  test_vs_triangle: the Python package `triangle` is not installed "
              "(pip install triangle)")
        print("0 passed, 0 failed, 1 skipped")
        return 0
    lib = load_delmesh()
    passed = failed = 0

    def check(ok, message):
        nonlocal passed, failed
        print(("PASS  " if ok else "FAIL  ") + message)
        passed, failed = passed + bool(ok), failed + (not ok)

    cases = [letter_a(), thin_rhombus(), square_with_hole()]
    n_generated = len(cases)
    cases += data_cases()
    totals = {}
    for index, (name, points, segments, holes) in enumerate(cases):
        generated = index < n_generated
        pairs = small_angle_pairs(points, segments)
        for bound in BOUNDS:
            label = f"{name} at {bound:g} degrees"
            try:
                v, tris, edges = delmesh_quality(lib, points, segments, holes, bound)
            except RuntimeError as e:
                check(False, f"{label}: {e}")
                continue
            why = check_delmesh(v, tris, edges)
            check(why is None, f"{label}: delmesh output valid, Delaunay, sub-segments admissible"
                  + ("" if why is None else f": {why}"))
            tv, ttris = triangle_quality(tr, points, segments, holes, bound, "p")
            dv, dtris = triangle_quality(tr, points, segments, holes, bound, "pD")
            ours, theirs = summary(v, tris, bound, pairs), summary(tv, ttris, bound, pairs)
            conforming = summary(dv, dtris, bound, pairs)
            print(f"      {label:34s} triangles delmesh {ours[0]:5d}  Triangle {theirs[0]:5d} "
                  f"(-D {conforming[0]:5d})  smallest angle {ours[1]:6.2f} / {theirs[1]:6.2f} "
                  f"({conforming[1]:6.2f})  below the bound away from / at small input angles "
                  f"{ours[2]}/{ours[3]}, {theirs[2]}/{theirs[3]} ({conforming[2]}/{conforming[3]})")
            t = totals.setdefault(bound, [0, 0, 0])
            t[0], t[1], t[2] = t[0] + ours[0], t[1] + theirs[0], t[2] + conforming[0]
            if generated:
                check(ours[0] <= SLACK * theirs[0],
                      f"{label}: delmesh's {ours[0]} triangles at most Triangle's {theirs[0]} + 15%")
            check(ours[2] <= theirs[2],
                  f"{label}: no more bad triangles away from small input angles than Triangle "
                  f"({ours[2]} / {theirs[2]})")
    for bound, (ours, theirs, conforming) in sorted(totals.items()):
        check(ours <= SLACK * theirs,
              f"all cases at {bound:g} degrees: delmesh's {ours} triangles at most Triangle's "
              f"{theirs} + 15% (Triangle -D: {conforming})")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
