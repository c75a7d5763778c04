"""The Python package against the library's promises: exact events, conservation, arrays of
the right shapes, clear errors, and agreement with the ccdsim binary."""

import json
import subprocess

import numpy as np
import pytest

import ccdsim



def two_balls():
    return {
        "dim": 2,
        "bodies": [
            {"pos": [0.0, 0.0], "vel": [1.0, 0.0], "radius": 0.5},
            {"pos": [3.0, 0.0], "vel": [-1.0, 0.0], "radius": 0.5},
        ],
    }


def test_head_on_collision_is_exact():
    sim = ccdsim.Simulation(two_balls(), finder="all-pairs")
    ev = sim.step()
    assert ev["t"] == 1.0 and ev["kind"] == ccdsim.BODY
    assert (ev["a"], ev["b"]) == (0, 1)
    np.testing.assert_array_equal(ev["vel"], [[-1.0, 0.0], [1.0, 0.0]])
    assert sim.step() is None  # they fly apart for ever


def test_every_finder_gives_the_same_events():
    scene = ccdsim.generate.gas(n=200, packing=0.3, seed=4)
    runs = []
    for name in ccdsim.FINDER_NAMES:
        sim = ccdsim.Simulation(scene, finder=name)
        runs.append(sim.advance(2.0))
    for other in runs[1:]:
        assert other.dtype == runs[0].dtype
        np.testing.assert_array_equal(other, runs[0])
    assert len(runs[0]) > 100


@pytest.mark.parametrize("dim", [2, 3])
def test_arrays_and_conservation(dim):
    scene = ccdsim.generate.gas(
        n=300, packing=0.3, dim=dim, periodic=True, lattice=True, temperature=1.0, seed=2
    )
    sim = ccdsim.Simulation(scene)
    e0 = sim.kinetic_energy()
    assert sim.run_events(5000) == 5000
    assert sim.positions.shape == (300, dim) and sim.velocities.shape == (300, dim)
    assert sim.radii.shape == (300,) and sim.masses.shape == (300,)
    assert abs(sim.kinetic_energy() - e0) <= 1e-12 * e0
    p = (sim.masses[:, None] * sim.velocities).sum(axis=0)
    np.testing.assert_allclose(p, 0.0, atol=1e-9)
    obs = sim.observables()
    assert obs["compressibility"] > 1.0
    assert sim.stats()["max_overlap"] < 1e-9
    box = np.array(scene["periodic"])
    assert np.all(sim.positions >= -1e-9) and np.all(sim.positions <= box + 1e-9)


def test_from_arrays_and_edits():
    sim = ccdsim.Simulation.from_arrays(
        positions=[[1.0, 1.0], [3.0, 1.0]],
        velocities=[[0.0, 0.0], [0.0, 0.0]],
        radii=[0.5, 0.5],
        walls=[{"a": [0, 0], "b": [4, 0]}, {"a": [4, 0], "b": [4, 2]},
               {"a": [4, 2], "b": [0, 2]}, {"a": [0, 2], "b": [0, 0]}],
    )
    assert len(sim.advance(1.0)) == 0
    sim.set_velocity(0, [1.0, 0.0])
    frame = sim.advance(2.0)
    assert frame[0]["kind"] == ccdsim.BODY and frame[0]["t"] == pytest.approx(2.0)
    with pytest.raises(IndexError):
        sim.set_velocity(7, [0.0, 0.0])
    with pytest.raises(ValueError, match="2 numbers"):
        sim.set_velocity(0, [1.0, 2.0, 3.0])


def test_bad_scenes_raise_value_errors_naming_the_culprit():
    bad = two_balls()
    bad["bodies"][1]["pos"] = [0.5, 0.0]
    with pytest.raises(ValueError, match="overlap"):
        ccdsim.Simulation(bad)
    with pytest.raises(ValueError, match="unknown finder"):
        ccdsim.Simulation(two_balls(), finder="nope")
    with pytest.raises(ValueError, match="line 1"):
        ccdsim.Simulation("{not json")
    late = two_balls()
    late["start_time"] = 1e17
    with pytest.raises(ValueError, match="start_time"):
        ccdsim.Simulation(late)


def test_agrees_with_the_binary_and_reads_its_run_files(tmp_path, ccdsim_binary):
    binary = ccdsim_binary
    scene = ccdsim.generate.rack()
    scene_file = tmp_path / "rack.json"
    scene_file.write_text(json.dumps(scene))
    record = tmp_path / "rack.ccd"
    out = subprocess.run(
        [str(binary), "run", str(scene_file), "--until", "5", "--json", "--quiet",
         "--record", str(record)],
        capture_output=True, text=True, check=True,
    )
    summary = json.loads(out.stdout)
    sim = ccdsim.Simulation(scene)
    frame = sim.advance(5.0)
    assert len(frame) == summary["events"]
    run = ccdsim.read_run(record)
    assert run["complete"] and run["end"] == 5.0
    assert run["scene"]["bodies"] == scene["bodies"]
    np.testing.assert_array_equal(run["events"], frame)


def test_thermostat_resets_are_events_and_hold_the_temperature():
    scene = ccdsim.generate.gas(n=150, packing=0.3, periodic=True, lattice=True,
                                temperature=0.5, seed=2)
    scene["settings"] = {"thermostat": {"temperature": 2.0, "rate": 0.5, "seed": 1}}
    sims = [ccdsim.Simulation(scene, finder=name) for name in ("all-pairs", "cells")]
    frames = [sim.advance(10.0) for sim in sims]
    np.testing.assert_array_equal(frames[0], frames[1])
    kinds = frames[1]["kind"]
    assert (kinds == ccdsim.RESET).sum() > 150 * 10 * 0.5 * 0.8
    assert (kinds == ccdsim.BODY).sum() > 0
    resets = frames[1][kinds == ccdsim.RESET]
    assert np.all(resets["b"] == 0) and np.all(resets["vel"][:, 1] == 0)
    temps = []
    for _ in range(100):
        sims[1].advance(0.5)
        temps.append(sims[1].observables()["temperature"])
    assert abs(np.mean(temps) - 2.0) < 0.1
    assert sims[1].stats()["resets"] > 0


def test_bad_thermostat_is_refused():
    scene = two_balls()
    scene["settings"] = {"thermostat": {"temperature": -1.0, "rate": 1.0}}
    with pytest.raises(ValueError, match="settings.thermostat.temperature"):
        ccdsim.Simulation(scene)


def test_gravity_bends_paths_and_keeps_the_total_energy():
    # A ball dropped 5 m onto a floor bounces back every 2 sqrt(2h/g) s, elastic.
    scene = {
        "dim": 2,
        "settings": {"gravity": [0.0, -9.81]},
        "bodies": [{"pos": [2.0, 5.5], "vel": [0.0, 0.0], "radius": 0.5}],
        "walls": [
            {"a": [0, 0], "b": [4, 0]},
            {"a": [4, 0], "b": [4, 40]},
            {"a": [4, 40], "b": [0, 40]},
            {"a": [0, 40], "b": [0, 0]},
        ],
    }
    fall = (2 * 5.0 / 9.81) ** 0.5
    sim = ccdsim.Simulation(scene)
    total = sim.kinetic_energy() + sim.potential_energy()
    ev = sim.step()
    assert ev["kind"] == ccdsim.WALL and abs(ev["t"] - fall) < 1e-12
    sim.run_until(fall * 2)  # back at the top: at rest, 5.5 m up
    np.testing.assert_allclose(sim.positions, [[2.0, 5.5]], atol=1e-9)
    np.testing.assert_allclose(sim.velocities, [[0.0, 0.0]], atol=1e-9)
    assert abs(sim.kinetic_energy() + sim.potential_energy() - total) < 1e-9 * total
    with pytest.raises(ValueError, match="settings.gravity"):
        ccdsim.Simulation({**scene, "settings": {"gravity": [0.0, -9.81, 0.0]}})


def test_set_position_teleports_and_refuses_overlaps():
    sim = ccdsim.Simulation(two_balls(), finder="cells")
    sim.set_position(1, [5.0, 0.0])
    np.testing.assert_array_equal(sim.positions[1], [5.0, 0.0])
    assert sim.step()["t"] == 2.0  # the gap of 4 m closes at 2 m/s
    with pytest.raises(ValueError, match="overlap body 0"):
        sim.set_position(1, list(sim.positions[0] + [0.5, 0.0]))


def test_collision_filters_let_bodies_pass_through():
    scene = two_balls()
    scene["bodies"][1]["group"] = 2
    scene["bodies"][1]["mask"] = 2  # collides only with group 2: not with body 0
    sim = ccdsim.Simulation(scene, finder="cells")
    sim.run_until(10.0)
    assert sim.stats()["body_collisions"] == 0
    sim = ccdsim.Simulation(two_balls(), finder="cells")
    sim.set_collision_filter(1, group=0, mask=0)  # a ghost
    sim.run_until(1.5)
    assert sim.stats()["body_collisions"] == 0
    with pytest.raises(ValueError, match="overlaps body 0"):
        sim.set_collision_filter(1, group=1)


def test_bodies_are_added_and_removed_in_stable_slots():
    sim = ccdsim.Simulation({"dim": 2, "bodies": []}, finder="cells")
    a = sim.add_body([0.0, 0.0], [1.0, 0.0], 0.5)
    b = sim.add_body([3.0, 0.0], [-1.0, 0.0], 0.5, id=77)
    assert (a, b) == (0, 1)
    assert sim.ids[b] == 77
    assert sim.step()["t"] == 1.0  # the gap of 2 m closes at 2 m/s
    sim.remove_body(a)
    assert not sim.present[a] and sim.present[b]
    assert sim.step() is None  # b flies off alone
    with pytest.raises(ValueError, match="vacant"):
        sim.set_velocity(a, [1.0, 0.0])
    with pytest.raises(ValueError, match="id 77 is taken"):
        sim.add_body([10.0, 10.0], [0.0, 0.0], 0.5, id=77)
    with pytest.raises(ValueError, match="overlap body 1"):
        sim.add_body(list(sim.positions[b]), [0.0, 0.0], 0.5)
    with pytest.raises(ValueError, match="radius"):
        sim.add_body([10.0, 10.0], [0.0, 0.0], -1.0)
    c = sim.add_body([-5.0, 0.0], [0.0, 0.0], 0.25)
    assert c == a  # the vacant slot is filled again
    assert sim.present.all()


def test_bodies_come_and_go_under_a_thermostat_and_with_growing_radii():
    # A thermostat resets the bodies that move freely, added ones from when they are added,
    # removed ones never again.
    scene = {
        "dim": 2,
        "periodic": [20.0, 20.0],
        "settings": {"thermostat": {"temperature": 1.0, "rate": 2.0, "seed": 4}},
        "bodies": [
            {"pos": [2.0 + 4.0 * k, 10.0], "vel": [0.0, 0.0], "radius": 0.5} for k in range(4)
        ],
    }
    sim = ccdsim.Simulation(scene, finder="cells")
    sim.remove_body(0)
    added = sim.add_body([10.0, 3.0], [0.0, 0.0], 0.5)
    assert added == 0  # the vacated slot
    sim.remove_body(1)
    events = sim.advance(20.0)
    resets = events[events["kind"] == 2]
    assert 60 < len(resets) < 180  # 3 bodies at 2 per second for 20 s: 120
    assert not (resets["a"] == 1).any()
    assert (resets["a"] == added).sum() > 20
    # Growing radii: an added body's radius is its radius when it is added.
    growing = {
        "dim": 2,
        "periodic": [20.0, 20.0],
        "settings": {"growth": {"rate": 0.1}},
        "bodies": [{"pos": [5.0, 5.0], "vel": [1.0, 0.5], "radius": 0.5}],
    }
    sim = ccdsim.Simulation(growing, finder="cells")
    sim.advance(2.0)
    b = sim.add_body([15.0, 15.0], [0.0, 0.0], 0.5)
    assert sim.radii[b] == pytest.approx(0.5, rel=1e-15)
    sim.advance(1.0)
    assert sim.radii[b] == pytest.approx(0.5 * 1.3 / 1.2, rel=1e-12)


def test_sensors_report_enters_and_leaves():
    scene = {
        "dim": 2,
        "bodies": [{"pos": [0.0, 0.0], "vel": [2.0, 0.0], "radius": 0.5}],
        "sensors": [{"center": [4.0, 0.0], "radius": 1.0}],
    }
    sim = ccdsim.Simulation(scene, finder="cells")
    sim.run_until(10.0)
    ev = sim.take_sensor_events()
    # Overlap while the centre is within 1.5 m of x = 4: from t = 1.25 to 2.75.
    assert ev["t"].tolist() == [1.25, 2.75]
    assert ev["enter"].tolist() == [True, False]
    assert ev["body"].tolist() == [0, 0] and ev["sensor"].tolist() == [0, 0]
    assert len(sim.take_sensor_events()) == 0


def test_moving_walls_are_steered_and_met_exactly():
    scene = {
        "dim": 2,
        "bodies": [{"pos": [0.0, 5.0], "vel": [0.0, 0.0], "radius": 0.5}],
        "walls": [{"point": [0.0, 10.0], "normal": [0.0, -1.0]}],
        "moving_walls": [{"point": [0.0, 0.0], "normal": [0.0, 1.0]}],
    }
    sim = ccdsim.Simulation(scene, finder="cells")
    sim.set_wall_velocity(0, [0.0, 1.0])  # the floor rises at 1 m/s
    ev = sim.step()
    # Moving wall 0 is wall 1 in events: after the scene's one static wall.
    assert (float(ev["t"]), int(ev["kind"]), int(ev["b"])) == (4.5, ccdsim.WALL, 1)
    np.testing.assert_array_equal(ev["vel"][0], [0.0, 2.0])
    assert sim.wall_offset(0) == [0.0, 4.5]
    sim.set_wall_velocity(0, [0.0, 0.0])
    sim.run_until(10.0)
    assert sim.wall_offset(0) == [0.0, 4.5]
    with pytest.raises(ValueError, match="moving wall 3 does not exist"):
        sim.set_wall_velocity(3, [0.0, 0.0])
    with pytest.raises(ValueError, match="a vector of 2 numbers"):
        sim.set_wall_velocity(0, [0.0])


def test_a_ball_comes_to_rest_on_the_floor_and_slides():
    # Dropped from 1.25 m with restitution 0.5 and rest_speed 0.4 m/s: it meets the floor at
    # 5 m/s, bounces at 2.5, 1.25, 0.625, then rests (0.3125 <= 0.4) and slides at 0.5 m/s.
    scene = {
        "dim": 2,
        "settings": {"restitution": 0.5, "gravity": [0.0, -10.0], "rest_speed": 0.4},
        "bodies": [{"pos": [0.0, 1.5], "vel": [0.5, 0.0], "radius": 0.25}],
        "walls": [{"point": [0.0, 0.0], "normal": [0.0, 1.0]}],
    }
    sim = ccdsim.Simulation(scene, finder="cells")
    assert sim.run_until(10.0) == 4
    assert sim.halt is None
    np.testing.assert_allclose(sim.positions[0], [5.0, 0.25], atol=1e-12)
    np.testing.assert_array_equal(sim.velocities[0], [0.5, 0.0])
    with pytest.raises(ValueError, match="rest_speed"):
        ccdsim.Simulation({**scene, "settings": {"rest_speed": 0.4}}, finder="cells")


def test_a_ball_slides_along_a_shelf_and_flies_off_its_end_or_rolls_over_it():
    # Put a hair above a shelf (y = 1, x from 0 to 2) at 2 m/s: it rests at once, slides to
    # x = 2 and, since 2^2 > r g = 0.2 * 10, flies off and falls 1 m onto the floor. At
    # 1 m/s it rolls over the edge, turning about (2, 1) until the point stops pushing:
    # g cos(theta) = r w^2 with w^2 = v^2/r^2 + 2 (g/r)(1 - cos(theta)), so cos(theta) = 5/6.
    def shelf(speed):
        return {
            "dim": 2,
            "settings": {"restitution": 0.5, "gravity": [0.0, -10.0], "rest_speed": 1.0},
            "bodies": [{"pos": [0.5, 1.2 + 1e-6], "vel": [speed, 0.0], "radius": 0.2}],
            "walls": [
                {"point": [0.0, 0.0], "normal": [0.0, 1.0]},
                {"a": [0.0, 1.0], "b": [2.0, 1.0]},
            ],
        }

    sim = ccdsim.Simulation(shelf(2.0), finder="cells")
    land, off, floor = sim.step(), sim.step(), sim.step()
    assert (land["b"], off["b"], floor["b"]) == (1, 1, 0)
    assert off["pos"][0][0] == pytest.approx(2.0, abs=1e-12)
    np.testing.assert_array_equal(off["vel"][0], land["vel"][0])
    assert floor["t"] - off["t"] == pytest.approx(0.2**0.5, abs=1e-9)
    assert not land["pivots"].any() and not off["pivots"].any()
    assert land["rests"][0] and not off["rests"][0]
    slow = ccdsim.Simulation(shelf(1.0), finder="cells")
    land, edge, release, floor = slow.step(), slow.step(), slow.step(), slow.step()
    assert (edge["kind"], edge["b"]) == (ccdsim.WALL, 1)
    assert edge["pivots"][0] and not edge["rests"][0]
    np.testing.assert_allclose(edge["pos"][0], [2.0, 1.2], atol=1e-9)
    # It comes off at cos(theta) = 5/6, with v^2 = 1 + 2 g r (1 - 5/6), and meets the
    # shelf's end no more: its next wall is the floor.
    assert (release["kind"], release["b"]) == (ccdsim.WALL, 1)
    assert not release["pivots"][0] and not release["rests"][0]
    s = (1 - (5 / 6) ** 2) ** 0.5
    np.testing.assert_allclose(release["pos"][0], [2.0 + 0.2 * s, 1.0 + 0.2 * 5 / 6], atol=1e-9)
    assert release["vel"][0] @ release["vel"][0] == pytest.approx(1 + 4 / 6, rel=1e-9)
    assert floor["b"] == 0
    assert slow.halt is None


def test_rough_spheres_trade_translational_for_rotational_energy():
    # A head-on-and-sideways meeting of two perfectly rough discs: energy moves into spin,
    # the total is kept, and the rotational temperature is reported.
    scene = {
        "dim": 2,
        "settings": {"tangential_restitution": 1.0},
        "bodies": [
            {"pos": [0.0, 0.0], "vel": [1.0, 0.5], "radius": 0.5},
            {"pos": [3.0, 0.0], "vel": [-1.0, 0.0], "radius": 0.5, "spin": 2.0},
        ],
    }
    sim = ccdsim.Simulation(scene, finder="all-pairs")
    assert sim.spins.shape == (2, 3)
    np.testing.assert_array_equal(sim.spins[:, 2], [0.0, 2.0])
    before = sim.kinetic_energy() + sim.rotational_energy()
    ev = sim.step()
    assert ev["kind"] == ccdsim.BODY
    assert not np.array_equal(sim.spins[:, 2], [0.0, 2.0])
    after = sim.kinetic_energy() + sim.rotational_energy()
    assert abs(after - before) < 1e-14 * before
    assert sim.observables()["rotational_temperature"] > 0.0
    smooth = ccdsim.Simulation(two_balls())
    assert smooth.observables()["rotational_temperature"] is None
    assert smooth.rotational_energy() == 0.0


def test_bad_rough_fields_are_refused():
    scene = two_balls()
    scene["bodies"][0]["spin"] = [0.0, 0.0, 1.0]
    with pytest.raises(ValueError, match=r"bodies\[0\]\.spin"):
        ccdsim.Simulation(scene)
    scene = two_balls()
    scene["settings"] = {"tangential_restitution": 1.5}
    with pytest.raises(ValueError, match="tangential_restitution"):
        ccdsim.Simulation(scene)


def test_a_scenes_arrivals_enter_at_their_times_in_every_finder():
    scene = two_balls()
    # A third ball arrives at t = 2 at x = 6, moving left: it meets ball 1 (moving right
    # from x = 2.0 at t = 2 after the first collision) head on.
    scene["arrivals"] = [
        {"time": 2.0, "body": {"pos": [6.0, 0.0], "vel": [-1.0, 0.0], "radius": 0.5}}
    ]
    runs = []
    for name in ccdsim.FINDER_NAMES:
        sim = ccdsim.Simulation(scene, finder=name)
        events = sim.advance(5.0)
        assert sim.stats()["arrivals"] == 1
        assert sim.stats()["arrival_energy"] == pytest.approx(0.5 * np.pi * 0.25)
        assert len(sim.present) >= 3 and sim.present[2]
        runs.append(events)
    for other in runs[1:]:
        np.testing.assert_array_equal(other, runs[0])
    # Ball 1 leaves the first collision at t = 1 from x = 2 moving right; the arrival leaves
    # x = 6 at t = 2 moving left: they touch when the gap 6 - 3 - 2(t - 2) is 1, at t = 3.
    assert [(e["a"], e["b"]) for e in runs[0]] == [(0, 1), (1, 2)]
    assert runs[0]["t"] == pytest.approx([1.0, 3.0], abs=1e-12)
