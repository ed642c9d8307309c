"""Rays traced from Python against a closed form: a GRIN rod lens's back focal distance.

In the rod of `scenes/grin_lens_chromatic.toml` (n = n0(λ)(1 − g² r²/2), length L = 4 mm) a
ray entering parallel to the axis at height h leaves the exit face and crosses the axis at
BFD(h) = 1/(n0 g tan gL) + c h² + O(h⁴) — the paraxial (ABCD) focus plus spherical
aberration. Traced at h and 2h, the aberration quadruples, and Richardson's extrapolation
BFD(h) − (BFD(2h) − BFD(h))/3 recovers the paraxial focus."""

import math

import numpy as np
import pytest

import grinlight
from conftest import ROOT

ROD = ROOT / "scenes" / "grin_lens_chromatic.toml"
L = 4.0
G = {400.0: 0.33, 550.0: 0.32, 700.0: 0.31}  # the scene's tabulated g (1/mm): exact at its knots


def back_focal_distance(scene, h, nm):
    """Traced with fixed 1 µm RKN steps to the exit face, found on the last step's cubic
    Hermite curve (ends and tangents: its error is of order Δs⁴ × the ray's third
    derivative, below 1e-18 mm here; a straight chord would err by κΔs²/8 ≈ 3e-10 mm, which
    the ray's slope of ~5e-3 would magnify to 5e-8 mm of focus); refracted into air by
    Snell's law (the direction interpolated linearly: 6e-13 rad, 6e-11 mm of focus), then
    carried straight to the axis."""
    ray = grinlight.trace(scene, origin=[h, 0, 0], direction=[0, 0, 1], length=1.01 * L, medium="rod",
                          stepper="rkn", control="fixed", step=1e-3, wavelength=nm)
    k = int(np.searchsorted(ray.points[:, 2], L))
    p0, p1 = ray.points[k - 1], ray.points[k]
    d0, d1 = ray.directions[k - 1], ray.directions[k]
    ds = ray.s[k] - ray.s[k - 1]

    def curve(t):
        h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
        h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
        return h00 * p0 + h10 * ds * d0 + h01 * p1 + h11 * ds * d1

    t = (L - p0[2]) / (p1[2] - p0[2])
    for _ in range(3):  # Newton on z(t) = L, dz/dt ≈ Δs·d_z
        t -= (curve(t)[2] - L) / (ds * ((1 - t) * d0[2] + t * d1[2]))
    x = curve(t)[0]
    d = (1 - t) * d0 + t * d1
    d = d / np.linalg.norm(d)
    n = (1 - t) * ray.n[k - 1] + t * ray.n[k]
    sin_out = n * d[0]
    return -x * math.sqrt(1.0 - sin_out**2 - (n * d[1]) ** 2) / sin_out


@pytest.mark.parametrize("nm", sorted(G))
def test_the_rods_focus_is_the_paraxial_one_plus_spherical_aberration(nm):
    scene = grinlight.load(ROD)
    n0 = grinlight.trace(scene, origin=[0, 0, 0], direction=[0, 0, 1], length=0.1, medium="rod", wavelength=nm).n[0]
    paraxial = 1.0 / (n0 * G[nm] * math.tan(G[nm] * L))
    h = 0.01
    near, far = back_focal_distance(scene, h, nm), back_focal_distance(scene, 2 * h, nm)
    # The aberration goes as h²: its ratio between 2h and h is 4 up to O(h²) ≈ 1e-4.
    assert (far - paraxial) / (near - paraxial) == pytest.approx(4.0, abs=1e-3)
    # Extrapolated to h → 0 it is the paraxial focus, up to the O(h⁴) rest, of order
    # (1.4e-5 mm)²/0.5 mm ≈ 4e-10 mm (measured: within 7e-11 mm); the aberration at h itself
    # is 1.4e-5 mm.
    assert near - (far - near) / 3.0 == pytest.approx(paraxial, abs=2e-9)


def test_blue_focuses_before_red():
    scene = grinlight.load(ROD)
    foci = [back_focal_distance(scene, 0.01, nm) for nm in sorted(G)]
    assert foci[0] < foci[1] < foci[2]


def test_a_traced_rays_optical_depth_is_per_channel():
    """A ray 2 long through a uniform medium absorbing σa = (0.1, 0.2, 0.3): ∫σa ds per
    channel, (0.2, 0.4, 0.6), to rounding."""
    scene = {"medium": [{"name": "tint", "profile": "uniform", "n": 1.3, "absorption": [0.1, 0.2, 0.3]}]}
    ray = grinlight.trace(scene, origin=[0, 0, 0], direction=[0, 0, 1], length=2.0, medium="tint")
    assert ray.arclength == pytest.approx(2.0, abs=1e-12)
    assert ray.optical_depth == pytest.approx([0.2, 0.4, 0.6], abs=1e-12)
