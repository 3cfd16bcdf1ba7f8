"""Clips are taken in simulated time: they play at the true speed whatever the machine
managed, and their memory is bounded."""

from __future__ import annotations

import os

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

import pygame  # noqa: E402
import pytest  # noqa: E402

from chainfountain.app.capture import GIF_FRAME_BUDGET, ClipRecorder, unique_path  # noqa: E402


@pytest.fixture
def surface():
    pygame.display.init()
    return pygame.Surface((64, 48))


def test_one_frame_per_interval_of_simulated_time_however_the_frames_come(surface,
                                                                          tmp_path):
    clip = ClipRecorder(tmp_path / "c.gif", fps=10.0)
    t = 0.0
    for dt in [0.001] * 200 + [0.03] * 20 + [0.0] * 50:  # fast, slow, paused
        clip.offer(surface, t)
        t += dt
    clip.offer(surface, t)
    assert clip.frames == int(t * 10.0 + 1e-6) + 1  # 0.8 s: 9 frames
    assert clip.seconds == pytest.approx(clip.frames / 10.0)
    assert clip.wait() and (tmp_path / "c.gif").stat().st_size > 100
    from PIL import Image

    with Image.open(tmp_path / "c.gif") as im:  # it plays as long as it was simulated
        ms = 0
        for k in range(im.n_frames):
            im.seek(k)
            ms += im.info["duration"]
    assert ms == pytest.approx(1000 * clip.seconds)


def test_a_reset_keeps_recording_and_a_jump_is_not_a_slow_machine(surface, tmp_path):
    clip = ClipRecorder(tmp_path / "c.gif", fps=10.0)
    for t in (0.0, 0.1, 0.2):
        clip.offer(surface, t)
    assert clip.frames == 3
    clip.offer(surface, 0.0)  # R: the simulation starts again
    assert clip.frames == 4
    clip.offer(surface, 0.1)
    assert clip.frames == 5
    clip.offer(surface, 100.0)  # a jump adds at most 4 frames
    assert clip.frames == 9
    clip.offer(surface, 100.1)
    assert clip.frames == 10
    clip.stop()


def test_a_gif_clip_stops_itself_within_its_memory_budget(surface, tmp_path):
    crop = pygame.Rect(0, 0, 64, 48)
    clip = ClipRecorder(tmp_path / "c.gif", fps=10.0, crop=crop)
    assert clip.max_frames == min(1200, int(GIF_FRAME_BUDGET / (64 * 48)))
    big = ClipRecorder(tmp_path / "d.gif", fps=20.0, crop=pygame.Rect(0, 0, 590, 760))
    assert big.max_frames * 590 * 760 <= GIF_FRAME_BUDGET
    assert big.max_frames / 20.0 > 15  # still a useful clip: over 15 s
    for c in (clip, big):
        c.stop()


def test_two_captures_in_one_second_get_two_names_before_either_is_written(tmp_path):
    # the PNG is written in a background thread: the second F12 of a second must not
    # take the first one's name while that file does not exist yet
    a = unique_path(tmp_path, "shot", ".png")
    b = unique_path(tmp_path, "shot", ".png")
    assert a != b and not a.exists() and not b.exists()
    (tmp_path / "other.png").write_bytes(b"x")
    assert unique_path(tmp_path, "other", ".png").name == "other-2.png"
