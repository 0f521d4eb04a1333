"""`Topography`: a height map with its lateral scale, periodicity and provenance, the object the
readers return and every array function accepts; and `LineScan`, a profile."""

from __future__ import annotations

import warnings
from types import MappingProxyType
from typing import Any, Dict, Iterator, Mapping, Optional, Sequence, Tuple, cast

import numpy as np

from . import _args, _native
from ._args import F64
from ._results import Acf, MaterialRatio, Psd, SurfaceStatistics, SurfaceTables, Summits
from ._plausibility import spacing_sentences
from ._warnings import warn

#: The keys of the dict `read_topography` returned before 0.x (deprecated access by key).
_OLD_KEYS = ("heights", "dx", "dy", "spacing_from_file", "height_unit_from_file", "channel", "channels", "metadata")


def _read_only(a: F64) -> F64:
    a.flags.writeable = False
    return a


class Topography:
    """A height map and its scale: ``heights`` (m, ``[iy, ix]``, missing points NaN, read-only),
    the spacing ``dx``, ``dy`` (m), whether the map is ``periodic`` (a synthetic surface: its
    statistics use the periodic boundary, as a study's), and where it came from: ``metadata``
    (the file's header entries), ``channel`` and ``channels`` (the channel read and all of the
    file's), ``spacing_source`` and ``height_unit_source`` (``"file"``, ``"given"`` or, for a
    height unit a file does not state, ``"assumed"``: read as metres). Heights are always in
    metres (``height_unit`` is ``"m"``).

    ``Topography(heights, dx, dy=None, *, periodic=False, metadata=None)`` wraps an array (a
    copy); :func:`read_topography` and :func:`synthetic_surface` return one. Every array
    function takes it in place of ``(heights, dx, dy)``. Analysis, as a study's surface node
    computes it (computed once, on first use): :meth:`statistics`, :meth:`psd`, :meth:`acf`,
    :meth:`material_ratio`, :meth:`summits`.
    """

    __slots__ = ("_heights", "_dx", "_dy", "_periodic", "_metadata", "_channel", "_channels", "_spacing_source", "_height_unit_source", "_reports")

    height_unit = "m"

    _heights: F64
    _dx: float
    _dy: float
    _periodic: bool
    _metadata: Mapping[str, str]
    _channel: Optional[str]
    _channels: Tuple[str, ...]
    _spacing_source: str
    _height_unit_source: str
    _reports: Dict[bool, Tuple[SurfaceStatistics, SurfaceTables]]

    def __init__(
        self,
        heights: Any,
        dx: Any,
        dy: Any = None,
        *,
        periodic: bool = False,
        metadata: Optional[Mapping[str, str]] = None,
    ) -> None:
        x, y = spacing(dx, dy)
        self._set(_read_only(np.array(_args.heights("heights", heights), dtype=np.float64, copy=True)), x, y, _args.boolean("periodic", periodic))
        warn(spacing_sentences(x, y))
        if metadata is not None:
            if not isinstance(metadata, Mapping) or not all(isinstance(k, str) and isinstance(v, str) for k, v in metadata.items()):
                raise TypeError(f"metadata: expected a mapping of str to str, got {_args.show(metadata)}")
            self._metadata = MappingProxyType(dict(metadata))

    def _set(self, heights: F64, dx: float, dy: float, periodic: bool) -> None:
        self._heights, self._dx, self._dy, self._periodic = heights, dx, dy, periodic
        self._metadata = MappingProxyType({})
        self._channel = None
        self._channels = ()
        self._spacing_source = "given"
        self._height_unit_source = "given"
        self._reports = {}

    @classmethod
    def _owning(
        cls,
        heights: F64,
        dx: float,
        dy: float,
        periodic: bool,
        *,
        metadata: Mapping[str, str] = MappingProxyType({}),
        channel: Optional[str] = None,
        channels: Sequence[str] = (),
        spacing_source: str = "given",
        height_unit_source: str = "given",
    ) -> "Topography":
        """A topography of heights no one else holds (a computation's result, a file's): no
        copy."""
        t = cls.__new__(cls)
        t._set(_read_only(heights), dx, dy, periodic)
        t._metadata = MappingProxyType(dict(metadata))
        t._channel, t._channels = channel, tuple(channels)
        t._spacing_source, t._height_unit_source = spacing_source, height_unit_source
        return t

    def with_heights(self, heights: F64) -> "Topography":
        """The same scale, periodicity and provenance with new heights (a filter's result)."""
        return Topography._owning(
            heights,
            self._dx,
            self._dy,
            self._periodic,
            metadata=self._metadata,
            channel=self._channel,
            channels=self._channels,
            spacing_source=self._spacing_source,
            height_unit_source=self._height_unit_source,
        )

    @property
    def heights(self) -> F64:
        """Heights (m, ``[iy, ix]``, NaN missing), read-only."""
        return self._heights

    @property
    def dx(self) -> float:
        """Spacing along x (m)."""
        return self._dx

    @property
    def dy(self) -> float:
        """Spacing along y (m)."""
        return self._dy

    @property
    def nx(self) -> int:
        return int(self._heights.shape[1])

    @property
    def ny(self) -> int:
        return int(self._heights.shape[0])

    @property
    def shape(self) -> Tuple[int, int]:
        """``(ny, nx)``, as the array's."""
        return (self.ny, self.nx)

    @property
    def size(self) -> Tuple[float, float]:
        """``(Lx, Ly)`` = ``(nx·dx, ny·dy)`` in m."""
        return (self.nx * self._dx, self.ny * self._dy)

    @property
    def periodic(self) -> bool:
        return self._periodic

    @property
    def metadata(self) -> Mapping[str, str]:
        return self._metadata

    @property
    def channel(self) -> Optional[str]:
        return self._channel

    @property
    def channels(self) -> Tuple[str, ...]:
        return self._channels

    @property
    def spacing_source(self) -> str:
        return self._spacing_source

    @property
    def height_unit_source(self) -> str:
        return self._height_unit_source

    @property
    def missing_points(self) -> int:
        return int(np.count_nonzero(np.isnan(self._heights)))

    def __repr__(self) -> str:
        lx, ly = self.size
        parts = [f"{self.nx}×{self.ny}", f"dx={self._dx:.4g} m", f"dy={self._dy:.4g} m", f"size={lx:.4g}×{ly:.4g} m"]
        if self._periodic:
            parts.append("periodic")
        if self._channel is not None:
            parts.append(f"channel={self._channel!r}")
        parts.append(f"spacing_source={self._spacing_source!r}, height_unit_source={self._height_unit_source!r}")
        return f"Topography({', '.join(parts)})"

    def _report(self, periodic: Optional[bool] = None) -> Tuple[SurfaceStatistics, SurfaceTables]:
        boundary = self._periodic if periodic is None else _args.boolean("periodic", periodic)
        if boundary not in self._reports:
            stats, tables, sentences = _native.surface_report(self._heights, self._dx, self._dy, boundary)
            warn(sentences)
            self._reports[boundary] = (cast(SurfaceStatistics, stats), tables)
        return self._reports[boundary]

    def statistics(self, *, periodic: Optional[bool] = None) -> SurfaceStatistics:
        """The ``surfaces`` row a study writes for this map: ISO 25178-2 amplitude, hybrid,
        functional and volume parameters, spectral parameters (complete maps only) and summit
        statistics, keyed by column name with the SI unit. ``periodic`` overrides the map's."""
        return dict(self._report(periodic)[0])  # type: ignore[return-value]

    def _table(self, name: str, what: str) -> Mapping[str, Any]:
        tables = self._report()[1]
        if name not in tables:
            raise ValueError(
                f"{what}: the map has {self.missing_points} missing point(s); spectra need a complete "
                "map: fill them first (asperity.fill_missing)"
            )
        return cast(Mapping[str, Any], tables[name])

    def psd(self) -> Psd:
        """The radially averaged power spectral density a study writes (``surfaces_psd``): wave
        numbers ``q_rad_per_m`` (rad/m) and C(q) ``c_m4`` (m⁴); a periodic map unwindowed, a
        measured one with a Hann window."""
        return cast(Psd, dict(self._table("psd", "psd")))

    def acf(self) -> Acf:
        """The radially averaged autocorrelation a study writes (``surfaces_acf``): lags ``r_m``
        (m) and the normalised ACF ``acf`` (1 at r = 0); periodic or zero-padded as the map."""
        return cast(Acf, dict(self._table("acf", "acf")))

    def material_ratio(self) -> MaterialRatio:
        """The ISO 25178-2 material ratio (Abbott–Firestone) curve a study writes, every 1 %:
        ``material_ratio_percent`` and ``height_m`` (m)."""
        return cast(MaterialRatio, dict(self._table(_native.MATERIAL_RATIO_TABLE, "material_ratio")))

    def summits(self) -> Summits:
        """The 8-neighbour summits a study writes (``surfaces_summits``): grid indices, position
        (m), height (m), slope and radius (m) of each."""
        return cast(Summits, dict(self._table("summits", "summits")))

    def __getitem__(self, key: str) -> Any:
        """Deprecated: the keys of the dict :func:`read_topography` returned before."""
        if key not in _OLD_KEYS:
            raise KeyError(f"{key!r}: a Topography has attributes, not keys (heights, dx, dy, size, periodic, metadata, channel, channels, spacing_source, height_unit_source)")
        warnings.warn(
            f"topography[{key!r}] is deprecated: read_topography returns a Topography; use its attributes (t.heights, t.dx, t.spacing_source == 'file', …)",
            DeprecationWarning,
            stacklevel=2,
        )
        if key == "spacing_from_file":
            return self._spacing_source == "file"
        if key == "height_unit_from_file":
            return self._height_unit_source == "file"
        return getattr(self, key)

    def __iter__(self) -> Iterator[Any]:
        """Deprecated: ``heights, dx, dy = synthetic_surface(…)``, the tuple it returned before."""
        warnings.warn(
            "unpacking a Topography into (heights, dx, dy) is deprecated: synthetic_surface returns a Topography; use t.heights, t.dx, t.dy",
            DeprecationWarning,
            stacklevel=2,
        )
        return iter((self._heights, self._dx, self._dy))


class LineScan:
    """A profile: positions ``x`` (m, ascending) and ``heights`` (m, NaN missing), with the
    file's ``metadata``, ``channel``, ``channels``, ``spacing_source`` and
    ``height_unit_source``, as :func:`read_line_scan` returns it."""

    __slots__ = ("x", "heights", "metadata", "channel", "channels", "spacing_source", "height_unit_source")

    def __init__(self, x: F64, heights: F64, metadata: Mapping[str, str], channel: Optional[str], channels: Sequence[str], spacing_source: str, height_unit_source: str) -> None:
        self.x, self.heights = _read_only(x), _read_only(heights)
        self.metadata: Mapping[str, str] = MappingProxyType(dict(metadata))
        self.channel, self.channels = channel, tuple(channels)
        self.spacing_source, self.height_unit_source = spacing_source, height_unit_source

    def __repr__(self) -> str:
        return f"LineScan({len(self.x)} points over {float(self.x[-1] - self.x[0]):.4g} m, channel={self.channel!r})"

    def __getitem__(self, key: str) -> Any:
        """Deprecated: the keys of the dict :func:`read_topography` returned for a line scan."""
        if key not in ("x", "heights", "spacing_from_file", "height_unit_from_file", "channel", "channels", "metadata"):
            raise KeyError(f"{key!r}: a LineScan has attributes, not keys (x, heights, metadata, channel, channels, spacing_source, height_unit_source)")
        warnings.warn(f"line_scan[{key!r}] is deprecated: use its attributes (s.x, s.heights, …)", DeprecationWarning, stacklevel=2)
        if key == "spacing_from_file":
            return self.spacing_source == "file"
        if key == "height_unit_from_file":
            return self.height_unit_source == "file"
        return getattr(self, key)


def spacing(dx: Any, dy: Any) -> Tuple[float, float]:
    """``dx`` and ``dy`` (default ``dx``) in m, each > 0."""
    x = _args.quantity("dx", dx, _args.LENGTH)
    return x, (x if dy is None else _args.quantity("dy", dy, _args.LENGTH))


def as_topography(name: str, heights: Any, dx: Any, dy: Any, periodic: bool = False) -> Tuple[Topography, bool]:
    """A map argument as a Topography (``heights`` one, or an array with ``dx``, ``dy``) and
    whether it was given as one. An array is wrapped without a copy, for this call only."""
    if isinstance(heights, Topography):
        if dx is not None or dy is not None:
            raise TypeError(f"dx: {name} is a Topography, which carries its spacing (dx = {heights.dx:g} m); omit dx and dy")
        return heights, True
    if isinstance(heights, np.ndarray) and dx is None:
        raise TypeError(f"dx: required with a height array: the spacing in m (or pass {name} as a Topography)")
    if not isinstance(heights, np.ndarray):
        raise TypeError(f"{name}: expected a Topography or a 2-D NumPy array of heights in m, got {_args.show(heights)}")
    h = _args.heights(name, heights)
    x, y = spacing(dx, dy)
    warn(f"{name}: {s}" for s in spacing_sentences(x, y))
    t = Topography.__new__(Topography)
    t._set(h, x, y, periodic)
    return t, False
