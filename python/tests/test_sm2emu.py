"""Tests of the Python module sm2emu (docs/python.md), run by ctest as python_pytest.

Expected values come from outside the emulator: D3D9's documented token encoding, arithmetic
done here by hand or in NumPy float32, the colour bytes of a clear, and the probe pixels of
samples/scenes/probes.txt (computed from each scene's geometry).
"""
import importlib.util
import os
import shutil
import subprocess

import numpy as np
import pytest

import sm2emu

SOURCE_DIR = os.environ.get("SM2_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(SOURCE_DIR, "samples", "scenes")

MAD_VS = """vs_2_0
dcl_position v0
mad oPos, v0, c0, c1
"""


def load_check_probes():
    spec = importlib.util.spec_from_file_location("check_probes", os.path.join(SOURCE_DIR, "scripts", "check_probes.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --- assemble / disassemble / validate ----------------------------------------------------------

def test_assemble_gives_the_d3d9_tokens():
    tokens = np.frombuffer(sm2emu.assemble(MAD_VS), dtype="<u4")
    assert [hex(t) for t in tokens] == [hex(t) for t in [
        0xFFFE0200,                          # vs_2_0
        0x0200001F, 0x80000000, 0x900F0000,  # dcl_position v0
        0x04000004, 0xC00F0000, 0x90E40000, 0xA0E40000, 0xA0E40001,  # mad oPos, v0, c0, c1
        0x0000FFFF,                          # end
    ]]


def test_disassemble_round_trips_bytes_and_token_arrays():
    data = sm2emu.assemble(MAD_VS)
    assert sm2emu.disassemble(data) == MAD_VS
    assert sm2emu.disassemble(np.frombuffer(data, dtype="<u4")) == MAD_VS
    assert sm2emu.disassemble(list(np.frombuffer(data, dtype="<u4"))) == MAD_VS


def test_assemble_error_names_line_and_column():
    with pytest.raises(sm2emu.Error, match=r"shader\.asm:2:\d+: error"):
        sm2emu.assemble("ps_2_0\nbogus r0, r1\n", file_name="shader.asm")
    assert issubclass(sm2emu.Error, ValueError)


def test_validate_lists_violations_by_rule():
    assert sm2emu.validate(MAD_VS) == []
    violations = sm2emu.validate("ps_2_0\nmov oC0, r0\n")
    assert [(v["rule"], v["instruction"], v["line"]) for v in violations] == [("temp-initialized", 0, 2)]
    # The same shader as bytecode (assembled without validation): the same rule, no line.
    data = sm2emu.assemble("ps_2_0\nmov oC0, r0\n", validate=False)
    assert [(v["rule"], v["line"]) for v in sm2emu.validate(data)] == [("temp-initialized", 0)]
    with pytest.raises(sm2emu.Error, match="temp-initialized"):
        sm2emu.assemble("ps_2_0\nmov oC0, r0\n")


def test_validate_slot_budget_follows_max_slots():
    body = "".join("add r0, r0, c0\n" for _ in range(100))
    shader = "ps_2_0\nmov r0, c0\n" + body + "mov oC0, r0\n"
    # ps_2_0: 64 arithmetic slots, 96 in all; the 65th add (instruction 64) is the first over.
    violations = sm2emu.validate(shader)
    assert [(v["rule"], v["instruction"], v["line"]) for v in violations] == [
        ("slot-budget", 64, 66), ("slot-budget", 96, 98)]
    assert "the limit is 64" in violations[0]["message"]
    assert sm2emu.validate(shader, max_slots=512) == []


# --- run ----------------------------------------------------------------------------------------

def test_run_mad_per_lane_by_hand():
    v0 = np.array([[1, 2, 3, 4], [-1, 0.5, 0, 2]], dtype=np.float32)
    out = sm2emu.run(MAD_VS, inputs={"v0": v0}, constants={"c0": [2, 3, 4, 5], 1: [10, 20, 30, 40]})
    assert set(out) == {"oPos"}
    assert out["oPos"].dtype == np.float32
    assert out["oPos"].tolist() == [[12, 26, 42, 60], [8, 21.5, 30, 50]]


def test_run_many_lanes_match_numpy_float32():
    # 40 lanes: three batches of 16, the last one partial.
    rng = np.random.default_rng(7)
    v0 = rng.uniform(-100, 100, size=(40, 4)).astype(np.float32)
    c0 = np.float32([0.1, -3.5, 7.25, 1e-3])
    c1 = np.float32([1, 2, 3, 4])
    for engine in ("interpreter", "jit"):
        out = sm2emu.run(MAD_VS, inputs={"v0": v0}, constants={0: c0, 1: c1}, engine=engine)
        expected = v0 * c0 + c1  # two float32 roundings, as mad without fusing
        np.testing.assert_array_equal(out["oPos"], expected)


def test_run_mov_pixel_shader_broadcast_and_defaults():
    shader = "ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, r0\nmov oC1, c2\n"
    out = sm2emu.run(shader, inputs={"t0": [0.25, 0.75]}, constants={"c2": [1, 2, 3, 4]}, lanes=4)
    # t0 has x, y given; z, w keep the input default (0, 1).
    assert out["oC0"].tolist() == [[0.25, 0.75, 0, 1]] * 4
    assert out["oC1"].tolist() == [[1, 2, 3, 4]] * 4
    assert out["killed"].tolist() == [False] * 4


def test_run_texkill_marks_killed_lanes():
    shader = "ps_2_0\ndcl t0\ntexkill t0\nmov oC0, t0\n"
    t0 = [[1, 1, 1, 1], [-1, 1, 1, 1], [1, 1, -0.5, 1], [0, 0, 0, 0]]
    out = sm2emu.run(shader, inputs={"t0": t0})
    assert out["killed"].tolist() == [False, True, True, False]


def test_run_precision_modes():
    shader = "ps_2_0\nmul_pp r0, c0, c1\nmov oC0, r0\n"
    third = 1.0 / 3.0
    fp32 = sm2emu.run(shader, constants={0: [third, 0, 0, 0], 1: [1, 1, 1, 1]})["oC0"]
    fp16 = sm2emu.run(shader, constants={0: [third, 0, 0, 0], 1: [1, 1, 1, 1]}, precision="fp16")["oC0"]
    fp64 = sm2emu.run("vs_2_0\ndcl_position v0\nmul oPos, v0, v0\n", inputs={"v0": [third, 0, 0, 0]},
                      precision="fp64")["oPos"]
    assert fp32[0, 0] == np.float32(third)
    assert fp16[0, 0] == np.float32(np.float16(third))  # 0.333251953125, s10e5
    assert fp64.dtype == np.float64 and fp64[0, 0] == third * third


def test_run_flow_constants():
    shader = "vs_2_0\ndcl_position v0\nmov r0, c0\nrep i0\nadd r0, r0, c1\nendrep\nif b0\nmul r0, r0, c2\nendif\nmov oPos, r0\n"
    out = sm2emu.run(shader, constants={0: [1, 1, 1, 1], 1: [1, 2, 3, 4], 2: [10, 10, 10, 10]},
                     integers={"i0": [3, 0, 0, 0]}, booleans={"b0": True})
    assert out["oPos"].tolist() == [[40, 70, 100, 130]]  # (1 + 3 * c1) * 10


def test_run_rejects_bad_registers():
    with pytest.raises(sm2emu.Error, match="v16"):
        sm2emu.run(MAD_VS, inputs={"v16": [1]})
    with pytest.raises(sm2emu.Error, match="c300"):
        sm2emu.run(MAD_VS, constants={"c300": [1]})
    with pytest.raises(sm2emu.Error, match="lanes"):
        sm2emu.run(MAD_VS, inputs={"v0": np.zeros((3, 4))}, lanes=2)
    with pytest.raises(ValueError, match="precision"):
        sm2emu.run(MAD_VS, precision="fp8")


# --- replay and the device state ----------------------------------------------------------------

CLEAR_2X2 = """sm2cs 1
CreateDevice 2 2 A8R8G8B8
SetRenderState CULLMODE NONE
SetSamplerState 1 MINFILTER LINEAR
SetScissorRect 0 0 1 2
SetVertexShaderConstantF 4 f32[ 1 2 3 4   5 6 7 8 ]
Clear TARGET 0x80FF4020 1 0
Present
SetViewport 0 0 2 1 0.25 0.75
Clear TARGET 0xFF000000 1 0
Present
"""


def test_replay_2x2_clear_gives_the_colour_bytes():
    device = sm2emu.Device()
    result = device.replay_text(CLEAR_2X2)
    assert result.ok and result.refused == 0 and result.calls == 10
    frames = result.frames
    assert len(frames) == 2 and device.frames_presented == 2
    assert frames[0].shape == (2, 2, 4) and frames[0].dtype == np.uint8
    assert frames[0].reshape(-1, 4).tolist() == [[0xFF, 0x40, 0x20, 0x80]] * 4  # R G B A of 0xAARRGGBB
    # Clear fills the viewport only: the top row (the scissor test is off).
    assert frames[1].reshape(-1, 4).tolist() == [[0, 0, 0, 0xFF]] * 2 + [[0xFF, 0x40, 0x20, 0x80]] * 2
    assert len(result.frame_stats) == 2 and result.frame_stats[0]["draws"] == 0


def test_device_state_after_replay():
    device = sm2emu.Device()
    device.replay_text(CLEAR_2X2)
    assert device.render_state("CULLMODE") == 1            # D3DCULL_NONE
    assert device.render_state("D3DRS_ZFUNC") == 4         # default D3DCMP_LESSEQUAL
    assert device.render_states()["CULLMODE"] == 1
    assert device.sampler_state(1, "MINFILTER") == 2       # D3DTEXF_LINEAR
    assert device.sampler_state(0, "MINFILTER") == 1       # default POINT
    assert device.viewport == {"x": 0, "y": 0, "width": 2, "height": 1, "min_z": 0.25, "max_z": 0.75}
    assert device.scissor_rect == (0, 0, 1, 2)
    assert device.vs_constants(4, 2).tolist() == [[1, 2, 3, 4], [5, 6, 7, 8]]
    assert device.vs_constants().shape == (256, 4)
    assert device.ps_constants(0, 1).tolist() == [[0, 0, 0, 0]]
    assert device.vs_flow_constants["booleans"] == [False] * 16
    with pytest.raises(sm2emu.Error):
        device.render_state("NOSUCHSTATE")


def test_refused_calls_are_diagnostics():
    result = sm2emu.Device().replay_text("sm2cs 1\nCreateDevice 2 2 A8R8G8B8\nSetTexture 0 missing\nPresent\n",
                                         file_name="bad.sm2cs")
    assert not result.ok and result.refused == 1
    assert result.diagnostics[0].startswith("bad.sm2cs:3: D3DERR_INVALIDCALL: SetTexture")
    assert len(result.frames) == 1


def test_replay_scene_matches_probes_and_sm2_png(tmp_path):
    stream = os.path.join(SCENES, "01_gouraud_triangle.sm2cs")
    result = sm2emu.replay(stream, threads=2)
    assert result.ok and len(result.frames) == 1
    frame = result.frames[0]
    assert frame.shape == (256, 256, 4)
    check_probes = load_check_probes()
    probes = [p for p in check_probes.parse_probes(os.path.join(SCENES, "probes.txt"))
              if p[1] == "01_gouraud_triangle.sm2cs"]
    assert len(probes) >= 5
    for _, _, _, x, y, expected, tol, why in probes:
        got = frame[y, x].astype(int)
        assert np.all(np.abs(got - np.array(expected)) <= tol), (x, y, why)
    # The device's back buffer after the replay, as floats.
    assert result.device.frames_presented == 1
    # The same bytes as sm2 replay's PNG, and as a replay of the packed (.sm2cb) stream.
    tool = os.environ.get("SM2_TOOL")
    if not tool or not shutil.which(tool):
        pytest.skip("SM2_TOOL not set: the sm2 comparison needs the built tool")
    subprocess.run([tool, "replay", stream, "-o", str(tmp_path / "frames"), "--quiet"], check=True)
    _, _, rows = check_probes.read_png(str(tmp_path / "frames" / "frame_0000.png"))
    np.testing.assert_array_equal(frame, np.array(rows, dtype=np.uint8))
    packed = tmp_path / "scene.sm2cb"
    subprocess.run([tool, "cs", "pack", stream, "-o", str(packed)], check=True)
    # A packed stream keeps no side-file paths; scene 01 has none.
    np.testing.assert_array_equal(sm2emu.replay(str(packed)).frames[0], frame)


def test_save_surface_and_surface_values():
    text = """sm2cs 1
CreateDevice 2 2 A8R8G8B8
CreateRenderTarget rt 2 1 A8R8G8B8
SetRenderTarget 0 rt
Clear TARGET 0xFF336699 1 0
SaveSurface rt "rt.png"
"""
    device = sm2emu.Device()
    assert device.replay_text(text).ok
    assert device.saved["rt.png"].reshape(-1, 4).tolist() == [[0x33, 0x66, 0x99, 0xFF]] * 2
    values = device.surface("rt")
    assert values.shape == (1, 2, 4)
    np.testing.assert_array_equal(values[0, 0], np.float32([0x33, 0x66, 0x99, 0xFF]) / np.float32(255))
    assert device.has_resource("rt") and not device.has_resource("nothing")
