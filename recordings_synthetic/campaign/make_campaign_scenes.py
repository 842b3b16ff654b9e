#!/usr/bin/env python3
"""Writes the scenes of the calibration campaign (scenes/*.json): situations that the nine
validation recordings of recordings_synthetic/ do not contain (other ranges, aspects, offsets,
speeds and the rear of the car), so that a model calibrated on the campaign can be measured on
the nine as data it has never seen. Run from this directory; the output is deterministic."""
import json, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes"))
from scene_json import SENSORS, scene  # noqa: E402
HALF_LENGTH_M = 2.3  # passenger_car


def node(t, x, y, yaw, v):
    return {"t_s": round(t, 3), "x_m": round(x, 4), "y_m": round(y, 4), "yaw_rad": round(yaw, 6), "speed_mps": round(v, 4)}


def straight(x0, y0, yaw, profile, dt=0.5):
    """Nodes along a straight line from (x0, y0) heading yaw, for a speed profile [(t, v), ...]
    with linear speed between its points (so the positions integrate the speeds exactly)."""
    nodes, s = [], 0.0
    t_end = profile[-1][0]
    times = sorted(set([p[0] for p in profile] + [k * dt for k in range(int(t_end / dt) + 1)]))

    def speed(t):
        for (t0, v0), (t1, v1) in zip(profile, profile[1:]):
            if t0 <= t <= t1:
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        return profile[-1][1]

    prev_t = 0.0
    for t in times:
        s += 0.5 * (speed(prev_t) + speed(t)) * (t - prev_t)
        prev_t = t
        nodes.append(node(t, x0 + s * math.cos(yaw), y0 + s * math.sin(yaw), yaw, speed(t)))
    return nodes


def still(x, y, yaw):
    return [node(0, x, y, yaw, 0.0)]


def car(ident, trajectory):
    return {"id": ident, "model": "passenger_car", "trajectory": trajectory}


# Ego standing turned by yaw so that one sensor sits at the world origin looking along +x.
def ego_with_sensor_at_origin(sensor_index, yaw):
    sx, sy = SENSORS[sensor_index]["x_m"], SENSORS[sensor_index]["y_m"]
    c, s = math.cos(yaw), math.sin(yaw)
    return still(-(c * sx - s * sy), -(s * sx + c * sy), yaw)


SCENES = {
    "front_approach_offset": scene(
        "front approach, offset", "Driving at 4 m/s towards the front of a car parked 1.2 m to the left, "
        "stopping 6 m before it: the front from 32 m down to 6 m, seen off-axis.", 8.0,
        straight(0, 0, 0, [(0, 4.0), (5, 4.0), (8, 0.0)]),
        [car("parked", still(38.0, 1.2, math.pi))]),
    "rear_approach": scene(
        "rear approach", "Driving at 3.5 m/s towards the rear of a car parked 0.5 m to the right, stopping "
        "about 5.5 m behind it.", 8.0,
        straight(0, 0, 0, [(0, 3.5), (6, 3.5), (8, 0.0)]),
        [car("parked", still(36.0, -0.5, 0.0))]),
    "rear_leaving_close": scene(
        "rear leaving from 0.7 m", "A car standing with its rear 0.7 m before the sensors drives away at "
        "0.6 m/s: its rear from 0.7 m to 5 m, with back-and-forth reflections while close.", 8.0,
        still(0, 0, 0),
        [car("leaving", straight(3.7 + 0.7 + HALF_LENGTH_M, 0.3, 0.0, [(0, 0.0), (1, 0.6), (8, 0.6)]))],
        effects={"multibounce": True}),
    "standstill_front_1_6m": scene(
        "standstill 1.6 m before a front", "Observer and car stand still, the car's front 1.6 m ahead of the "
        "sensors and 0.6 m to the left.", 2.0,
        still(0, 0, 0), [car("parked", still(3.7 + 1.6 + HALF_LENGTH_M, 0.6, math.pi))],
        effects={"multibounce": True}),
    "standstill_front_0_7m": scene(
        "standstill 0.7 m before a front", "Observer and car stand still, the car's front 0.7 m ahead of the "
        "sensors, centred.", 2.0,
        still(0, 0, 0), [car("parked", still(3.7 + 0.7 + HALF_LENGTH_M, 0.0, math.pi))],
        effects={"multibounce": True}),
    "rear_corner_approach": scene(
        "rear corner approach", "Driving towards a car parked turned -0.4 rad so that its rear-right corner "
        "and right side face the observer; stopping about 8 m before the corner.", 8.0,
        straight(0, 0, 0, [(0, 3.0), (5, 3.0), (8, 0.0)]),
        [car("parked", still(34.0, 1.0, -0.4))]),
    "front_corner_approach": scene(
        "front corner approach at 30 deg", "Driving towards a car parked facing the observer turned by "
        "0.5 rad, 1.5 m to the right, stopping about 9 m before it.", 8.0,
        straight(0, 0, 0, [(0, 3.0), (5, 3.0), (8, 0.0)]),
        [car("parked", still(33.0, -1.5, math.pi - 0.5))]),
    "crossing_8m": scene(
        "crossing at 8 m, right to left", "A car crosses 8 m ahead of the sensors from right to left at "
        "3 m/s while the observer stands.", 6.0,
        still(0, 0, 0), [car("crossing", straight(3.7 + 8.0 + 0.9, -9.0, math.pi / 2, [(0, 3.0), (6, 3.0)]))]),
    "crossing_4m_slow": scene(
        "slow crossing at 4 m", "A car crosses 4 m ahead of the sensors from left to right at 1.5 m/s "
        "while the observer stands.", 9.0,
        still(0, 0, 0), [car("crossing", straight(3.7 + 4.0 + 0.9, 7.0, -math.pi / 2, [(0, 1.5), (9, 1.5)]))]),
    "following": scene(
        "following a lead car", "The observer follows a lead car at 7 m/s; the lead car speeds up from 6 "
        "to 10 m/s and slows to 5 m/s, so the gap to its rear runs between 10 and 16 m.", 12.0,
        straight(0, 0, 0, [(0, 7.0), (12, 7.0)]),
        [car("lead", straight(20.0, 0.3, 0.0, [(0, 6.0), (4, 6.0), (8, 10.0), (12, 5.0)]))]),
    "passing_parked_cars": scene(
        "passing parked cars", "Driving at 5 m/s past a car parked on the left (its right side 1.6 m from "
        "the left sensor's track) and one parked facing the observer on the right.", 8.0,
        straight(0, 0, 0, [(0, 5.0), (8, 5.0)]),
        [car("parked_left", still(25.0, 3.2, 0.0)), car("parked_right", still(32.0, -3.4, math.pi))]),
    "two_cars_diverging": scene(
        "two cars diverging in range", "The observer stands turned 0.5 rad to the right so that its left "
        "sensor looks along a road where two cars drive away side by side (3.0 m apart) at 3.0 and "
        "3.3 m/s: one cell at first, two targets later.", 6.0,
        ego_with_sensor_at_origin(0, -0.5),
        [car("car_left", straight(6.3, 1.5, 0.0, [(0, 3.0), (6, 3.0)])),
         car("car_right", straight(6.3, -1.5, 0.0, [(0, 3.3), (6, 3.3)]))]),
    "oncoming": scene(
        "oncoming car", "Driving at 6 m/s while a car comes the other way at 8 m/s in the lane to the left.",
        5.0, straight(0, 0, 0, [(0, 6.0), (5, 6.0)]),
        [car("oncoming", straight(60.0, 3.2, math.pi, [(0, 8.0), (5, 8.0)]))]),
}

if __name__ == "__main__":
    os.makedirs("scenes", exist_ok=True)
    for name, s in SCENES.items():
        with open(os.path.join("scenes", name + ".json"), "w") as f:
            json.dump(s, f, indent=1)
            f.write("\n")
        print(f"scenes/{name}.json")
