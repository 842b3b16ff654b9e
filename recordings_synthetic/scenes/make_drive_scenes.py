#!/usr/bin/env python3
"""Writes overtaking.json and city_drive_60s.json (the two scenes of recordings_synthetic/ that
are not adapted from docs/examples/). Run from this directory; the output is deterministic."""
import json, math

from scene_json import scene

def sample(t, x, y, yaw, v):
    return {"t_s": round(t, 3), "x_m": round(x, 3), "y_m": round(y, 3), "yaw_rad": round(yaw, 5), "speed_mps": round(v, 3)}

def lane_change_yaw(dy, dx):
    return math.atan2(dy, dx)

# Overtaking: the ego (22 m/s) pulls out to the left lane, passes a car at 14 m/s and cuts back in.
v = 22.0
ego = [sample(0, 0, 0, 0, v), sample(1.5, 33, 0, 0, v),
       sample(2.75, 60.5, 1.75, lane_change_yaw(3.5, 2.5 * v) * 1.5, v), sample(4.0, 88, 3.5, 0, v),
       sample(6.5, 143, 3.5, 0, v), sample(7.75, 170.5, 1.75, -lane_change_yaw(3.5, 2.5 * v) * 1.5, v),
       sample(9.0, 198, 0, 0, v)]
overtaking = scene(
    "overtaking",
    "The observer (22 m/s) pulls out into the left lane 30 m behind a car driving at 14 m/s, passes it "
    "(the right sensor sees its rear, then its left side and wheel houses) and cuts back in ahead of it.",
    10.0, ego,
    [{"id": "slow_car", "model": "passenger_car", "trajectory": [sample(0, 35.0, 0.0, 0.0, 14.0)]}])

# A 60-s drive on a two-lane road with a lead car, a truck in the left lane, oncoming traffic,
# parked cars and street furniture, with a gentle left curve at the end.
def ego_path():
    # speed profile (t, v): accelerate, follow, slow down for a queue, speed up again
    profile = [(0, 8.0), (8, 13.0), (20, 13.0), (27, 5.0), (33, 5.0), (40, 12.0), (60, 12.0)]
    def speed(t):
        for (t0, v0), (t1, v1) in zip(profile, profile[1:]):
            if t <= t1:
                a = (t - t0) / (t1 - t0)
                return v0 + (v1 - v0) * (0.5 - 0.5 * math.cos(math.pi * a))
        return profile[-1][1]
    pts, x, y, yaw, dt = [], 0.0, 0.0, 0.0, 0.05
    t = 0.0
    while t <= 62.0 + 1e-9:
        v = speed(t)
        yaw_rate = 0.012 if 46.0 <= t <= 58.0 else 0.0  # left curve, radius ~1 km at 12 m/s
        pts.append((t, x, y, yaw, v, yaw_rate))
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw += yaw_rate * dt
        t += dt
    return pts

path = ego_path()
def at(t):
    i = min(range(len(path)), key=lambda k: abs(path[k][0] - t))
    return path[i]
ego = []
for k in range(0, 61, 2):
    t, x, y, yaw, v, r = at(float(k))
    s = sample(t, x, y, yaw, v)
    s["yaw_rate_radps"] = r
    ego.append(s)
objects = []
# lead car: the ego's own path, 2.2 s ahead (so it brakes and accelerates first)
lead = []
for k in range(0, 61, 2):
    t, x, y, yaw, v, r = at(min(62.0, k + 2.2))
    s = sample(float(k), x, y, yaw, v)
    s["yaw_rate_radps"] = r
    lead.append(s)
objects.append({"id": "lead_car", "model": "passenger_car", "trajectory": lead})
# truck in the left lane, slower than the ego early on, passed during the first 20 s
objects.append({"id": "truck", "model": "truck_trailer",
                "trajectory": [sample(0, 40.0, 3.5, 0.0, 9.0), sample(20, 220.0, 3.5, 0.0, 9.0),
                               sample(27, 260.0, 3.5, 0.0, 3.0), sample(40, 300.0, 3.5, 0.0, 6.0)]})
# oncoming cars in the far lane (y = 7), 12-14 m/s
for i, (x0, t0, vv) in enumerate([(180.0, 0.0, 13.0), (420.0, 5.0, 14.0), (520.0, 22.0, 12.0), (700.0, 30.0, 13.0)]):
    objects.append({"id": f"oncoming_{i + 1}", "model": "passenger_car",
                    "trajectory": [sample(t0, x0, 7.0, math.pi, vv)]})
# parked cars on the right (y = -3.6) and street lights (poles) on both sides
for i, x0 in enumerate([60.0, 66.0, 150.0, 232.0, 238.0, 300.0]):
    objects.append({"id": f"parked_{i + 1}", "model": "passenger_car",
                    "trajectory": [sample(0, x0, -3.7, 0.0 if i % 2 else math.pi, 0.0)]})
for i, x0 in enumerate(range(30, 480, 45)):
    objects.append({"id": f"light_{i + 1}", "model": "pole", "trajectory": [sample(0, float(x0), -5.5, 0.0, 0.0)]})
objects.append({"id": "board_curve", "model": "guide_board", "trajectory": [sample(0, 560.0, -6.0, 2.6, 0.0)]})
drive = scene(
    "city drive 60 s",
    "60 s on a two-lane road: following a lead car through a slow-down, passing a truck in the left lane, "
    "oncoming cars, parked cars and street lights on the right, a guide board in a gentle left curve; "
    "road clutter on.",
    60.0, ego, objects, {"clutter": True, "occlusion": True})

for name, s in [("overtaking.json", overtaking), ("city_drive_60s.json", drive)]:
    with open(name, "w") as f:
        json.dump(s, f, indent=1)
        f.write("\n")
