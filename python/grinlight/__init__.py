"""grinlight from Python: a photon-mapping renderer for gradient-index (GRIN) media.

Scenes are read from TOML files (:func:`load`) or from dicts of the same schema
(:func:`load_dict`); :meth:`Scene.render` returns an :class:`Image` whose layers are float32
numpy arrays; :meth:`Scene.measure` returns the receivers' irradiance maps and the energy
budget; :func:`trace` follows one ray through a medium and returns its path as arrays;
:meth:`Scene.render` with ``shard=(k, n)`` and :func:`merge` split a render across machines
as the command line does.

The work runs in Rust with the interpreter released. Ctrl-C stops a render after its current
tiles: the ``KeyboardInterrupt`` raised carries the finished passes as ``.image``.
"""

from __future__ import annotations

import os
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _grinlight

__version__: str = _grinlight.__version__

__all__ = [
    "GrinlightWarning",
    "Image",
    "Measurement",
    "Ray",
    "Scene",
    "load",
    "load_dict",
    "merge",
    "trace",
]

PathLike = Union[str, "os.PathLike[str]"]
Progress = Union[bool, Callable[[int, int, str], None]]


class GrinlightWarning(UserWarning):
    """Something a scene's user should know though the work went on (a scene key that has
    no effect, a camera inside a black hole's horizon, pixels left out of the film)."""


@dataclass
class Measurement:
    """The receivers' measurements, by receiver name — each a dict with ``irradiance`` and
    ``stderr`` (W per scene unit², shape (ny, nx)), bin centres ``x`` and ``y``, ``flux``
    and ``flux_stderr`` (W) and ``bands`` — and the energy ``budget`` (W by fate); with the
    report of the work that made them."""

    receivers: Dict[str, Dict[str, Any]]
    budget: Optional[Dict[str, Any]]
    report: List[str] = field(repr=False)
    warnings: List[str] = field(repr=False)
    interrupted: bool = False

    @classmethod
    def _of(cls, result: Dict[str, Any], **more: Any) -> Any:
        return cls(result["receivers"], result["budget"], result["report"], result["warnings"], result["interrupted"], **more)


@dataclass
class Image(Measurement):
    """A rendered image: every layer of the film (``beauty`` is the sum of the radiance
    layers) as a float32 array of shape (height, width, 3), linear RGB, row 0 at the top;
    with the render's report and, when the scene has receivers, their measurements."""

    _film: Any = field(default=None, repr=False)

    @property
    def width(self) -> int:
        return self._film.width

    @property
    def height(self) -> int:
        return self._film.height

    @property
    def passes(self) -> int:
        """The passes the film holds."""
        return self._film.passes

    @property
    def error(self) -> Optional[float]:
        """The image's expected relative RMSE, estimated from the spread of its passes (the
        noise; None before two passes); the ``error`` layer holds each pixel's standard
        error."""
        return self._film.error

    @property
    def names(self) -> List[str]:
        """The layers written, ``beauty`` first (a layer nothing wrote is left out; reading
        it gives zeros)."""
        return self._film.names

    def layer(self, name: str) -> np.ndarray:
        """The layer ``name`` as a (height, width, 3) float32 array."""
        return self._film.layer(name)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.layer(name)

    @property
    def layers(self) -> Dict[str, np.ndarray]:
        """Every layer by name."""
        return {name: self.layer(name) for name in self.names}

    def write(self, path: PathLike) -> None:
        """Writes every layer into one EXR (ending in .exr), as ``grinlight render`` writes
        it, atomically; refuses to replace the scene's inputs or a file that is not an EXR."""
        self._film.write(Path(path))

    def write_png(self, path: PathLike, exposure: Optional[float] = None) -> None:
        """Writes the beauty layer as an 8-bit sRGB PNG, scaled by ``exposure`` (default:
        the scene's ``[output] exposure``)."""
        self._film.write_png(Path(path), exposure)


@dataclass
class Ray:
    """A traced ray: per accepted point (the start first) ``s`` (arclength), ``opl``
    (optical path length), ``points`` and ``directions`` (N × 3) and the index ``n``; how it
    ended (``reason``: "length reached", "left bounds", ...) after ``steps`` accepted steps
    of ``attempts``; its total ``arclength``, ``optical_path`` and ``optical_depth`` (3 numbers:
    ∫σa ds per RGB channel); with
    ``polarization`` asked, the ``field`` carried to the end (3 numbers, unit, perpendicular to
    the ray) and the geometric ``phase`` (radians: the solid angle the direction swept, closed
    by the shortest arc back to its start's, by which the field turned about the ray), else
    None."""

    s: np.ndarray
    opl: np.ndarray
    points: np.ndarray
    directions: np.ndarray
    n: np.ndarray
    reason: str
    steps: int
    attempts: int
    arclength: float
    optical_path: float
    optical_depth: np.ndarray
    field: Optional[np.ndarray] = None
    phase: Optional[float] = None


def _progress_bar(progress: Progress) -> Tuple[Optional[Callable[[int, int, str], None]], Callable[[], None]]:
    """A progress callable and its closer: the given callable; for True a tqdm bar (in a
    terminal or a notebook) when tqdm is installed, else a line on a terminal's stderr."""
    if callable(progress):
        return progress, lambda: None
    if not progress:
        return None, lambda: None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        tqdm = None
    if tqdm is not None:
        bars: Dict[str, Any] = {}

        def update(done: int, total: int, stage: str) -> None:
            if not stage:
                return  # nothing started yet
            bar = bars.get(stage)
            if bar is None:
                for old in bars.values():
                    old.close()
                bar = bars[stage] = tqdm(total=total or None, desc=stage, unit="photon" if stage == "measuring" else "tile")
            if total and bar.total != total:
                bar.total = total
            bar.update(done - bar.n)

        return update, lambda: [b.close() for b in bars.values()] and None
    if not sys.stderr.isatty():
        return None, lambda: None

    def line(done: int, total: int, stage: str) -> None:
        if not stage:
            return
        share = f"{100 * done / total:5.1f} %" if total else ""
        sys.stderr.write(f"\r{stage} {share} ({done}{'/' + str(total) if total else ''})   ")
        sys.stderr.flush()

    return line, lambda: sys.stderr.write("\n")


def _given(values: Mapping[str, Any]) -> Dict[str, Any]:
    return {k: v for k, v in values.items() if v is not None}


class Scene:
    """A scene read from a file or a dict, with the render settings given when it was
    loaded; each render starts from it anew."""

    def __init__(self, inner: Any, overrides: Mapping[str, Any]):
        self._inner = inner
        self._overrides = dict(overrides)

    @property
    def path(self) -> Path:
        """The scene file (for a dict, a name in its ``base_dir``)."""
        return Path(self._inner.path)

    @property
    def camera(self) -> Optional[Tuple[int, int]]:
        """The camera's image size (width, height) in pixels as its renders have it: the
        scene's, or the ``width`` and ``height`` given to :func:`load`; None without a
        camera. (A ``width`` given to one :meth:`render` sizes that render only.)"""
        size = self._inner.camera
        if size is None:
            return None
        return (self._overrides.get("width", size[0]), self._overrides.get("height", size[1]))

    @property
    def media(self) -> List[str]:
        """The media's names, in scene order (a dielectric's ``ior`` adds one)."""
        return self._inner.media

    @property
    def receivers(self) -> List[str]:
        """The receivers' names, in scene order."""
        return self._inner.receivers

    def _run(self, overrides: Mapping[str, Any], progress: Progress, camera: bool) -> Dict[str, Any]:
        callback, close = _progress_bar(progress)
        try:
            result = self._inner.render({**self._overrides, **_given(overrides)}, callback, camera)
        finally:
            close()
        for w in result["warnings"]:
            warnings.warn(w, GrinlightWarning, stacklevel=3)
        return result

    def render(
        self,
        spp: Optional[int] = None,
        passes: Optional[int] = None,
        time_budget: Optional[float] = None,
        seed: Optional[int] = None,
        threads: Optional[int] = None,
        integrator: Optional[str] = None,
        progress: Progress = True,
        shard: Optional[Tuple[int, int]] = None,
        output: Optional[PathLike] = None,
        resume: bool = False,
        **overrides: Any,
    ) -> Union[Image, Path]:
        """Renders the camera's view (and measures the receivers) in memory; every keyword
        replaces the scene's ``[render]``/``[camera]`` key of its name (the settings listed
        below; ``no_table=True`` is ``deflection_table=False``). The same scene, settings and
        seed give the EXR ``grinlight render`` writes, bit for bit.

        With ``shard=(k, n)`` renders the k-th of n slices of the scene file's render into a
        partial result at ``output`` (default ``<scene>.shard-k-of-n.partial``) and returns
        its path, for :func:`merge`; ``resume=True`` continues a shard an interrupt cut short
        (its partial holds the work done).

        Ctrl-C stops after the tiles in flight: ``KeyboardInterrupt`` is raised with the
        finished passes as its ``.image``."""
        values = dict(overrides, spp=spp, passes=passes, time_budget=time_budget, seed=seed, threads=threads, integrator=integrator)
        if shard is not None:
            if (
                isinstance(shard, (str, bytes))
                or not isinstance(shard, Sequence)
                or len(shard) != 2
                or not all(isinstance(x, int) and not isinstance(x, bool) for x in shard)
            ):
                raise ValueError(f"shard: expected (k, n), two whole numbers with 1 ≤ k ≤ n, got {shard!r}")
            k, n = shard
            if k < 1 or n < k or n >= 2**32:
                raise ValueError(f"shard: expected (k, n) with 1 ≤ k ≤ n, got {shard!r}")
            callback, close = _progress_bar(progress)
            try:
                out = self._inner.render_shard(
                    {**self._overrides, **_given(values)}, f"{k}/{n}", None if output is None else Path(output), bool(resume), callback
                )
            finally:
                close()
            return Path(out)
        if resume:
            raise ValueError("resume: a whole render in memory keeps no state to resume; resume a shard's render (shard=(k, n))")
        if output is not None:
            raise ValueError("output: a whole render returns its image (write it with Image.write); output names a shard's partial")
        if self.camera is None:
            raise ValueError(f"{self.path}: the scene has no [camera]: use measure() for its receivers")
        result = self._run(values, progress, camera=True)
        film = result["film"]
        image = None if film is None or film.passes == 0 else Image._of(result, _film=film)
        if result["interrupted"]:
            stop = KeyboardInterrupt("render interrupted: the finished passes are in this exception's .image (None before the first)")
            stop.image = image  # type: ignore[attr-defined]
            raise stop
        return image

    def measure(
        self,
        photons: Optional[int] = None,
        seed: Optional[int] = None,
        threads: Optional[int] = None,
        progress: Progress = True,
    ) -> Measurement:
        """Measures the scene's receivers with ``photons`` photons (default: ``[render]
        receiver_photons``), without rendering the camera's view. Ctrl-C stops after the
        photon blocks in flight: ``KeyboardInterrupt`` carries the estimate so far as
        ``.measurement``."""
        if not self.receivers:
            raise ValueError(f"{self.path}: the scene has no [[receiver]] to measure")
        result = self._run(dict(receiver_photons=photons, seed=seed, threads=threads), progress, camera=False)
        m = Measurement._of(result)
        if m.interrupted:
            stop = KeyboardInterrupt("measurement interrupted: the estimate so far is in this exception's .measurement")
            stop.measurement = m  # type: ignore[attr-defined]
            raise stop
        return m

    def trace(self, origin: Sequence[float], direction: Sequence[float], length: float, medium: Optional[str] = None, **options: Any) -> Ray:
        """See :func:`trace`."""
        return trace(self, origin, direction, length, medium=medium, **options)


def load(
    path: PathLike,
    *,
    defines: Optional[Mapping[str, Any]] = None,
    approximate: bool = False,
    **overrides: Any,
) -> Scene:
    """Reads the scene file at ``path``: grinlight's TOML, a Mitsuba 3 scene (``.xml``) or a
    pbrt-v4 scene (``.pbrt``), converted as ``grinlight convert`` does (docs/import.md); a
    Mitsuba scene's ``$parameters`` take the values ``defines`` gives (as ``-D``). Approximations
    are made (and listed among
    a render's warnings) only when ``approximate``. ``overrides`` replace its ``[render]`` and
    ``[camera]`` keys for every render (as the command line's options do). Errors raise
    ``ValueError`` naming the file, line, column and key (``OSError`` for an unreadable
    file)."""
    given = _given(overrides)
    pairs = [(str(k), str(v)) for k, v in (defines or {}).items()]
    return Scene(_grinlight.load(Path(path), given, pairs, bool(approximate)), given)


def load_dict(data: Mapping[str, Any], base_dir: PathLike = ".", **overrides: Any) -> Scene:
    """Reads a scene given as a dict of the scene file's schema (tables as dicts, arrays of
    tables as lists of dicts; numpy arrays allowed as lists); relative file names in it are
    resolved in ``base_dir``. Errors raise ``ValueError`` naming the key's path, e.g.
    ``medium[0].radius``."""
    given = _given(overrides)
    return Scene(_grinlight.load_dict(data, Path(base_dir), given), given)


def trace(
    scene: Union[Scene, PathLike, Mapping[str, Any]],
    origin: Sequence[float],
    direction: Sequence[float],
    length: float,
    medium: Optional[str] = None,
    stepper: Optional[str] = None,
    tolerance: Optional[float] = None,
    wavelength: Optional[float] = None,
    **options: Any,
) -> Ray:
    """Follows one ray from ``origin`` along ``direction`` (any length) for ``length`` scene
    units through the medium ``medium`` of ``scene`` (a Scene, a scene file or a dict; the
    medium may be left out when the scene has one), unbounded, as ``grinlight trace`` does:
    ``stepper`` rkn, rk4, arc, snell or linearize (the default); ``tolerance`` of the adaptive control;
    ``wavelength`` in nm for a dispersive medium; ``control`` ("adaptive", "fixed",
    "tessendorf"), ``step``, ``t_max``, ``t_min``, ``seed``, ``max_steps`` as the command's
    options; ``polarization`` (three numbers): the field's direction at the start (its part
    perpendicular to ``direction``), carried along the ray by Rytov's law (the result's
    ``field`` and ``phase``)."""
    if not isinstance(scene, Scene):
        scene = load_dict(scene) if isinstance(scene, Mapping) else load(scene)
    if medium is None:
        media = scene.media
        if len(media) != 1:
            raise ValueError(f"medium: the scene has {len(media)} media ({', '.join(media)}): name one")
        medium = media[0]
    values = _given(dict(options, stepper=stepper, tolerance=tolerance, wavelength=wavelength))
    return Ray(**scene._inner.trace(medium, origin, direction, length, values))


def merge(partials: Sequence[PathLike], output: Optional[PathLike] = None, allow_missing: bool = False) -> Optional[Image]:
    """Merges the partial results of a render's shards as ``grinlight merge`` does — writing
    the render's EXR, PNG and receiver files (at ``output``, default the scene's) — and
    returns the merged image (None for a scene without a camera)."""
    if isinstance(partials, (str, bytes, os.PathLike)):
        raise ValueError(f"partials: expected a list of partial files, got one path {partials!r} (write [{partials!r}])")
    film = _grinlight.merge([Path(p) for p in partials], None if output is None else Path(output), allow_missing)
    return None if film is None else Image({}, None, [], [], _film=film)


def _settings_doc() -> str:
    """The render settings' list, from the table the scene file and the command line read."""
    rows = [f"    ``{name}``: {doc} ({values}; default {default})" for name, doc, values, default in _grinlight.render_settings()]
    return "\n\n        Settings (a value is refused in the scene file's words):\n\n    " + "\n    ".join(rows)


if Scene.render.__doc__ is not None:
    Scene.render.__doc__ += _settings_doc()
