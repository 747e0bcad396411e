"""Scenarios from Python: build one (a dict in the JSON schema of docs/scenarios.md), preview a
frame, render a release of several, then read it with flowscape.FlowScape, so a sweep (say 50 sun
elevations) is a loop:

    from flowscape import scenario as sc
    runs = [sc.scenario(map="downtown", seed=7, time_of_day=str(e), frames=10) for e in range(5, 55)]
    sc.render_release(runs, "sweep/", resolution=256, spp=4)

The rendering runs in the toolkit's C++ library through the flowscape_scenarios extension (built
by CMake with the toolkit into build/python; not by pip, which builds the plugin's own extension
only). Scenario dicts are checked by the library as files are: a bad key or value is a ValueError
naming it."""
import json
import os

try:
    import flowscape_scenarios as _native
except ImportError:  # the plugin alone (pip, or a build with FLOWSCAPE_PYTHON_EXTENSION off)
    _native = None

SCHEMA = 1


def scenario(map="downtown", seed=0, rig="flowscape", route="drive", waypoints=None,
             pose_file=None, pose_format="tum", poses_of="rig", vehicles=120, pedestrians=-1,
             standing=-1, weather="sunny", time_of_day="day", sky="physical", frames=100,
             name="scenario", ego="auto", frame_rate=30, lane_change_at=None, world_file=None,
             actors=None):
    """A scenario dict. The motion is the ego's `route` (drive, turn, lane_change, free;
    `lane_change_at` seconds for lane_change) unless `waypoints` (a list of dicts: position, time
    or speed, optional yaw_pitch_roll_degrees) or a `pose_file` (tum, kitti, colmap; its poses
    the rig's or a camera's, `poses_of`) gives the rig its own. `world_file` is a dict (file,
    units, up, classes: docs/scenarios.md) in place of the map, with no traffic; `actors` a list
    of dicts (kind, waypoints, optional model) placed one by one. `pedestrians` walk, `standing`
    stand on the pavements; -1: the map's own (docs/scenes.md)."""
    if waypoints is not None:
        motion = {"waypoints": list(waypoints)}
    elif pose_file is not None:
        motion = {"pose_file": os.path.abspath(pose_file), "format": pose_format, "poses_of": poses_of}
    else:
        motion = {"route": route}
        if lane_change_at is not None:
            motion["lane_change_at"] = lane_change_at
    world = {"map": map, "seed": seed}
    traffic = {"vehicles": vehicles, "pedestrians": pedestrians, "standing": standing}
    if world_file is not None:
        world = dict(world_file, file=os.path.abspath(world_file["file"]), seed=seed)
        traffic = {"vehicles": 0, "pedestrians": 0, "standing": 0}
    out = {"flowscape_scenario": SCHEMA, "name": name, "world": world, "rig": rig, "ego": ego,
           "motion": motion, "traffic": traffic, "weather": weather, "time_of_day": time_of_day,
           "sky": sky, "frames": frames, "frame_rate": frame_rate}
    if actors:
        out["actors"] = [dict(a, model=os.path.abspath(a["model"])) if "model" in a else dict(a)
                         for a in actors]
    return out


def _library():
    if _native is None:
        raise ImportError("flowscape_scenarios is not built: build the toolkit with CMake "
                          "(scripts/build.sh) and put build/python on PYTHONPATH")
    return _native


def preview(scenario, frame=0, height=128, **options):
    """The scenario's frame as an ERP `height` pixels high, colour as a release renders it
    (H x 2H x 3 uint8). `options` are release config keys (spp, denoise, ...)."""
    return _library().preview(json.dumps(scenario), frame, height, json.dumps(options))


def write_scenarios(scenarios, folder):
    """Each scenario as a file in `folder` (<k>_<name>.json); their paths."""
    os.makedirs(folder, exist_ok=True)
    paths = []
    for k, s in enumerate(scenarios):
        stem = "".join(c if c.isalnum() or c in "-_" else "_" for c in s.get("name", "scenario"))
        paths.append(os.path.join(folder, f"{k:03d}_{stem}.json"))
        with open(paths[-1], "w") as f:
            json.dump(s, f, indent=1)
    return paths


def render_release(scenarios, out, scenario_folder=None, **options):
    """A release in `out` of the scenarios (dicts), one sequence each, as `gen_flowscape
    --scenario` makes it; they are written as files to `scenario_folder` (default: beside the
    release, <out>.scenarios/), which its config records. `options` are release config keys
    (resolution, face_size, spp, frames, rig...), overriding the scenarios' release-wide ones.
    Calling it again resumes. Returns the manifest's path and the counts written."""
    out = os.path.abspath(out)
    folder = scenario_folder or out.rstrip(os.sep) + ".scenarios"
    return _library().render_release(write_scenarios(scenarios, folder), out, json.dumps(options))
