"""What the scene generators (make_drive_scenes.py here, ../campaign/make_campaign_scenes.py)
share: the ego's two srr24 sensors and an rcsim-scene v1 document."""

SENSORS = [{"id": "front_left", "type": "srr24", "x_m": 3.7, "y_m": 0.7, "yaw_rad": 0.5},
           {"id": "front_right", "type": "srr24", "x_m": 3.7, "y_m": -0.7, "yaw_rad": -0.5}]


def scene(name, description, duration, ego, objects, effects=None):
    s = {"format": "rcsim-scene", "version": 1, "name": name, "description": description, "duration_s": duration}
    if effects:
        s["effects"] = effects
    s["ego"] = {"trajectory": ego, "sensors": SENSORS}
    s["objects"] = objects
    return s
