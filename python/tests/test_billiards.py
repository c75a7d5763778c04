"""Pool shots through the Python API: the rack, a break to the end, and bad input."""

import pytest

import ccdsim
from ccdsim import billiards


def test_a_nine_ball_break_plays_to_the_end():
    balls = billiards.rack("nine-ball", seed=1)
    assert [b[0] for b in balls][:2] == ["cue", "1"] and len(balls) == 10
    result = billiards.shot(balls, speed=8.0, phi=billiards.aim(balls, "1"))
    kinds = [k for _, k, _ in result.events]
    assert kinds.count("ball_ball") >= 9
    # The first collision is the cue ball on the 1 ball.
    first = next(e for e in result.events if e[1] == "ball_ball")
    assert sorted(first[2]) == ["1", "cue"]
    times = [t for t, _, _ in result.events]
    assert times == sorted(times) and result.time == times[-1]
    assert set(result.positions) == {b[0] for b in balls}
    for name, pocket in result.pocketed.items():
        assert pocket in {"lb", "lc", "lt", "rb", "rc", "rt"}
        assert any(k == "ball_pocket" and a[0] == name for _, k, a in result.events)


def test_the_same_shot_gives_the_same_events():
    balls = billiards.rack("eight-ball", seed=3)
    assert len(balls) == 16
    one = billiards.shot(balls, speed=7.0, phi=billiards.aim(balls, "1"), b=0.2)
    two = billiards.shot(balls, speed=7.0, phi=billiards.aim(balls, "1"), b=0.2)
    assert one == two


def test_bad_shots_are_refused_with_the_reason():
    with pytest.raises(ValueError, match="overlap"):
        billiards.shot([("cue", 0.5, 0.5), ("1", 0.51, 0.5)], speed=1.0, phi=0.0)
    with pytest.raises(ValueError, match="not on the table"):
        billiards.shot([("cue", 2.0, 0.5)], speed=1.0, phi=0.0)
    with pytest.raises(ValueError, match="no ball named"):
        billiards.shot([("white", 0.5, 0.5)], speed=1.0, phi=0.0)
    with pytest.raises(ValueError, match="miss"):
        billiards.shot([("cue", 0.5, 0.5)], speed=1.0, phi=0.0, a=2.0, b=2.0)
    with pytest.raises(ValueError, match="nine-ball"):
        billiards.rack("snooker")
    assert ccdsim.billiards is billiards


def test_the_frictional_model_throws_a_cut_ball():
    balls = [("cue", 0.5, 0.5), ("1", 0.5, 1.0)]
    plain = billiards.shot(balls, speed=2.0, phi=88.0)
    frictional = billiards.shot(balls, speed=2.0, phi=88.0, ball_ball={"friction": 0.06})
    assert plain.positions["1"] != frictional.positions["1"]
    assert frictional == billiards.shot(
        balls, speed=2.0, phi=88.0, ball_ball={"restitution": 0.95, "friction": 0.06}
    )
    with pytest.raises(ValueError, match="restitution"):
        billiards.shot(balls, speed=2.0, phi=88.0, ball_ball={"restitution": 2.0})
    with pytest.raises(ValueError, match="unknown keys"):
        billiards.shot(balls, speed=2.0, phi=88.0, ball_ball={"mu": 0.1})


def test_eight_ball_breaks_whose_balls_press_together_play_to_the_end():
    pressed = 0
    for seed in range(1, 9):
        balls = billiards.rack("eight-ball", seed=seed)
        result = billiards.shot(balls, speed=8.0, phi=billiards.aim(balls, "1"))
        assert result.time > 0 and result.pressing_energy < 1e-5
        pressed += result.pressings
    assert pressed > 0


def test_a_recorded_shot_writes_its_run_file(tmp_path):
    balls = billiards.rack("nine-ball", seed=1)
    path = tmp_path / "break.ccd"
    recorded = billiards.shot(balls, speed=8.0, phi=billiards.aim(balls, "1"), record=str(path))
    assert recorded == billiards.shot(balls, speed=8.0, phi=billiards.aim(balls, "1"))
    data = path.read_bytes()
    assert data[:8] == b"CCDSIMRF" and int.from_bytes(data[8:12], "little") == 16
    # The strike, every event and the end, 135 bytes each, after the header.
    header = int.from_bytes(data[16:24], "little")
    assert len(data) == 24 + header + 135 * (len(recorded.events) + 2)
    with pytest.raises(ValueError, match="pool shot"):
        ccdsim.read_run(str(path))
    with pytest.raises(ValueError, match="overlap"):
        billiards.shot([("cue", 0.5, 0.5), ("1", 0.51, 0.5)], 1.0, 0.0, record=str(tmp_path / "x"))
    assert not (tmp_path / "x").exists()


def test_every_finder_plays_a_break_the_same_and_writes_the_same_file(tmp_path):
    balls = billiards.rack("eight-ball", seed=4)
    phi = billiards.aim(balls, "1")
    files = {}
    results = {}
    for finder in ["all-pairs", "sedgewick", "cells", "bvh"]:
        path = tmp_path / f"{finder}.ccd"
        results[finder] = billiards.shot(balls, speed=8.0, phi=phi, record=str(path), finder=finder)
        files[finder] = path.read_bytes()
    assert len({bytes(f) for f in files.values()}) == 1
    assert all(r == results["all-pairs"] for r in results.values())
    assert len(results["cells"].events) > 1000
    with pytest.raises(ValueError, match="unknown finder"):
        billiards.shot(balls, speed=8.0, phi=phi, finder="grid")
