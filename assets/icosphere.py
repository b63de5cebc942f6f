"""The unit icosphere both generated scenes use (material-box's glass sphere,
veach-mis's lights): an icosahedron whose triangles are split in four
`level` times, every vertex pushed onto the sphere. Faces wind outwards."""
import math


def _unit(p):
    n = math.sqrt(sum(c * c for c in p))
    return tuple(c / n for c in p)


def icosphere(level):
    """(vertices, faces): unit vectors and index triples."""
    t = (1 + 5 ** 0.5) / 2
    v = [_unit(p) for p in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
                            (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache, nf = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                v.append(_unit(tuple((v[a][i] + v[b][i]) / 2 for i in range(3))))
                cache[key] = len(v) - 1
            return cache[key]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    return v, f
