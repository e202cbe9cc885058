"""The Python module (docs/reference.md section 8) against the aesim program: the same library, so the same
events, decisions and messages; a scene given as an array; the GIL released during a run; Ctrl-C.

Environment: AESIM_BINARY, AESIM_SOURCE_DIR, and PYTHONPATH holding the built module.
"""
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import aesim

AESIM = os.environ["AESIM_BINARY"]
SCENES = os.path.join(os.environ["AESIM_SOURCE_DIR"], "scenes")
ENV = dict(os.environ, SYSTEMC_DISABLE_COPYRIGHT_MESSAGE="1")


def cli(*args, cwd=None):
    return subprocess.run([AESIM, *args], capture_output=True, text=True, env=ENV, cwd=cwd)


def csv_events(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, dtype=np.int64, ndmin=2)


def test_run_gives_the_programs_events_and_summary(tmp_path):
    scene = os.path.join(SCENES, "natural.pgm")
    done = cli("run", "--scene", scene, "--duration", "300ms", "--set", "pixel.c_int=80fF",
               "--csv", str(tmp_path / "e.csv"), "--summary", str(tmp_path / "s.json"))
    assert done.returncode == 0, done.stderr
    r = aesim.run(scene=scene, duration="300ms", set={"pixel.c_int": "80fF"})
    assert r.events.dtype == np.dtype([("t", "<f8"), ("x", "<u2"), ("y", "<u2"), ("tile", "<u4"), ("flags", "u1")])
    csv = csv_events(tmp_path / "e.csv")
    assert len(r.events) == len(csv) > 1000
    assert np.array_equal(np.rint(r.events["t"] * 1e6).astype(np.int64), csv[:, 0])
    for i, name in enumerate(["x", "y", "tile", "flags"], start=1):
        assert np.array_equal(r.events[name].astype(np.int64), csv[:, i]), name
    summary = json.loads((tmp_path / "s.json").read_text())
    for key in ["events_fired", "events_delivered", "events_collided", "offered_load", "throughput", "tau_s"]:
        assert r.summary[key] == summary[key], key
    assert r.summary["sensor"]["pixel"]["c_int"] == pytest.approx(80e-15)
    assert r.truth is None


def test_the_version_is_the_programs():
    assert cli("--version").stdout == f"aesim {aesim.__version__}\n"


def test_warnings_are_the_programs_raised_as_runtime_warnings(tmp_path):
    # aesim_pixel is calibrated from 1 fA to 1 nA; the gradient at i_max = 2 nA leaves that range.
    scene = os.path.join(SCENES, "gradient.pgm")
    done = cli("run", "--sensor", "aesim_pixel", "--scene", scene, "--duration", "10ms", "--set", "pixel.i_max=2nA",
               "--summary", str(tmp_path / "s.json"))
    assert done.returncode == 0, done.stderr
    assert done.stderr.startswith("aesim: warning: ")
    with pytest.warns(RuntimeWarning) as caught:
        aesim.run(sensor="aesim_pixel", scene=scene, duration="10ms", set={"pixel.i_max": "2nA"})
    assert [str(w.message) for w in caught] == [done.stderr[len("aesim: warning: "):].rstrip("\n")]


def test_a_scene_array_is_the_same_scene_as_its_file(tmp_path):
    img = np.zeros((32, 48), np.uint8)
    img[4:20, 10:40] = 200
    img[20:28, :] = 37
    path = tmp_path / "s.pgm"
    path.write_bytes(b"P5\n48 32\n255\n" + img.tobytes())
    settings = {"array.rows": 32, "array.cols": 48, "array.tile_rows": 16, "array.tile_cols": 16}
    from_file = aesim.run(scene=str(path), duration="200ms", set=settings, truth=True)
    from_array = aesim.run(scene=img, duration="200ms", set=settings, truth=True)
    assert len(from_file.events) > 100
    assert np.array_equal(from_file.events, from_array.events)
    for name in from_file.truth.dtype.names:  # t_deliver is NaN for an event never delivered
        assert np.array_equal(from_file.truth[name], from_array.truth[name], equal_nan=name == "t_deliver"), name
    # Floats are fractions of full scale: the same light as the 8-bit codes.
    as_float = aesim.run(scene=img / 255.0, duration="200ms", set=settings)
    assert np.array_equal(as_float.events, from_file.events)
    # Truth: every firing, with its fate; the delivered ones are the events.
    assert set(np.unique(from_file.truth["fate"])) <= {"delivered", "collided", "ghost", "dropped", "pending"}
    assert (from_file.truth["fate"] == "delivered").sum() == (from_file.events["flags"] == 0).sum()


def test_an_array_saved_by_numpy_is_the_same_scene_as_the_array(tmp_path):
    # numpy.save's files, written by NumPy itself, in every type, order and byte order the module
    # takes: the file's events are the array's, bit for bit.
    rng = np.random.default_rng(7)
    light = rng.random((32, 48))
    settings = {"array.rows": 32, "array.cols": 48, "array.tile_rows": 16, "array.tile_cols": 16}
    arrays = {"u1": (light * 255).astype(np.uint8), "u2be": (light * 65535).astype(">u2"),
              "f2": light.astype(np.float16), "f4_fortran": np.asfortranarray(light.astype(np.float32)),
              "f8": light, "bool": light > 0.5}
    for name, array in arrays.items():
        path = tmp_path / (name + ".npy")
        np.save(path, array)
        from_array = aesim.run(scene=array, duration="100ms", set=settings)
        from_file = aesim.run(scene=str(path), duration="100ms", set=settings)
        assert len(from_file.events) > 100, name
        assert np.array_equal(from_file.events, from_array.events), name
    # A 3-D array saved is a moving scene: its frames one after the other at scene.frame_rate.
    np.save(tmp_path / "stack.npy", np.stack([light, light[::-1], light[:, ::-1]]).astype(np.float32))
    moving = aesim.run(scene=str(tmp_path / "stack.npy"), duration="100ms", set={**settings, "scene.frame_rate": 30})
    still = aesim.run(scene=light.astype(np.float32), duration="100ms", set=settings)
    assert len(moving.events) > 100
    assert not np.array_equal(moving.events, still.events)
    first_frame = moving.events[moving.events["t"] < 1 / 30]
    assert np.array_equal(first_frame, still.events[still.events["t"] < 1 / 30])
    # The same 3-D array given as it is: the same moving scene, event for event.
    in_memory = aesim.run(scene=np.load(tmp_path / "stack.npy"), duration="100ms", set={**settings, "scene.frame_rate": 30})
    assert np.array_equal(in_memory.events, moving.events)


@pytest.mark.parametrize("kwargs,option", [
    ({"set": {"pixel.c_int": "-5fF"}}, ["--set", "pixel.c_int=-5fF"]),
    ({"set": {"pixel.no_such_key": "1"}}, ["--set", "pixel.no_such_key=1"]),
    ({"duration": "soon"}, ["--duration", "soon"]),
    ({"sensor": "no_such_sensor"}, ["--sensor", "no_such_sensor"]),
    ({"scene": "/no/such/scene.pgm"}, ["--scene", "/no/such/scene.pgm"]),
])
def test_bad_input_raises_value_error_with_the_programs_message(kwargs, option, tmp_path):
    done = cli("run", "--summary", str(tmp_path / "s.json"), *option)
    assert done.returncode == 2
    message = done.stderr.strip().splitlines()[-1]
    assert message.startswith("aesim: ")
    with pytest.raises(ValueError) as e:
        aesim.run(**kwargs)
    assert str(e.value) == message[len("aesim: "):]


def test_bad_arrays_are_value_errors():
    for bad, words in [(np.zeros((2, 2, 2, 2)), "2-D"), (np.zeros((0, 2, 2)), "of 0 frames"),
                       (np.array([[[1.0]], [[-1.0]]]), "not negative"), (np.array([[1.0, -1.0]]), "not negative"),
                       (np.array([[np.nan]]), "finite"), (np.zeros((0, 3)), "of 0 rows and 3 columns"),
                       (np.zeros((4, 4), np.int64), "8 or 16 bit")]:
        with pytest.raises(ValueError, match=words):
            aesim.run(scene=bad, duration="10ms")
    # The emulator takes its frames from an array by the same rule.
    with pytest.raises(ValueError, match="input: an array of 0 frames"):
        aesim.emulate(np.zeros((0, 4, 4)))


def test_a_colour_picture_array_is_refused_as_its_npy_file_is(tmp_path):
    # What imaging libraries hand NumPy, colour last (rows, columns, 3 or 4), would read as 48
    # frames of 64x3 pixels: refused in the same words as the same array saved as a .npy scene.
    picture = np.zeros((48, 64, 3), np.uint8)
    np.save(tmp_path / "rgb.npy", picture)
    done = cli("run", "--scene", str(tmp_path / "rgb.npy"), "--summary", str(tmp_path / "s.json"))
    assert done.returncode == 2
    assert "(48, 64, 3) array reads as colour channels last" in done.stderr
    for rgb in (picture, np.zeros((48, 64, 4), np.float32)):
        with pytest.raises(ValueError, match=r"array reads as colour channels last .* 0.2126 R"):
            aesim.run(scene=rgb, duration="10ms")
        with pytest.raises(ValueError, match="input: a .* array reads as colour channels last"):
            aesim.emulate(rgb)
    # A stack of small frames is a moving scene still, four columns wide or not.
    for frames in (np.full((3, 8, 8), 0.5), np.full((6, 4, 4), 0.5), np.full((6, 8, 3), 0.5)[:3]):
        assert len(aesim.run(scene=frames, duration="10ms").events) > 0


def test_emulate_and_classify_mirror_the_commands(tmp_path):
    letter = os.path.join(SCENES, "letters", "O.pgm")
    done = cli("emulate", letter, "--queue", str(tmp_path / "q.txt"), "--out", str(tmp_path / "o.aedat"))
    assert done.returncode == 0, done.stderr
    queue = np.loadtxt(tmp_path / "q.txt", dtype=np.int64, ndmin=2)
    events = aesim.emulate(letter)
    assert np.array_equal(np.stack([events["x"], events["y"]], axis=1).astype(np.int64), queue)
    decided = json.loads(cli("classify", str(tmp_path / "o.aedat"), "--json", "--center", "500").stdout)
    assert aesim.classify(str(tmp_path / "o.aedat"), center=500) == decided
    # The emulator's events as an array: the same decision as from its file.
    from_array = aesim.classify(events, size="32x32", center=500)
    assert from_array["winner"] == decided["winner"] == "O"
    assert from_array["events_used"] == decided["events_used"]
    with pytest.raises(ValueError, match="size"):
        aesim.classify(events)


def test_sweep_returns_the_programs_rows(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text('sensor = "aloha"\nduration = "100ms"\n[[group]]\nname = "c_int"\nscene = "%s"\n'
                    '"pixel.c_int" = ["50fF", "100fF"]\n' % os.path.join(SCENES, "natural.pgm"))
    done = cli("sweep", str(spec), "-o", str(tmp_path / "cli.csv"), "--no-chart")
    assert done.returncode == 0, done.stderr
    rows = aesim.sweep(str(spec))
    assert len(rows) == 2
    cli_rows = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    assert [r["events_fired"] for r in rows] == [float(v) for v in cli_rows["events_fired"]]
    # Twice the capacitance, half the events (eq. 2), within the mismatch and the random start.
    assert rows[0]["events_fired"] / rows[1]["events_fired"] == pytest.approx(2.0, rel=0.05)


def test_a_run_releases_the_gil():
    # A run long enough to see another thread tick through it: the simulated time grows until the
    # run takes over 0.2 s of wall time, whatever the machine's speed.
    for duration in ("4s", "16s", "64s"):
        ticks = []
        stop = threading.Event()

        def count():
            while not stop.is_set():
                ticks.append(time.monotonic())
                time.sleep(0.001)

        counter = threading.Thread(target=count)
        counter.start()
        started = time.monotonic()
        aesim.run(scene=np.ones((256, 256)), duration=duration, set={"array.rows": 256, "array.cols": 256})
        ended = time.monotonic()
        stop.set()
        counter.join()
        if ended - started > 0.2:
            break
    during = [t for t in ticks if started < t < ended]
    assert ended - started > 0.2
    # The other thread ran all through the run (at ~1 ms a tick when it has the interpreter).
    assert len(during) > 0.3 * (ended - started) / 0.001


def test_ctrl_c_interrupts_a_long_run():
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        # About 10^9 events: minutes of work, stopped at the next window.
        aesim.run(scene=np.ones((256, 256)), duration="100s", set={"array.rows": 256, "array.cols": 256},
                  max_events="1e10")
    assert time.monotonic() - started < 10
    # A run of the cycle rung (SystemC) stops too, between slices of its simulated time.
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        aesim.run(scene=os.path.join(SCENES, "natural.pgm"), duration="200s", set={"sim.fidelity": "cycle"})
    assert time.monotonic() - started < 10
    # Python's own handler is back, and the next call runs.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert len(aesim.run(duration="50ms").events) > 0


def test_a_camera_files_exif_orientation_turns_the_scene_as_pillow_shows_it(tmp_path):
    # Six 16x16 blocks of distinct greys, 3 across and 2 down, stored with each EXIF orientation by
    # Pillow; Pillow's exif_transpose is the picture a viewer shows. aesim's events, block by block,
    # must rank as that picture's blocks do (a pixel fires at a rate proportional to its light).
    from PIL import Image, ImageOps
    codes = np.array([[30, 70, 110], [150, 190, 230]], np.uint8)
    stored = np.kron(codes, np.ones((16, 16), np.uint8))
    for orientation in range(1, 9):
        path = tmp_path / f"turned{orientation}.png"
        exif = Image.Exif()
        exif[0x0112] = orientation
        Image.fromarray(stored, "L").save(path, exif=exif.tobytes())
        shown = np.asarray(ImageOps.exif_transpose(Image.open(path)))
        rows, cols = shown.shape
        r = aesim.run(scene=str(path), duration="200ms",
                      set={"array.rows": str(rows), "array.cols": str(cols), "pixel.mismatch": "0"})
        counts = np.zeros((rows, cols))
        np.add.at(counts, (r.events["y"], r.events["x"]), 1)
        block_counts = counts.reshape(rows // 16, 16, cols // 16, 16).sum(axis=(1, 3))
        block_codes = shown.reshape(rows // 16, 16, cols // 16, 16)[:, 0, :, 0]
        assert np.array_equal(np.argsort(block_counts, axis=None), np.argsort(block_codes, axis=None)), orientation
