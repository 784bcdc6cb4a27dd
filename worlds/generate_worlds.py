#!/usr/bin/env python3
"""Generates the world files in this folder (run: python3 worlds/generate_worlds.py).

Walls are described as room rectangles and door gaps on axis-aligned lines; collinear pieces are
merged (a wall shared by two rooms exists once), the ends of a merged run are extended by half the
thickness so outside corners close, and door gaps are cut out afterwards, so a door is exactly the
gap it names. Ground-truth room polygons are the free space inside the wall faces.
"""
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


class Builder:
    def __init__(self, name, height=2.8, thickness=0.15):
        self.name, self.h, self.t = name, height, thickness
        self.lines = {}  # ('h', y) or ('v', x) -> [(a, b)]
        self.gaps = {}
        self.walls, self.boxes, self.rooms = [], [], []
        self.floors, self.ceilings = [], []
        self.trajectory, self.sensor = None, {"model": "vlp16", "rate_hz": 10,
                                              "mount_height_m": 0.5,
                                              "range_noise_std_m": 0.01, "seed": 1}

    # -- walls --------------------------------------------------------------------------------
    def line(self, orient, c, a, b):
        self.lines.setdefault((orient, c), []).append((min(a, b), max(a, b)))

    def rect(self, x0, y0, x1, y1):
        self.line('h', y0, x0, x1), self.line('h', y1, x0, x1)
        self.line('v', x0, y0, y1), self.line('v', x1, y0, y1)

    def door(self, orient, c, a, b):
        """A gap from a to b along line ('h', y=c) or ('v', x=c)."""
        assert abs(b - a) >= 0.8, "doors are at least 0.8 m wide"
        self.gaps.setdefault((orient, c), []).append((min(a, b), max(a, b)))

    def wall(self, p, q, z_min=0.0, z_max=None, thickness=None, reflectivity=None):
        w = {"from": list(p), "to": list(q), "z_min": z_min,
             "z_max": self.h if z_max is None else z_max,
             "thickness": self.t if thickness is None else thickness}
        if reflectivity is not None:
            w["reflectivity"] = reflectivity
        self.walls.append(w)

    def _line_walls(self):
        out = []
        for (orient, c), ivs in sorted(self.lines.items()):
            ivs = sorted(ivs)
            merged = [list(ivs[0])]
            for a, b in ivs[1:]:
                if a <= merged[-1][1] + 1e-9:
                    merged[-1][1] = max(merged[-1][1], b)
                else:
                    merged.append([a, b])
            for a, b in merged:
                pieces = [[a - self.t / 2, b + self.t / 2]]
                for ga, gb in sorted(self.gaps.get((orient, c), [])):
                    nxt = []
                    for pa, pb in pieces:
                        if gb <= pa or ga >= pb:
                            nxt.append([pa, pb])
                            continue
                        if ga - pa > 1e-6:
                            nxt.append([pa, ga])
                        if pb - gb > 1e-6:
                            nxt.append([gb, pb])
                    pieces = nxt
                for pa, pb in pieces:
                    if orient == 'h':
                        out.append(((pa, c), (pb, c)))
                    else:
                        out.append(((c, pa), (c, pb)))
        return out

    # -- rooms, furniture ----------------------------------------------------------------------
    def room(self, rid, kind, x0, y0, x1, y1, walls=True, shrink=None):
        """A rectangular room; `shrink` per side (w, s, e, n) defaults to half a wall."""
        if walls:
            self.rect(x0, y0, x1, y1)
        s = [self.t / 2] * 4 if shrink is None else shrink
        self.polygon_room(rid, kind, [[x0 + s[0], y0 + s[1]], [x1 - s[2], y0 + s[1]],
                                      [x1 - s[2], y1 - s[3]], [x0 + s[0], y1 - s[3]]])

    def polygon_room(self, rid, kind, poly):
        self.rooms.append({"id": rid, "kind": kind, "polygon": poly})

    def open_floor(self, rid, x1, y1, north_rooms):
        """The ground-truth room of the open floor of an x1 x y1 building (walls at its edges):
        the free space inside the walls, minus the rooms along its north wall, each (x0, x1,
        y0), returned as a polygon that keeps half a wall from every wall."""
        h = self.t / 2
        tops = []  # (x0, x1, top) along the north side, west to east
        x = 0.0
        for rx0, rx1, ry0 in sorted(north_rooms):
            if rx0 > x:
                tops.append((x, rx0, y1))
            tops.append((rx0, rx1, ry0))
            x = rx1
        if x < x1:
            tops.append((x, x1, y1))
        poly = [[h, h], [x1 - h, h]]
        for k in range(len(tops) - 1, -1, -1):  # east to west along the north side
            a, b, top = tops[k]
            # At a step the wall between belongs to the lower part's room: both corners keep
            # half a wall from it on the side of the higher part.
            east = b + h if k < len(tops) - 1 and tops[k + 1][2] > top else b - h
            west = a - h if k > 0 and tops[k - 1][2] > top else a + h
            poly += [[east, top - h], [west, top - h]]
        self.polygon_room(rid, "room", poly)

    def box(self, cx, cy, z0, sx, sy, sz, yaw=0.0, refl=None):
        b = {"center": [cx, cy, z0 + sz / 2], "size": [sx, sy, sz], "yaw_deg": yaw}
        if refl is not None:
            b["reflectivity"] = refl
        self.boxes.append(b)

    def table(self, x0, y0, x1, y1, h=0.75, legs=True):
        self.box((x0 + x1) / 2, (y0 + y1) / 2, h - 0.04, x1 - x0, y1 - y0, 0.04)
        if legs:
            for lx in (x0 + 0.05, x1 - 0.05):
                for ly in (y0 + 0.05, y1 - 0.05):
                    self.box(lx, ly, 0.0, 0.05, 0.05, h - 0.04)

    def floor_rect(self, x0, y0, x1, y1, z=0.0, ceiling=True):
        poly = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
        self.floors.append({"polygon": poly, "z": z})
        if ceiling:
            self.ceilings.append({"polygon": poly, "z": z + self.h})

    def path(self, waypoints, speed=0.8, laps=1, corner=0.5):
        self.trajectory = {"waypoints": waypoints, "speed_mps": speed, "laps": laps,
                           "corner_radius_m": corner, "jitter_deg": 0.3, "jitter_z_m": 0.004}

    # -- output --------------------------------------------------------------------------------
    def write(self, rotate_deg=0.0):
        walls = [dict(w) for w in self.walls]
        for p, q in self._line_walls():
            walls.append({"from": list(p), "to": list(q), "z_min": 0.0, "z_max": self.h,
                          "thickness": self.t})
        th = math.radians(rotate_deg)
        c, s = math.cos(th), math.sin(th)

        def rot(p):
            return [round(c * p[0] - s * p[1], 4), round(s * p[0] + c * p[1], 4)] + \
                [round(v, 4) for v in p[2:]]

        for w in walls:
            w["from"], w["to"] = rot(w["from"]), rot(w["to"])
        boxes = []
        for b in self.boxes:
            b = dict(b)
            b["center"] = rot(b["center"])
            b["size"] = [round(v, 4) for v in b["size"]]
            b["yaw_deg"] = round(b["yaw_deg"] + rotate_deg, 4)
            boxes.append(b)
        world = {
            "name": self.name,
            "walls": walls,
            "boxes": boxes,
            "floors": [{**f, "polygon": [rot(p) for p in f["polygon"]]} for f in self.floors],
            "ceilings": [{**f, "polygon": [rot(p) for p in f["polygon"]]} for f in self.ceilings],
            "rooms": [{**r, "polygon": [rot(p) for p in r["polygon"]]} for r in self.rooms],
            "trajectory": {**self.trajectory,
                           "waypoints": [rot(p) for p in self.trajectory["waypoints"]]},
            "sensor": self.sensor,
        }
        path = os.path.join(HERE, self.name + ".json")
        with open(path, "w") as f:
            f.write(dump(world) + "\n")
        print(path, len(walls), "walls", len(boxes), "boxes")


def dump(world):
    """Compact JSON: one element of each list per line."""
    parts = ["{"]
    keys = list(world.keys())
    for i, k in enumerate(keys):
        v = world[k]
        sep = "," if i + 1 < len(keys) else ""
        if isinstance(v, list) and v:
            parts.append(' "%s": [' % k)
            parts.append(",\n".join("  " + json.dumps(e) for e in v))
            parts.append(" ]" + sep)
        else:
            parts.append(' "%s": %s%s' % (k, json.dumps(v), sep))
    return "\n".join(parts) + "\n}"


# ---------------------------------------------------------------------------------------------
def smoke():
    b = Builder("smoke")
    b.room("room_a", "room", 0, 0, 5, 4)
    b.room("room_b", "room", 5, 0, 10, 4)
    b.room("corridor", "corridor", 0, 4, 10, 6)
    b.door('v', 5, 1.5, 2.5)
    b.door('h', 4, 2.0, 3.0)
    b.door('h', 4, 7.0, 8.0)
    b.floor_rect(0, 0, 10, 6)
    b.box(0.6, 3.2, 0, 0.8, 1.2, 0.9)
    b.box(9.2, 0.8, 0, 1.0, 1.0, 1.5, yaw=20)
    b.table(1.0, 0.4, 2.6, 1.2)
    b.path([[2, 2], [4.2, 2], [6, 2], [7.5, 2.8], [7.5, 5], [2.5, 5], [2.5, 3.0], [2, 2]],
           speed=1.3)
    b.write()


def lab_room():
    b = Builder("lab_room", height=3.0)
    b.room("lab", "room", 0, 0, 12, 9)
    b.floor_rect(0, 0, 12, 9)
    # Central island of four tables with legs, chairs around them.
    for x in (4.0, 6.0):
        for y in (3.3, 4.6):
            b.table(x, y, x + 1.9, y + 1.2)
    for x in (4.5, 5.7, 6.9):
        b.box(x, 3.0, 0, 0.45, 0.45, 0.45, yaw=10 * x)
        b.box(x + 0.3, 6.1, 0, 0.45, 0.45, 0.45, yaw=-12 * x)
    # Desks with monitors along the south wall, shelves along the north wall.
    for x in (1.0, 3.4, 5.8, 8.2):
        b.box(x + 1.0, 0.5, 0, 2.0, 0.8, 0.75)
        b.box(x + 1.0, 0.45, 0.75, 0.6, 0.08, 0.4)
    for x in (0.8, 2.4, 4.0, 7.6, 9.2):
        b.box(x + 0.7, 8.6, 0, 1.4, 0.45, 2.0)
    # Cabinets and a robot cell on the east wall, a pillar, a cart on the west side.
    b.box(11.6, 2.0, 0, 0.6, 1.6, 1.2)
    b.box(11.4, 5.0, 0, 1.0, 2.2, 1.6)
    b.box(11.6, 7.5, 0, 0.6, 1.0, 2.2)
    b.box(6.0, 8.0, 0, 0.5, 0.5, 3.0)
    b.box(0.6, 4.5, 0, 0.7, 1.1, 1.0, yaw=5)
    b.path([[2.2, 2.0], [9.8, 2.0], [9.8, 7.1], [2.2, 7.1], [2.2, 2.0]], speed=1.2, laps=3)
    b.write()


def corridor_loop():
    b = Builder("corridor_loop")
    n, w, t = 40.0, 2.4, b.t
    b.rect(0, 0, n, n)
    b.rect(w, w, n - w, n - w)
    b.floor_rect(0, 0, n, n)
    h = t / 2
    b.polygon_room("corridor_south", "corridor", [[h, h], [n - h, h], [n - h, w - h], [h, w - h]])
    b.polygon_room("corridor_north", "corridor",
                   [[h, n - w + h], [n - h, n - w + h], [n - h, n - h], [h, n - h]])
    b.polygon_room("corridor_west", "corridor", [[h, w - h], [w - h, w - h], [w - h, n - w + h],
                                                 [h, n - w + h]])
    b.polygon_room("corridor_east", "corridor", [[n - w + h, w - h], [n - h, w - h],
                                                 [n - h, n - w + h], [n - w + h, n - w + h]])
    # Door frames on both walls, radiators, benches, notice boards: something to hold on to.
    rnd = random.Random(9)
    for k in range(6):
        s = 4.0 + k * 6.2 + rnd.uniform(-0.8, 0.8)
        f = w - h - 0.04  # door frames stand 8 cm out of the block's wall
        b.box(s, f, 0.0, 1.1, 0.08, 2.1)                      # south corridor
        b.box(n - s, n - f, 0.0, 1.1, 0.08, 2.1)              # north corridor
        b.box(f, n - s, 0.0, 0.08, 1.1, 2.1)                  # west corridor
        b.box(n - f, s, 0.0, 0.08, 1.1, 2.1)                  # east corridor
        b.box(s + 2.5, h + 0.06, 0.3, 1.6, 0.12, 0.6)         # radiators, outer walls
        b.box(h + 0.25, s + 2.8, 0.0, 0.45, 1.5, 0.45)        # benches
        b.box(n - h - 0.25, n - s - 2.8, 0.0, 0.45, 1.2, 1.1)  # cabinets
    for k in range(5):
        b.box(10 + 6 * k, n - h - 0.04, 1.2, 1.0, 0.05, 0.7)  # notice boards, north outer wall
    c = w / 2
    b.path([[6, c], [n - c, c], [n - c, n - c], [c, n - c], [c, c], [6, c]], speed=0.9)
    b.write()


def long_corridor():
    b = Builder("long_corridor")
    y0, y1 = 10.0, 12.4
    b.room("corridor", "corridor", 0, y0, 45, y1)
    rooms = [("office_1", 0, 2, 10, y0), ("office_2", 10, 2, 20, y0), ("lab_3", 20, 2, 30, y0),
             ("meeting_4", 5, y1, 17, 20.4), ("office_5", 30, y1, 42, 20.4),
             ("hall_6", 45, 6, 53, 16)]
    for rid, x0, ya, x1, yb in rooms:
        b.room(rid, "room", x0, ya, x1, yb)
    b.floor_rect(0, 2, 45, 20.4)
    b.floor_rect(45, 6, 53, 16)
    for xc in (6.6, 15.0, 25.0):
        b.door('h', y0, xc - 0.6, xc + 0.6)
    for xc in (11.0, 36.0):
        b.door('h', y1, xc - 0.6, xc + 0.6)
    b.door('v', 45, 10.6, 11.8)
    # Furniture: desks along the outer walls, a meeting table, lab benches, shelves.
    for x0, x1 in ((0, 10), (10, 20)):
        for k in range(3):
            b.box(x0 + 1.5 + 3 * k, 2.6, 0, 1.6, 0.8, 0.75)
        b.box(x0 + 0.5, 6.0, 0, 0.5, 2.0, 1.9)
    b.table(10.0, 16.0, 12.0, 17.0)
    for x in (21.5, 26.5):
        b.box(x + 0.5, 3.0, 0, 2.4, 0.9, 0.9)
    b.box(29.5, 4.0, 0, 0.6, 3.0, 2.0)
    for k in range(3):
        b.box(32 + 3.5 * k, 19.8, 0, 1.8, 0.8, 0.75)
    b.box(41.4, 15.0, 0, 0.6, 2.5, 1.9)
    b.box(49.4, 11.6, 0, 0.9, 0.9, 1.0, yaw=30)
    b.box(52.4, 7.5, 0, 0.6, 2.0, 2.0)
    for x in (8, 20, 32, 44):
        b.box(x, y1 - 0.3, 0, 0.5, 0.4, 1.0)  # bins and printers in the corridor
    c = (y0 + y1) / 2

    def loop_south(xd):  # through the door at x = xd on the south side, around, back out
        return [[xd, c], [xd, 8.3], [xd + 1.6, 6.5], [xd, 4.7], [xd - 1.6, 6.5], [xd, 8.3], [xd, c]]

    def loop_north(xd):
        return [[xd, c], [xd, 14.2], [xd + 2.2, 16.5], [xd, 18.6], [xd - 2.2, 16.5], [xd, 14.2],
                [xd, c]]

    wp = [[1.5, c]] + loop_south(6.6) + loop_north(11.0) + loop_south(15.0) + loop_south(25.0) + \
        loop_north(36.0) + [[44, c], [47, c], [50.5, 8.5], [51.2, 13], [47.5, 14], [46, c],
                            [42, c]] + loop_south(15.0)
    b.path(wp, speed=0.9)
    b.write()


def large_hall():
    b = Builder("large_hall", height=3.5)
    hx0, hy0, hx1, hy1 = 10, 10, 40, 30
    b.room("hall", "room", hx0, hy0, hx1, hy1)
    rooms = [("room_s1", 10, 0, 22, 10), ("room_s2", 22, 0, 34, 10), ("room_n1", 10, 30, 24, 40),
             ("room_n2", 24, 30, 40, 40), ("room_w", 0, 12, 10, 28), ("room_e", 40, 10, 50, 22)]
    for rid, x0, y0, x1, y1 in rooms:
        b.room(rid, "room", x0, y0, x1, y1)
    b.floor_rect(10, 0, 40, 40)
    b.floor_rect(0, 12, 10, 28)
    b.floor_rect(40, 10, 50, 22)
    # Wide entrances (3 m).
    b.door('h', 10, 14.5, 17.5)
    b.door('h', 10, 26.5, 29.5)
    b.door('h', 30, 15.5, 18.5)
    b.door('h', 30, 30.5, 33.5)
    b.door('v', 10, 18.5, 21.5)
    b.door('v', 40, 14.5, 17.5)
    # Pillars in the hall, furniture in the rooms.
    for x in (17.5, 25.0, 32.5):
        for y in (15.5, 24.5):
            b.box(x, y, 0, 0.6, 0.6, 3.5)
    for x0, y0, x1, y1 in [(10, 0, 22, 10), (22, 0, 34, 10), (10, 30, 24, 40), (24, 30, 40, 40)]:
        b.box(x0 + 1.0, (y0 + y1) / 2, 0, 0.8, 3.0, 1.8)
        b.box(x1 - 1.0, (y0 + y1) / 2 + 1, 0, 0.8, 2.0, 1.0)
        b.table((x0 + x1) / 2 - 1.2, (y0 + y1) / 2 - 0.6, (x0 + x1) / 2 + 1.2,
                (y0 + y1) / 2 + 0.6, legs=False)
        b.box((x0 + x1) / 2, (y0 + y1) / 2, 0, 2.4, 1.2, 0.74)
    b.box(1.0, 20.0, 0, 0.8, 4.0, 2.0)
    b.box(49.0, 16.0, 0, 0.8, 3.0, 1.2)

    def loop(door, entry_axis, cx, cy, rx, ry):
        """Enter through `door` ((x, y) in the wall), go around the room centre, come back."""
        dx, dy = door
        inside = [dx, dy - 1.5] if entry_axis == 's' else [dx, dy + 1.5] if entry_axis == 'n' \
            else [dx - 1.5, dy] if entry_axis == 'w' else [dx + 1.5, dy]
        outside = [dx, dy + 1.5] if entry_axis == 's' else [dx, dy - 1.5] if entry_axis == 'n' \
            else [dx + 1.5, dy] if entry_axis == 'w' else [dx - 1.5, dy]
        ring = [[cx - rx, cy - ry], [cx + rx, cy - ry], [cx + rx, cy + ry], [cx - rx, cy + ry]]
        # Start the ring at the corner nearest to the door, go around once.
        k = min(range(4), key=lambda i: math.dist(ring[i], inside))
        ring = ring[k:] + ring[:k]
        return [outside, inside] + ring + [ring[0], inside, outside]

    wp = [[20, 12.5]]
    wp += loop((16, 10), 's', 16, 5, 3.0, 2.2)
    wp += loop((28, 10), 's', 28, 5, 3.0, 2.2)
    wp += [[37.5, 13]]
    wp += loop((40, 16), 'e', 45, 16, 2.2, 3.0)
    wp += [[37.5, 27.5]]
    wp += loop((32, 30), 'n', 32, 35, 3.8, 2.2)
    wp += loop((17, 30), 'n', 17, 35, 3.3, 2.2)
    wp += [[12.5, 27.5]]
    wp += loop((10, 20), 'w', 5, 20, 2.2, 4.5)
    wp += [[12.5, 12.5], [20, 12.5]]
    b.path(wp, speed=1.0, corner=0.6)
    b.write()


def open_lobby():
    b = Builder("open_lobby", height=3.2)
    t = b.t
    h = t / 2
    b.rect(0, 0, 26, 18)
    b.line('v', 12, 10, 18)
    b.line('h', 10, 12, 26)
    b.door('v', 12, 14.0, 15.2)
    # The half wall between the entrance and the storage area (1.1 m), opening at y 4.5..6.5.
    b.wall((12, 0.0), (12, 4.5), z_max=1.1, thickness=0.2)
    b.wall((12, 6.5), (12, 10.0), z_max=1.1, thickness=0.2)
    # Drop-off: a void [4, 10] x [12, 18] down to a lower level at -3.5 m, railing around it.
    floor = [[0, 0], [26, 0], [26, 18], [10, 18], [10, 12], [4, 12], [4, 18], [0, 18]]
    b.floors.append({"polygon": floor, "z": 0.0})
    b.floors.append({"polygon": [[4, 12], [10, 12], [10, 18], [4, 18]], "z": -3.5})
    b.ceilings.append({"polygon": [[0, 0], [26, 0], [26, 18], [0, 18]], "z": b.h})
    b.wall((4, 12), (10, 12), z_min=-3.5, z_max=0.0)
    b.wall((4, 12), (4, 18), z_min=-3.5, z_max=0.0)
    b.wall((10, 12), (10, 18), z_min=-3.5, z_max=0.0)
    b.wall((4, 18), (10, 18), z_min=-3.5, z_max=0.0)
    r = 0.12  # railing line, just outside the void
    for z0, z1 in ((0.95, 1.05), (0.5, 0.55)):
        b.wall((4 - r, 12 - r), (10 + r, 12 - r), z_min=z0, z_max=z1, thickness=0.05)
        b.wall((4 - r, 12 - r), (4 - r, 18 - h), z_min=z0, z_max=z1, thickness=0.05)
        b.wall((10 + r, 12 - r), (10 + r, 18 - h), z_min=z0, z_max=z1, thickness=0.05)
    for k in range(5):
        b.box(4 - r + 1.5 * k, 12 - r, 0, 0.05, 0.05, 1.05)
    for k in range(1, 5):
        b.box(4 - r, 12 - r + 1.5 * k, 0, 0.05, 0.05, 1.05)
        b.box(10 + r, 12 - r + 1.5 * k, 0, 0.05, 0.05, 1.05)
    b.polygon_room("entrance", "room", [[h, h], [11.9, h], [11.9, 18 - h], [10 + r + 0.03, 18 - h],
                                        [10 + r + 0.03, 12 - r - 0.03],
                                        [4 - r - 0.03, 12 - r - 0.03], [4 - r - 0.03, 18 - h],
                                        [h, 18 - h]])
    b.polygon_room("storage", "room", [[12.1, h], [26 - h, h], [26 - h, 10 - h], [12.1, 10 - h]])
    b.room("seminar", "room", 12, 10, 26, 18, walls=False)
    # Lobby furniture: reception desk, sofas; storage shelves; seminar tables.
    b.box(6.0, 5.0, 0, 3.0, 0.8, 1.1)
    b.box(0.6, 8.5, 0, 0.9, 2.0, 0.8)
    for x in (15.0, 18.0, 21.0, 24.0):
        b.box(x, 1.6, 0, 0.6, 2.6, 2.0)
        b.box(x, 8.6, 0, 0.6, 2.2, 2.0)
    b.box(25.3, 5.5, 0, 0.8, 1.2, 1.2)
    for x in (16.0, 20.0):
        b.table(x, 13.9, x + 2.4, 14.7, legs=False)
        b.box(x + 1.2, 14.3, 0, 2.4, 0.8, 0.72)
    b.path([[2, 2], [9.5, 2.2], [10.5, 5.5], [14, 5.5], [15.8, 4.6], [24.2, 4.6], [24.2, 6.4],
            [15.8, 6.4], [14, 5.5], [10.5, 5.5], [11, 9], [11, 14.6], [13.5, 14.6], [14.5, 11.5],
            [24, 11.5], [24, 17], [14.5, 17], [13.5, 14.6], [11, 14.6], [11, 11], [9, 10.8], [2.2, 10.8],
            [1.8, 16.5], [2.8, 16.8], [3.0, 11.5], [2, 2]], speed=0.8, laps=1, corner=0.4)
    b.write()


def cluttered_rooms():
    b = Builder("cluttered_rooms", height=3.2)
    rnd = random.Random(3)
    b.room("corridor", "corridor", 0, 10, 42, 12.4)
    b.floor_rect(0, 0, 42, 12.4)
    doors = []
    for i in range(3):
        x0 = 14.0 * i
        b.room("plant_%d" % (i + 1), "room", x0, 0, x0 + 14, 10)
        b.door('h', 10, x0 + 6.4, x0 + 7.6)
        doors.append(x0 + 7.0)
        # Wall-mounted cabinets and panels along the south, west and east walls.
        for k in range(6):
            b.box(x0 + 1.2 + 2.1 * k, 0.3, 1.3, 1.6, 0.45, 0.8)
        for y in (2.5, 5.5, 8.0):
            b.box(x0 + 0.35, y, 0.0, 0.5, 1.2, 2.0)
            b.box(x0 + 13.7, y - 0.8, 1.2, 0.45, 1.4, 0.9)
        # Pipes: horizontal runs under the ceiling, vertical drops near the walls.
        b.box(x0 + 7, 0.35, 2.6, 13.6, 0.15, 0.15)
        b.box(x0 + 7, 9.6, 2.4, 13.6, 0.2, 0.2)
        b.box(x0 + 0.3, 5, 2.8, 0.15, 9.6, 0.15)
        for x in (2.0, 5.0, 9.0, 12.0):
            b.box(x0 + x, 9.75, 0.0, 0.12, 0.12, 3.2)
        # Clutter: machines and crates in the centre island and along the walls.
        for k in range(6):
            b.box(x0 + 5.0 + rnd.uniform(0, 4), 4.3 + rnd.uniform(0, 1.4), 0,
                  rnd.uniform(0.5, 1.1), rnd.uniform(0.5, 1.0), rnd.uniform(0.4, 1.6),
                  yaw=rnd.uniform(0, 90))
        for k in range(4):
            b.box(x0 + 1.3 + rnd.uniform(0, 3) + 7.0 * (k % 2), 0.9 + rnd.uniform(0, 0.4), 0,
                  rnd.uniform(0.5, 0.9), rnd.uniform(0.4, 0.7), rnd.uniform(0.4, 1.2),
                  yaw=rnd.uniform(0, 90))
            b.box(x0 + 1.3 + rnd.uniform(0, 3) + 7.0 * (k % 2), 9.0 + rnd.uniform(-0.2, 0.1), 0,
                  rnd.uniform(0.5, 0.9), rnd.uniform(0.4, 0.7), rnd.uniform(0.4, 1.2),
                  yaw=rnd.uniform(0, 90))
    for x in (4, 18, 32):
        b.box(x, 12.0, 0, 1.0, 0.5, 1.2)
    c = 11.2
    wp = [[1.5, c]]
    for xd in doors:
        x0 = xd - 7
        wp += [[xd, c], [xd, 7.6], [x0 + 11.6, 7.4], [x0 + 11.6, 2.6], [x0 + 2.4, 2.6],
               [x0 + 2.4, 7.4], [xd, 7.6], [xd, c]]
    wp += [[40.5, c], [40.5, 10.6], [39, 10.6]]
    wp = wp[:-2] + [[40.5, c], [41.2, 11.6]]
    b.path(wp, speed=0.8, corner=0.4)
    b.write()


def construction_site():
    b = Builder("construction_site", height=2.7, thickness=0.2)
    for i in range(3):
        b.room("room_s%d" % (i + 1), "room", 5 * i, 0, 5 * i + 5, 4)
        b.room("room_n%d" % (i + 1), "room", 5 * i, 6, 5 * i + 5, 10)
        b.door('h', 4, 5 * i + 2.0, 5 * i + 3.0)
        b.door('h', 6, 5 * i + 2.0, 5 * i + 3.0)
    b.room("corridor", "corridor", 0, 4, 15, 6)
    b.line('v', 0, 4, 6)
    b.line('v', 15, 4, 6)
    for x in (5, 10):
        b.door('v', x, 1.5, 2.5)
        b.door('v', x, 7.5, 8.5)
    b.floor_rect(0, 0, 15, 10)
    rnd = random.Random(5)
    # Pallets, material stacks and columns.
    for i in range(3):
        x0 = 5 * i
        b.box(x0 + 0.8, 3.2, 0, 1.0, 1.2, 0.15 + 0.5 * rnd.random())
        b.box(x0 + 4.2, 0.7, 0, 0.8, 1.0, 0.3 + rnd.random())
        b.box(x0 + 0.6, 9.3, 0, 0.8, 0.8, 1.4, yaw=rnd.uniform(0, 30))
        b.box(x0 + 4.3, 6.8, 0, 0.9, 0.8, 0.12)
        b.box(x0 + 4.4, 9.3, 0, 0.6, 0.9, 0.8 + rnd.random())
    for x in (5, 10):
        for y in (0.2, 9.8):
            b.box(x, y, 0, 0.4, 0.4, 2.7)
    b.box(5.0, 5.65, 0, 1.6, 0.25, 0.5)
    b.path([[1.0, 5.0], [2.5, 5.0], [2.5, 2.0], [7.5, 2.0], [12.5, 2.0], [12.5, 5.0], [7.5, 5.0],
            [7.5, 8.0], [2.5, 8.0], [2.5, 5.0], [1.0, 5.0]], speed=0.6, laps=3, corner=0.35)
    b.write(rotate_deg=30.0)


def legged_office():
    """An office floor walked by a quadruped (S-Graphs' Spot): 1.5 m/s, 90 deg/s turns, a trotting
    gait's roll, pitch and bounce, an Ouster OS1-64 (uint32 ns `t`) with motion distortion."""
    b = Builder("legged_office", height=2.8)
    b.room("office_w", "room", 0, 0, 6, 5)
    b.room("office_e", "room", 6, 0, 12, 5)
    b.room("corridor", "corridor", 0, 5, 12, 7.5)
    b.room("meeting", "room", 3, 7.5, 9, 12)
    b.door('h', 5, 2.0, 3.2)
    b.door('h', 5, 8.8, 10.0)
    b.door('v', 6, 1.5, 2.5)
    b.door('h', 7.5, 5.4, 6.6)
    b.line('v', 0, 5, 7.5)
    b.line('v', 12, 5, 7.5)
    b.line('h', 7.5, 0, 3)
    b.line('h', 7.5, 9, 12)
    b.floor_rect(0, 0, 12, 12)
    for x in (0.6, 6.6):
        b.box(x + 1.2, 0.45, 0, 2.4, 0.8, 0.75)
        b.box(x + 4.6, 4.4, 0, 0.6, 1.0, 1.9)
    b.table(4.5, 9.0, 7.5, 10.5)
    b.box(3.5, 11.6, 0, 1.6, 0.5, 1.2)
    b.path([[1.5, 6.2], [2.6, 6.2], [2.6, 2.5], [4.5, 2.5], [4.5, 1.8], [9.4, 1.8], [9.4, 3.5],
            [9.4, 6.2], [6.0, 6.2], [6.0, 8.3], [3.8, 8.3], [3.8, 11.0], [8.2, 11.0], [8.2, 8.3],
            [6.0, 8.3], [6.0, 6.2], [1.5, 6.2]],
           speed=1.5, laps=2, corner=0.4)
    b.trajectory.update({"max_yaw_rate_dps": 90.0, "max_accel_mps2": 1.5, "jitter_deg": 2.0,
                         "jitter_z_m": 0.02})
    b.sensor = {"model": "os1_64", "rate_hz": 10, "mount_height_m": 0.6,
                "range_noise_std_m": 0.01, "motion_distortion": True, "seed": 1}
    b.write()


def warehouse():
    """Open plan (issue: rooms in open-plan interiors): a 40 x 24 m hall under an 8 m roof with
    five rows of see-through 2.5 m racks (2.5 m aisles), a loading area with pallets and two
    walled offices (3 m walls and ceiling) in a corner. Ground truth: the hall is one room, each
    office one room."""
    b = Builder("warehouse", height=8.0, thickness=0.2)
    t = b.t
    h = t / 2
    b.rect(0, 0, 40, 24)
    b.floor_rect(0, 0, 40, 24)
    # Offices A (x 0..5) and B (x 5..10), y 0..4: 3 m walls, 1 m doors on their north side.
    oh = 3.0
    for x0, x1, door in ((0, 5, 2.0), (5, 10, 7.0)):
        b.wall((x0 + h if x0 == 0 else x0, 4), (door, 4), z_max=oh)
        b.wall((door + 1.0, 4), (x1, 4), z_max=oh)
        b.ceilings.append({"polygon": [[x0, 0], [x1, 0], [x1, 4], [x0, 4]], "z": oh})
        b.polygon_room("office_" + ("a" if x0 == 0 else "b"), "room",
                       [[x0 + h, h], [x1 - h, h], [x1 - h, 4 - h], [x0 + h, 4 - h]])
    b.wall((5, h), (5, 4), z_max=oh)
    b.wall((10, h), (10, 4 + h), z_max=oh)
    b.polygon_room("hall", "room", [[h, 4 + h], [10 + h, 4 + h], [10 + h, h], [40 - h, h],
                                    [40 - h, 24 - h], [h, 24 - h]])
    # Racks along x from 14 to 36, 1 m deep: uprights every 2.75 m, four boards, goods on some.
    rng = random.Random(34)
    for yc in (6.0, 9.5, 13.0, 16.5, 20.0):
        for k in range(9):
            b.box(14.0 + 2.75 * k, yc, 0.0, 0.1, 1.0, 2.5)
        for z in (0.1, 0.9, 1.7, 2.45):
            b.box(25.0, yc, z, 22.0, 1.0, 0.05)
        for k in range(8):
            for z in (0.15, 0.95, 1.75):
                if rng.random() < 0.55:
                    w = rng.uniform(0.8, 2.4)
                    x = 14.0 + 2.75 * k + 0.15 + rng.uniform(0.0, 2.45 - w)
                    b.box(x + w / 2, yc, z, w, rng.uniform(0.6, 0.95), rng.uniform(0.3, 0.7))
    # Loading area (x 0..12, y 9..21): pallets, a lane at x 5..7 kept clear.
    for _ in range(22):
        x = rng.choice([rng.uniform(1.0, 4.3), rng.uniform(7.7, 11.0)])
        y = rng.uniform(9.5, 20.5)
        b.box(x, y, 0.0, 1.2, 1.0, rng.choice([0.15, 0.8, 1.2, 1.6]))
    b.path([[2.5, 2.0], [2.5, 5.0], [12.5, 7.75], [37.5, 7.75], [37.5, 14.75], [12.5, 14.75],
            [12.5, 18.25], [37.5, 18.25], [38.0, 22.3], [6.0, 22.3], [6.0, 6.0], [7.5, 5.0],
            [7.5, 2.0]], speed=1.0, corner=0.6)
    b.write()


def cubicle_cluster(b, rng, x0, y0, cols=3, size=2.4):
    """Two rows of `cols` cubicles back to back (x0..x0 + cols * size, y0..y0 + 2 * size), open
    to the aisles on their long sides: partitions are 1.2-1.6 m high, 6 cm thick boxes (no
    walls), each cubicle with an L-shaped desk, a monitor and a chair."""
    x1, ym = x0 + cols * size, y0 + size
    ph = rng.uniform(1.2, 1.6)
    b.box((x0 + x1) / 2, ym, 0.0, x1 - x0, 0.06, ph)  # the spine
    for k in range(cols + 1):
        b.box(x0 + k * size, ym, 0.0, 0.06, 2 * size - 0.8, rng.uniform(1.2, 1.6))
    for k in range(cols):
        cx = x0 + (k + 0.5) * size
        for side in (-1, 1):
            near, far = ym + side * 0.05, ym + side * 0.75
            b.table(cx - size / 2 + 0.1, min(near, far), cx + size / 2 - 0.1, max(near, far),
                    legs=False)
            b.box(cx - size / 2 + 0.4, ym + side * 1.0, 0.0, 0.7, 1.2, 0.75)  # the desk return
            b.box(cx + rng.uniform(-0.5, 0.5), ym + side * 0.2, 0.75, 0.55, 0.05, 0.35)
            b.box(cx + rng.uniform(-0.4, 0.6), ym + side * rng.uniform(0.9, 1.4), 0.0,
                  0.55, 0.55, rng.uniform(0.9, 1.1))  # a chair


def open_office():
    """Open plan (issue: rooms in open-plan interiors): a 32 x 20 m office floor under a 3 m
    ceiling. Four clusters of six cubicles with 1.2-1.6 m partitions fill the open area, a lounge
    with low cabinets and sofas opens off it; three walled offices and a meeting room with doors
    line the north side. Ground truth: the open area (cubicles and lounge) is one room, each
    office and the meeting room one room."""
    b = Builder("open_office", height=3.0, thickness=0.15)
    h = b.t / 2
    b.rect(0, 0, 32, 20)
    b.floor_rect(0, 0, 32, 20)
    for i, x0 in enumerate((0, 4, 8)):
        b.room("office_" + "abc"[i], "room", x0, 15, x0 + 4, 20)
        b.door('h', 15, x0 + 1.5, x0 + 2.5)
        b.table(x0 + 0.4, 18.6, x0 + 2.4, 19.5)
        b.box(x0 + 3.4, 17.5, 0.0, 0.5, 1.8, 1.9)  # a cabinet
    b.room("meeting", "room", 24, 13, 32, 20)
    b.door('v', 24, 16.4, 17.6)
    b.table(26.0, 14.2, 30.5, 15.6)
    for x in (26.5, 27.7, 28.9, 30.0):
        for y in (13.7, 16.1):
            b.box(x, y, 0.0, 0.5, 0.5, 0.95)
    b.open_floor("open_area", 32, 20, [(0, 12, 15), (24, 32, 13)])
    rng = random.Random(35)
    for x0 in (3.0, 12.0):
        for y0 in (1.5, 8.3):
            cubicle_cluster(b, rng, x0, y0)
    # The lounge (x 12..24, y 15..20): low cabinets, two sofas, a coffee table; printers east.
    b.box(15.0, 19.5, 0.0, 4.0, 0.6, 1.1)
    b.box(20.5, 19.5, 0.0, 3.0, 0.6, 1.1)
    b.box(14.5, 18.3, 0.0, 2.2, 0.9, 0.8)
    b.box(20.5, 18.3, 0.0, 2.2, 0.9, 0.8)
    b.box(15.0, 16.0, 0.0, 1.2, 0.7, 0.45)
    for y in (3.0, 6.5, 10.0):
        b.box(31.3, y, 0.0, 0.8, 1.2, 1.3)
    b.path([[1.5, 7.3], [21.5, 7.3], [21.5, 14.05], [2.0, 14.05], [2.0, 17.5], [2.0, 14.05],
            [6.0, 14.05], [6.0, 17.5], [6.0, 14.05], [10.0, 14.05], [10.0, 17.5], [10.0, 14.05], [18.0, 14.05], [18.0, 17.0],
            [27.0, 17.0], [30.8, 17.4], [22.5, 17.0], [22.5, 11.0], [22.0, 0.8], [1.5, 0.8],
            [1.5, 7.3], [10.0, 7.3]], speed=1.0, corner=0.6)
    b.write()


def library_stacks():
    """Open plan (issue: rooms in open-plan interiors): a 36 x 24 m reading hall under a 4 m
    ceiling. Two blocks of 2.2 m double-sided book stacks (rows along y, 1.8 m aisles) with a
    cross aisle between them fill the east half, reading tables the west half, a 1.1 m service
    counter stands by the entrance; a group-study room and a staff office with doors in the
    north-west corner. Ground truth: the hall (stacks, tables) is one room, each walled room one
    room."""
    b = Builder("library_stacks", height=4.0, thickness=0.2)
    h = b.t / 2
    b.rect(0, 0, 36, 24)
    b.floor_rect(0, 0, 36, 24)
    b.room("study", "room", 0, 18, 8, 24)
    b.door('h', 18, 6.0, 7.2)
    b.room("staff", "room", 8, 18, 14, 24)
    b.door('h', 18, 9.0, 10.0)
    b.table(1.0, 20.0, 5.0, 21.4)
    b.table(10.0, 22.6, 13.0, 23.6)
    b.box(13.4, 20.0, 0.0, 0.5, 1.6, 1.9)
    b.open_floor("hall", 36, 24, [(0, 14, 18)])
    rng = random.Random(36)
    # Stacks: rows along y of 0.9 m sections, each a little deeper or shallower (books).
    for y0, y1 in ((3.0, 11.1), (13.5, 21.6)):
        for k in range(7):
            x = 19.0 + 2.4 * k
            y = y0
            while y < y1 - 1e-6:
                b.box(x, y + 0.45, 0.0, rng.uniform(0.52, 0.6), 0.88, 2.2)
                y += 0.9
    # Reading tables with chairs (x 3..15, y 3..15) and the counter by the entrance.
    for tx in (3.0, 8.0):
        for ty in (3.0, 7.0, 11.0):
            b.table(tx, ty, tx + 3.0, ty + 1.2)
            for cx in (tx + 0.7, tx + 2.3):
                for cy in (ty - 0.45, ty + 1.65):
                    b.box(cx, cy, 0.0, 0.45, 0.45, 0.9)
    b.box(14.0, 6.0, 0.0, 0.7, 3.0, 1.1)
    b.path([[1.5, 1.5], [16.5, 1.5], [16.5, 12.3], [35.0, 12.3], [35.0, 1.6], [20.2, 1.6],
            [20.2, 11.8], [22.6, 11.8], [22.6, 22.8], [16.5, 22.8], [16.5, 16.5], [6.6, 16.5],
            [6.6, 21.5], [6.6, 16.5], [9.5, 16.5], [9.5, 21.0], [9.5, 16.5], [1.5, 16.5],
            [1.5, 1.5], [12.0, 1.5]], speed=1.0, corner=0.6)
    b.write()


def market_hall():
    """Open plan (issue: rooms in open-plan interiors): a 30 x 20 m supermarket hall under a 5 m
    roof whose 1.6 m gondola rows run both ways: along x in the west half, along y in the east
    half, with checkout counters by the entrance and a walled storeroom (door) in the north-east
    corner. Ground truth: the sales floor is one room, the storeroom one room."""
    b = Builder("market_hall", height=5.0, thickness=0.2)
    b.rect(0, 0, 30, 20)
    b.floor_rect(0, 0, 30, 20)
    b.room("storeroom", "room", 23, 15, 30, 20)
    b.door('v', 23, 16.2, 17.6)
    for k, pallet_h in enumerate((1.2, 1.6, 0.8)):
        b.box(25.0 + 2.0 * k, 18.8, 0.0, 1.2, 1.0, pallet_h)
    b.open_floor("sales_floor", 30, 20, [(23, 30, 15)])
    rng = random.Random(37)
    # Gondolas: 0.9 m deep, 1.6 m high, in 1.25 m sections (goods make each face uneven).
    def gondola(x0, y0, along_x, sections):
        for k in range(sections):
            d = rng.uniform(0.84, 0.9)
            if along_x:
                b.box(x0 + 1.25 * (k + 0.5), y0, 0.0, 1.23, d, 1.6)
            else:
                b.box(x0, y0 + 1.25 * (k + 0.5), 0.0, d, 1.23, 1.6)
    for y in (6.0, 8.8, 11.6, 14.4, 17.2):
        gondola(2.5, y, True, 9)  # x 2.5..13.75
    for x in (17.0, 19.8, 22.6, 25.4):
        gondola(x, 3.5, False, 7)  # y 3.5..12.25
    for x in (4.0, 7.0, 10.0):  # checkouts: a counter and a belt by the entrance
        b.box(x, 2.4, 0.0, 0.8, 2.0, 0.9)
    b.path([[1.2, 1.0], [15.0, 1.0], [15.0, 7.4], [1.2, 7.4], [1.2, 13.0], [15.0, 13.0],
            [15.4, 18.6], [21.0, 18.6], [21.0, 16.9], [27.0, 16.9], [21.0, 16.9], [21.0, 14.3],
            [28.8, 14.3], [28.8, 1.8], [24.0, 1.8], [24.0, 13.3], [18.4, 13.3], [18.4, 1.0],
            [1.2, 1.0], [1.2, 7.4]], speed=1.0, corner=0.6)
    b.write()

if __name__ == "__main__":
    for fn in (smoke, lab_room, corridor_loop, long_corridor, large_hall, open_lobby,
               cluttered_rooms, construction_site, legged_office, warehouse, open_office,
               library_stacks, market_hall):
        fn()
