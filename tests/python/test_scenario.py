"""Scenarios from Python (flowscape/scenario.py over the flowscape_scenarios extension): a
2-frame sequence rendered into a release and read back through the plugin, a preview, and a bad
scenario named (issue 36)."""
import os
import subprocess

import numpy as np
import pytest

import flowscape
from flowscape import scenario as sc

BIN = os.environ.get("FLOWSCAPE_BIN", "build/apps")
pytestmark = pytest.mark.skipif(sc._native is None, reason="flowscape_scenarios is not built")

DRONE = [{"position": [26, -138.5, 20], "time": 0}, {"position": [20, -138.5, 20.5], "time": 1}]


def test_a_scenario_renders_into_a_release_the_plugin_reads(tmp_path):
    drone = sc.scenario(map="downtown", seed=3, waypoints=DRONE, frames=2, vehicles=4,
                        pedestrians=2, name="drone")
    out = tmp_path / "release"
    summary = sc.render_release([drone], out, resolution=16, face_size=8, spp=1)
    assert summary["sequences"] == 1 and summary["frames"] == 2
    assert (tmp_path / "release.scenarios" / "000_drone.json").is_file()
    subprocess.run([f"{BIN}/flowscape_split", str(out)], check=True, capture_output=True)
    dataset = flowscape.FlowScape(out, "all")
    img1, img2, flow, valid = dataset[0]
    assert img1.shape == (3, 16, 32) and flow.shape == (2, 16, 32)
    meta = flowscape.ReleaseLayout(out).meta("map00_seq00")
    assert meta["scenario"]["motion"]["waypoints"][0]["position"] == [26, -138.5, 20]
    first = np.asarray(meta["poses"][0]).reshape(3, 4)
    assert np.abs(first[:, 3] - [26, -138.5, 20]).max() < 1e-9  # the first waypoint at t = 0
    # the same call again resumes: nothing to render
    again = sc.render_release([drone], out, resolution=16, face_size=8, spp=1)
    assert again["sequences"] == 1


def test_a_preview_and_a_bad_scenario(tmp_path):
    turn = sc.scenario(map="suburb", seed=5, route="turn", frames=4, vehicles=4, pedestrians=2)
    image = sc.preview(turn, frame=1, height=16, spp=1)
    assert image.shape == (16, 32, 3) and image.dtype == np.uint8 and image.max() > 0
    with pytest.raises(ValueError, match='unknown key "wether"'):
        sc.preview({**turn, "wether": "rain"})
    with pytest.raises(ValueError, match="the sequence has 4 frames"):
        sc.preview(turn, frame=9, height=16)


def test_a_user_world_with_scripted_actors_at_its_own_frame_rate(tmp_path):
    square = os.path.join(os.path.dirname(__file__), "../../examples/worlds/square.gltf")
    world = {"file": square, "units": "metres", "up": "y",
             "classes": [["road*", "Road"], ["*", "Building"]]}
    walk = [{"position": [-6, 9, 1.6], "time": 0}, {"position": [0, 7.5, 1.6], "time": 4}]
    car = {"kind": "car", "waypoints": [{"position": [-30, -2, 0]},
                                        {"position": [30, -2, 0], "speed": 9}]}
    s = sc.scenario(world_file=world, waypoints=walk, actors=[car], frames=2, frame_rate=10,
                    name="square")
    assert s["traffic"] == {"vehicles": 0, "pedestrians": 0, "standing": 0}
    image = sc.preview(s, frame=0, height=16, spp=1)
    assert image.shape == (16, 32, 3) and image.max() > 0
    with pytest.raises(ValueError, match="matches no class pattern"):
        sc.preview(sc.scenario(world_file={**world, "classes": [["road*", "Road"]]},
                               waypoints=walk, frames=2))
