"""Orbit camera: matrices, presets, navigation, framing, mouse rays, mouse mappings."""

import numpy as np
import pytest

from jackpy.ui.camera import NavAction, OrbitCamera, navigation_action

W, H = 640, 480


def project(cam: OrbitCamera, p: np.ndarray) -> np.ndarray:
    """World point to NDC (x, y, z)."""
    clip = cam.projection_matrix(W / H) @ cam.view_matrix() @ np.append(p, 1.0)
    return clip[:3] / clip[3]


def to_pixel(ndc: np.ndarray) -> np.ndarray:
    return np.array([(ndc[0] + 1.0) * 0.5 * W, (1.0 - ndc[1]) * 0.5 * H])


def test_view_matrix_puts_eye_at_origin_and_target_ahead():
    cam = OrbitCamera(target=np.array([0.3, 1.0, -0.2]), distance=2.5, yaw=0.7, pitch=0.3)
    view = cam.view_matrix()
    assert np.allclose(view @ np.append(cam.eye(), 1.0), [0, 0, 0, 1])
    assert np.allclose(view @ np.append(cam.target, 1.0), [0, 0, -2.5, 1])
    assert np.allclose(view[:3, :3] @ view[:3, :3].T, np.eye(3))
    assert np.allclose(view @ cam.camera_to_world(), np.eye(4))


@pytest.mark.parametrize("name, eye_dir, screen_up", [
    ("front", [0, 0, 1], [0, 1, 0]),
    ("side", [1, 0, 0], [0, 1, 0]),
    ("back", [0, 0, -1], [0, 1, 0]),
    ("top", [0, 1, 0], [0, 0, -1]),
    ("iso", np.ones(3) / np.sqrt(3), None),
])
def test_presets_look_from_the_named_direction(name, eye_dir, screen_up):
    cam = OrbitCamera(target=np.zeros(3), distance=2.0)
    cam.set_preset(name)
    assert np.allclose(cam.eye(), 2.0 * np.asarray(eye_dir))
    if screen_up is not None:
        assert np.allclose(cam.rotation()[:, 1], screen_up, atol=1e-12)


def test_target_projects_to_centre_in_both_projections():
    cam = OrbitCamera(target=np.array([0.0, 1.0, 0.0]), distance=3.0, yaw=0.4, pitch=0.2)
    assert np.allclose(project(cam, cam.target)[:2], 0.0)
    cam.orthographic = True
    assert np.allclose(project(cam, cam.target)[:2], 0.0)


def test_orthographic_keeps_apparent_size_at_target():
    cam = OrbitCamera(target=np.zeros(3), distance=3.0)
    p = np.array([0.0, 0.5, 0.0])
    y_persp = project(cam, p)[1]
    cam.orthographic = True
    assert project(cam, p)[1] == pytest.approx(y_persp)


def test_orbit_clamps_pitch_and_wraps_yaw():
    cam = OrbitCamera()
    cam.orbit(3.5 * np.pi, 10.0)
    assert cam.pitch == pytest.approx(np.pi / 2)
    assert -np.pi <= cam.yaw < np.pi
    assert cam.yaw == pytest.approx(-0.5 * np.pi)


def test_pan_moves_the_scene_with_the_cursor():
    cam = OrbitCamera(target=np.array([0.0, 1.0, 0.0]), distance=3.0, yaw=0.5, pitch=0.3)
    p = cam.target.copy()  # a world point at the target's depth
    before = to_pixel(project(cam, p))
    cam.pan(40.0, -25.0, H)
    after = to_pixel(project(cam, p))
    assert np.allclose(after - before, [40.0, -25.0], atol=1e-6)


def test_zoom_dollies_and_clamps():
    cam = OrbitCamera(distance=4.0)
    cam.zoom(1.0)
    assert cam.distance == pytest.approx(3.6)
    cam.zoom(-2.0)
    assert cam.distance == pytest.approx(3.6 / 0.81)
    cam.zoom(1000.0)
    assert cam.distance == cam.min_distance


@pytest.mark.parametrize("aspect", [0.5, 1.0, 2.0])
def test_frame_fits_the_box(aspect):
    cam = OrbitCamera(yaw=0.3, pitch=0.4)
    lo, hi = np.array([-0.3, 0.0, -0.2]), np.array([0.4, 1.8, 0.3])
    cam.frame(lo, hi, aspect)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    proj, view = cam.projection_matrix(aspect), cam.view_matrix()
    for c in corners:
        clip = proj @ view @ np.append(c, 1.0)
        assert np.all(np.abs(clip[:3] / clip[3]) <= 1.0)
    assert np.allclose(cam.target, 0.5 * (lo + hi))


@pytest.mark.parametrize("orthographic", [False, True])
def test_ray_from_pixel_passes_through_the_pixel(orthographic):
    cam = OrbitCamera(target=np.array([0.2, 1.0, 0.0]), distance=3.0, yaw=-0.6, pitch=0.35,
                      orthographic=orthographic)
    origin, direction = cam.ray_from_pixel(W / 2, H / 2, W, H)
    assert np.linalg.norm(direction) == pytest.approx(1.0)
    # the centre ray passes through the target
    to_target = cam.target - origin
    assert np.linalg.norm(np.cross(to_target, direction)) == pytest.approx(0.0, abs=1e-9)
    if not orthographic:
        assert np.allclose(origin, cam.eye())
    for px in [(10.0, 20.0), (600.0, 400.0), (123.5, 321.25)]:
        o, d = cam.ray_from_pixel(*px, W, H)
        for s in (1.0, 4.0):
            assert np.allclose(to_pixel(project(cam, o + s * d)), px, atol=1e-6)


def test_mouse_mappings():
    assert navigation_action("default", "left") is NavAction.ORBIT
    assert navigation_action("default", "right") is NavAction.PAN
    assert navigation_action("default", "left", {"shift"}) is NavAction.PAN
    assert navigation_action("blender", "middle") is NavAction.ORBIT
    assert navigation_action("blender", "middle", {"shift"}) is NavAction.PAN
    assert navigation_action("blender", "middle", {"ctrl"}) is NavAction.ZOOM
    assert navigation_action("blender", "left") is None
    assert navigation_action("default", "left", {"ctrl"}) is None
