"""detach from Python: certified detachment regions, as the `detach` CLI.

    import detach
    rod = detach.Scene.load("painleve-rod", mu="1.5")
    paving = rod.pave(eps=1/256)
    paving.areas["omega"]          # certified inner and outer bounds
    paving.plot()                  # the atlas, in the CLI's colours

Parameters are decimal text (`mu="1.5"`), or ints or `decimal.Decimal`; a
float is refused (see `detach._text.decimal_text`). Every number comes from
the Rust library the CLI is built from, so results equal the CLI's.
"""

from __future__ import annotations

import decimal
import fractions
import json
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _detach
from ._detach import DetachError, ProofRejected, SceneFileError
from ._text import decimal_text

__all__ = [
    "DetachError",
    "SceneFileError",
    "ProofRejected",
    "Scene",
    "Paving",
    "ParamAtlas",
    "Share",
    "SetArea",
    "Area",
    "Verification",
    "Trajectory",
    "Event",
    "Reach",
    "Explorer",
    "FATES",
    "Interrupted",
    "verify",
    "scenes",
    "palette",
    "LABELS",
    "CLASSES",
    "STATUSES",
]

__version__ = _detach.VERSION.split()[0]

#: Label words of a leaf per constraint, as in `detach pave --leaves`.
LABELS = ("in", "out", "undecided", "undefined")
#: A parameter box's status per set, as `detach params` reports it.
STATUSES = ("nonempty", "empty", "undecided")
#: A leaf's class: the four cells (both labels decided), then undecided and
#: undefined; the order of `palette()`. Read from the library.
CLASSES = tuple(_detach.class_names())

#: The library's defaults per call (the command line's), read from it.
_DEFAULTS = json.loads(_detach.defaults())


def scenes():
    """The names `Scene.load` knows: the paper's scenes, then shipped files."""
    return list(_detach.scene_names())


def palette():
    """`{class: (symbol, meaning, "#rrggbb")}` as the CLI's atlas draws them."""
    return dict(zip(CLASSES, _detach.palette()))


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during `Scene.pave` or `Scene.param_atlas`: `.paving` (its
    `stop` is `"interrupted"`) or `.atlas` (not `complete`) is the valid,
    coarser result reached; `.result` is either."""

    def __init__(self, result):
        what = "atlas" if isinstance(result, ParamAtlas) else "paving"
        super().__init__(f"{what} interrupted; the partial result is in .{what}")
        self.result = result
        setattr(self, what, result)


def _pairs(params):
    return [(name, decimal_text(name, value)) for name, value in params.items()]


def _window(name, window):
    if window is None:
        return None
    try:
        lo, hi = window
    except (TypeError, ValueError):
        raise DetachError(f"{name} must be (lo, hi), got {window!r}") from None
    return [decimal_text(name, lo), decimal_text(name, hi)]


class Scene:
    """A scene at given parameters, in one reading of the paper."""

    def __init__(self, native, toml=None):
        self._native = native
        self._toml = toml

    @classmethod
    def load(cls, name, variant="derived", **params):
        """A paper scene (`viscous-disc`, `smooth-disc`, `ice-disc`; `variant`
        `derived` or `printed`) or a shipped scene file (`painleve-rod`)."""
        return cls(_detach.Scene.load(name, _pairs(params), variant))

    @classmethod
    def from_file(cls, path, **params):
        """A scene file (TOML, docs/scene-files.md)."""
        native = _detach.Scene.from_file(str(path), _pairs(params))
        with open(path, encoding="utf-8") as f:
            return cls(native, f.read())

    @classmethod
    def from_toml(cls, text, **params):
        """A scene file's text."""
        return cls(_detach.Scene.from_toml(text, "<toml>", _pairs(params)), text)

    @classmethod
    def from_sympy(cls, omega, omega0=None, **kwargs):
        """A scene from sympy expressions: see `detach.sympy.scene_toml` for
        the arguments. The text written is `scene.toml`."""
        from .sympy import scene_toml

        return cls.from_toml(scene_toml(omega, omega0, **kwargs))

    @property
    def name(self):
        return self._native.name

    @property
    def title(self):
        return self._native.title

    @property
    def variant(self):
        return self._native.variant

    @property
    def params(self):
        """`{name: decimal text}` of every parameter."""
        return dict(self._native.params)

    @property
    def domain(self):
        """`{"theta": (lo, hi), "theta_dot": (lo, hi)}` as text."""
        th, thd = self._native.domain_text
        return {"theta": tuple(th), "theta_dot": tuple(thd)}

    @property
    def toml(self):
        """The scene file's text (None for a paper scene)."""
        return self._toml

    @property
    def warnings(self):
        return list(self._native.warnings)

    def __repr__(self):
        ps = " ".join(f"{k}={v}" for k, v in self.params.items())
        return f"<detach.Scene {self.name} ({self.variant}) {ps}>"

    def pave(
        self,
        *,
        eps=_DEFAULTS["pave"]["eps"],
        method=_DEFAULTS["pave"]["method"],
        region=None,
        theta=None,
        theta_dot=None,
        max_boxes=_DEFAULTS["pave"]["max_boxes"],
        progress=None,
    ):
        """Paves Ω and Ω₀ as `detach pave` does (same defaults).

        `theta`, `theta_dot`: windows `(lo, hi)` inside the domain (decimal
        text, `"pi/2"`). `progress`: called as `progress(level, open,
        leaves)` at the start of each level of the tree (quiet when None;
        with tqdm, `bar.set_postfix(level=level, leaves=leaves)`); an
        exception it raises stops the paving and is raised. The GIL is
        released while paving; Ctrl-C stops it between levels and raises
        `Interrupted`, which carries the valid, coarser paving reached."""
        if isinstance(max_boxes, bool) or not isinstance(max_boxes, int) or max_boxes < 0:
            raise DetachError(f"max_boxes must be a positive integer, got {max_boxes!r}")
        native, interrupted = self._native.pave(
            _eps(eps),
            max_boxes,
            method,
            region,
            _window("theta", theta),
            _window("theta_dot", theta_dot),
            _callable("progress", progress),
        )
        paving = Paving(native, self)
        if interrupted:
            raise Interrupted(paving)
        return paving

    def param_atlas(
        self,
        x,
        y=None,
        *,
        sets=tuple(_DEFAULTS["param_atlas"]["sets"]),
        eps=None,
        max_boxes=_DEFAULTS["param_atlas"]["max_boxes"],
        progress=None,
    ):
        """A certified parameter atlas, as `detach params`: where in a range
        of one parameter (`x`) or two (`x`, `y`) each set is proved
        non-empty, proved empty, or undecided; the other parameters keep
        this scene's values.

        `x`, `y`: `"mu=0:2"` or `("mu", "0", "2")` (decimal ends). `sets`:
        names among `CLASSES[:4]`, `"omega"`, `"omega0"`. `eps`: resolution
        per axis relative to its range (default 2⁻³⁴ in one parameter, so a
        threshold is enclosed to about 1e-10, and 1/256 in two). The GIL is
        released while it runs; Ctrl-C stops it between levels and raises
        `Interrupted`, which carries the valid, coarser atlas reached.
        `progress`: as for `pave`, `progress(level, open, boxes)`."""
        if isinstance(max_boxes, bool) or not isinstance(max_boxes, int) or max_boxes < 1:
            raise DetachError(f"max_boxes must be a positive integer, got {max_boxes!r}")
        if isinstance(sets, str):
            sets = [sets]
        axes = [_axis("x", x)] + ([] if y is None else [_axis("y", y)])
        native, interrupted = self._native.param_atlas(
            axes, list(sets), None if eps is None else _eps(eps), max_boxes,
            _callable("progress", progress),
        )
        atlas = ParamAtlas(native, self)
        if interrupted:
            raise Interrupted(atlas)
        return atlas

    def flow(self, start, t, *, until="cell,domain", order=_DEFAULTS["flow"]["order"], proof=False):
        """A certified trajectory, as `detach flow`: the tube of every
        solution from `start` over [0, t], up to the first event of `until`
        (`"U=0"`, `"N=0"`, `"cell"`, `"domain"`, `"none"`, comma-separated).

        `start`: `(theta, theta_dot)`, each decimal text (`"pi/4"`), an int,
        a `Decimal`, or a pair `(lo, hi)` for a box of initial states. `t`:
        the end time, decimal text. With `proof=True` the run also makes its
        `trajectory` proof (`Trajectory.save_proof`), and fails when it
        ends undecided. The GIL is released while it runs."""
        try:
            theta, theta_dot = start
        except (TypeError, ValueError):
            raise DetachError(f"start must be (theta, theta_dot), got {start!r}") from None
        native = self._native.flow(
            _state("theta", theta),
            _state("theta_dot", theta_dot),
            decimal_text("t", t),
            str(until),
            _order(order),
            bool(proof),
        )
        return Trajectory(native)

    def explore(self, *, port=0):
        """The page of `detach explore` for this scene at its parameters,
        served on 127.0.0.1 until `Explorer.stop` (or the kernel ends). In
        Jupyter the returned `Explorer` shows the page inline; its `params`
        are those of the page's last drawn atlas."""
        if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
            raise DetachError(f"port must be an integer in 0..=65535, got {port!r}")
        scene, text = (self.name, None) if self._toml is None else (None, self._toml)
        return Explorer(_detach.Explorer(scene, text, list(self.params.items()), port))

    def reach(self, t, *, until="cell", theta=None, theta_dot=None, eps=_DEFAULTS["reach"]["eps"],
              max_boxes=_DEFAULTS["reach"]["max_boxes"], proof=False):
        """The initial states whose motion reaches the first event of
        `until` within time `t`, as `detach reach`: a certified paving of
        the domain (or the window `theta`, `theta_dot`), each leaf proved to
        reach (with the time window of its arrival), proved to avoid, or
        undecided with the reason. With `proof=True` the run also makes its
        `reach` proof (`Reach.save_proof`). The GIL is released while it
        runs."""
        if isinstance(max_boxes, bool) or not isinstance(max_boxes, int) or max_boxes < 1:
            raise DetachError(f"max_boxes must be a positive integer, got {max_boxes!r}")
        leaves, complete, made = self._native.reach(
            decimal_text("t", t), str(until), _eps(eps), max_boxes,
            _window("theta", theta), _window("theta_dot", theta_dot), bool(proof),
        )
        return Reach(leaves, complete, made)

    def singular_points(self, *, theta=None, theta_dot=None, x=None, eps=None):
        """The equilibria and singular points of the scene's `[dynamics]`,
        as `detach singular --json`: each proved unique in its box, with its
        type (`"saddle"`, `"stable node"`, ...). `theta`, `theta_dot`: a
        window `(lo, hi)`. With `x` (`"mu=1:2"` or `(name, lo, hi)`): the
        scan over that parameter, whose `"thresholds"` are the certified
        values where the number or type of the points changes. Numbers are
        exact decimal text."""
        window = (_window("theta", theta), _window("theta_dot", theta_dot))
        if x is None:
            return json.loads(self._native.singular_points(*window))
        return json.loads(
            self._native.singular_scan(
                _axis("x", x), None if eps is None else _eps(eps), *window
            )
        )

    def area(self, *, digits=_DEFAULTS["area"]["digits"]):
        """Certified areas of Ω, Ω₀ and the four cells to `digits` places, as
        `detach area`: `{name: Area}`, each saying how it was obtained."""
        return {
            name: Area(name, label, lower, upper, how)
            for name, label, lower, upper, how in self._native.area(int(digits))
        }


def _callable(name, f):
    if f is not None and not callable(f):
        raise DetachError(f"{name} must be a callable or None, got {f!r}")
    return f


def _eps(eps):
    """A resolution as a float: a number, or text such as `"1/64"` or
    `"0.01"` (a resolution is a size asked for, not a certified value)."""
    if isinstance(eps, bool):
        raise DetachError(f"eps must be a number in (0, 1], got {eps!r}")
    if isinstance(eps, str):
        try:
            return float(fractions.Fraction(eps.strip()))
        except (ValueError, ZeroDivisionError):
            raise DetachError(
                f"eps must be a number in (0, 1] such as 1/256 or '1/256', got {eps!r}"
            ) from None
    try:
        return float(eps)
    except (TypeError, ValueError):
        raise DetachError(f"eps must be a number in (0, 1], got {eps!r}") from None


def _state(name, value):
    """One coordinate of a start: a number's text, or `LO:HI` for a pair."""
    if isinstance(value, (tuple, list)):
        lo, hi = _window(name, value)
        return f"{lo}:{hi}"
    return decimal_text(name, value)


def _order(order):
    if isinstance(order, bool) or not isinstance(order, int):
        raise DetachError(f"order must be an integer in 2..=60, got {order!r}")
    return order


@dataclass(frozen=True)
class Event:
    """The first event of a run: its kind (`"U=0"`, `"N=0"`, `"domain"`)
    and enclosures `(lo, hi)` of its time, of the state there, and of the
    watched function's rate of change (of one sign: a transversal crossing).
    The floats are exact: each is the double whose decimal value detach
    wrote."""

    kind: str
    time: tuple
    theta: tuple
    theta_dot: tuple
    slope: tuple


def _pair(texts):
    return (float(texts[0]), float(texts[1]))


class Explorer:
    """A running `detach explore` page (`Scene.explore`)."""

    def __init__(self, native):
        self._native = native

    @property
    def url(self):
        """The page's address, its session token included."""
        return self._native.url

    @property
    def state(self):
        """`{"scene", "params", "text"?}` of the page's last drawn atlas."""
        return json.loads(self._native.state())

    @property
    def params(self):
        """`{name: decimal text}` the page's last atlas was drawn at: the
        parameters the user ended on."""
        return dict(self.state["params"])

    def stop(self):
        """Stops serving; the page stops answering."""
        self._native.stop()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()

    def _repr_html_(self):
        return (f'<iframe src="{self.url}" width="100%" height="1150" '
                'style="border: 1px solid #ccc"></iframe>'
                f'<div><a href="{self.url}" target="_blank">open in a tab</a></div>')

    def __repr__(self):
        return f"<detach.Explorer {self.url}>"


class Trajectory:
    """The result of `Scene.flow`: a certified tube, its first events, its
    end and why it ended."""

    def __init__(self, native):
        self._native = native
        self._doc = json.loads(native.json())

    def json(self):
        """What `detach flow --json` prints (without the run's arguments)."""
        return self._doc

    def save_proof(self, path):
        """Writes the run's `trajectory` proof file (proofs/FORMAT.md), once
        the independent checker says VALID, as `detach flow --proof`; the
        run must have been made with `Scene.flow(..., proof=True)`."""
        self._native.save_proof(str(path))

    @property
    def events(self):
        return [
            Event(e["kind"], _pair(e["time"]), _pair(e["theta"]), _pair(e["theta_dot"]),
                  _pair(e["slope"]))
            for e in self._doc["events"]
        ]

    @property
    def end_time(self):
        """The end time asked for (a `Decimal`, exact) when reached, else
        `(lo, hi)`: the event's window or the last certified step's end."""
        t = self._doc["end"]["time"]
        if isinstance(t, str):
            return decimal.Decimal(t)
        return _pair(t)

    @property
    def end(self):
        """`((θ lo, θ hi), (θ̇ lo, θ̇ hi))` at the end."""
        e = self._doc["end"]
        return (_pair(e["theta"]), _pair(e["theta_dot"]))

    @property
    def stop(self):
        return self._doc["stop"]

    @property
    def steps(self):
        return self._doc["steps"]

    def band(self, pieces=8):
        """The tube as a numpy structured array, `pieces` rows per step:
        `t_lo, t_hi, theta_lo, theta_hi, theta_dot_lo, theta_dot_hi`. Every
        solution is in a row's box at every time of its time interval."""
        raw = self._native.band(int(pieces))
        return np.frombuffer(raw, dtype=_BAND_DTYPE)

    def plot(self, ax=None, pieces=8, color="black"):
        """Draws the band's boxes on the phase plane (θ, θ̇)."""
        from ._plot import plot_band

        return plot_band(self.band(pieces), ax=ax, color=color)

    def __repr__(self):
        return f"<detach.Trajectory {self.steps} steps, {self.stop}>"


#: A reach leaf's fate, by its code in `Reach.leaves["fate"]`.
FATES = ("reaches", "avoids", "undecided")


class Reach:
    """The result of `Scene.reach`: leaves (a numpy structured array with
    `theta_lo, theta_hi, theta_dot_lo, theta_dot_hi, fate, t_lo, t_hi`),
    the undecided leaves' reasons, and certified area bounds."""

    def __init__(self, leaves, complete, proof=None):
        self._proof = proof
        self.leaves = np.array(
            [row[:7] for row in leaves],
            dtype=[("theta_lo", "f8"), ("theta_hi", "f8"), ("theta_dot_lo", "f8"),
                   ("theta_dot_hi", "f8"), ("fate", "u1"), ("t_lo", "f8"), ("t_hi", "f8")],
        )
        self.reasons = [row[7] for row in leaves]
        #: False when the box budget ended the paving (open boxes undecided).
        self.complete = complete

    def area(self):
        """`(inner, outer)`: the area of the leaves proved to reach, and of
        those not proved to avoid (floats summed in exact rationals, then
        rounded outward)."""
        from fractions import Fraction

        def total(mask):
            leaves = self.leaves[mask]
            return sum(
                (Fraction(float(a)) - Fraction(float(b))) * (Fraction(float(c)) - Fraction(float(d)))
                for a, b, c, d in zip(leaves["theta_hi"], leaves["theta_lo"],
                                      leaves["theta_dot_hi"], leaves["theta_dot_lo"])
            )

        inner, outer = total(self.leaves["fate"] == 0), total(self.leaves["fate"] != 1)
        return (_round(inner, down=True), _round(outer, down=False))

    @property
    def undecided_in_proof(self):
        """How many decided leaves the proof states undecided (their
        certificates are not confirmed by every checker); `None` without a
        proof."""
        return None if self._proof is None else self._proof[1]

    def save_proof(self, path):
        """Writes the paving's `reach` proof file (proofs/FORMAT.md), once
        the independent checker says VALID, as `detach reach --proof`; the
        paving must have been made with `Scene.reach(..., proof=True)`."""
        if self._proof is None:
            raise DetachError("this paving has no proof: run Scene.reach(..., proof=True)")
        _detach.write_proof(self._proof[0], str(path))

    def plot(self, ax=None, legend=True):
        """Draws the paving with matplotlib: leaves proved to reach the
        target, proved to avoid it, undecided; returns the axes."""
        from ._plot import plot_reach

        return plot_reach(self, ax=ax, legend=legend)

    def __len__(self):
        return len(self.leaves)

    def __repr__(self):
        counts = [int((self.leaves["fate"] == k).sum()) for k in range(3)]
        return "<detach.Reach {} reach, {} avoid, {} undecided>".format(*counts)


def _round(q, down):
    """The double next to the rational `q` on the side asked for."""
    import math

    x = float(q)
    from fractions import Fraction

    if down and Fraction(x) > q:
        x = math.nextafter(x, -math.inf)
    if not down and Fraction(x) < q:
        x = math.nextafter(x, math.inf)
    return x


_BAND_DTYPE = np.dtype(
    [
        ("t_lo", "f8"),
        ("t_hi", "f8"),
        ("theta_lo", "f8"),
        ("theta_hi", "f8"),
        ("theta_dot_lo", "f8"),
        ("theta_dot_hi", "f8"),
    ]
)


def _axis(flag, axis):
    """`"mu=0:2"`, or `("mu", lo, hi)` with decimal ends."""
    if isinstance(axis, str):
        try:
            return _detach.param_axis(axis)
        except ValueError as e:
            raise DetachError(f"{flag}: {e}") from None
    try:
        name, lo, hi = axis
    except (TypeError, ValueError):
        raise DetachError(f"{flag} must be 'NAME=LO:HI' or (name, lo, hi), got {axis!r}") from None
    return (str(name), decimal_text(name, lo), decimal_text(name, hi))


@dataclass(frozen=True)
class Area:
    """`lower ≤ area ≤ upper` (doubles rounded outward); `how`:
    `quadrature`, `paving`, `quadrature and paving`, or `empty: ...`."""

    name: str
    label: str
    lower: float
    upper: float
    how: str

    @property
    def width(self):
        return self.upper - self.lower


@dataclass(frozen=True)
class SetArea:
    """A set's certified area bounds from a paving: `inner ≤ area ≤ outer`.

    `inner`, `outer` are doubles rounded outward; `inner_text`,
    `outer_text` the same doubles' exact decimal values. `empty` says why a
    set is empty by construction (both bounds then exactly 0)."""

    name: str
    label: str
    inner: float
    outer: float
    empty: Optional[str]

    @property
    def inner_text(self):
        return str(decimal.Decimal(self.inner))

    @property
    def outer_text(self):
        return str(decimal.Decimal(self.outer))


_LEAF_DTYPE_EDGES = [
    ("theta_lo", "f8"),
    ("theta_hi", "f8"),
    ("theta_dot_lo", "f8"),
    ("theta_dot_hi", "f8"),
]


class Paving:
    """The result of `Scene.pave`: leaves, certified areas, why it stopped."""

    def __init__(self, native, scene):
        self._native = native
        self.scene = scene
        self._leaves = None

    @property
    def leaves(self):
        """Every leaf as a numpy structured array: `theta_lo`, `theta_hi`,
        `theta_dot_lo`, `theta_dot_hi` (the exact double edges), one label
        column per region (`omega`, `omega0`: in, out, undecided, undefined)
        and `cell` (one of `CLASSES`)."""
        if self._leaves is None:
            edges = np.frombuffer(self._native.edges(), dtype=np.float64).reshape(-1, 4)
            names = list(self._native.names)
            codes = np.frombuffer(self._native.labels(), dtype=np.uint8).reshape(-1, len(names) + 1)
            dtype = _LEAF_DTYPE_EDGES + [(n, "U9") for n in names] + [("cell", "U24")]
            out = np.empty(len(edges), dtype=dtype)
            for i, (field, _) in enumerate(_LEAF_DTYPE_EDGES):
                out[field] = edges[:, i]
            for j, n in enumerate(names):
                out[n] = np.array(LABELS)[codes[:, j]]
            out["cell"] = np.array(CLASSES)[codes[:, -1]]
            out.flags.writeable = False
            self._leaves = out
        return self._leaves

    @property
    def areas(self):
        """`{name: SetArea}` for Ω, Ω₀ and the four cells, as `detach pave`
        reports them."""
        return {
            name: SetArea(name, label, inner, outer, empty or None)
            for name, label, inner, outer, empty in self._native.areas()
        }

    @property
    def stop(self):
        """Why refinement stopped: `all_decided`, `resolution`,
        `double_precision_limit`, `budget` or `interrupted`."""
        return self._native.stop

    @property
    def stop_text(self):
        return self._native.stop_text

    @property
    def complete(self):
        """False when the budget or an interruption stopped refinement."""
        return self._native.complete

    @property
    def elapsed(self):
        """Seconds spent paving (as `pave --json`'s `elapsed_s`)."""
        return self._native.elapsed

    @property
    def eps(self):
        return self._native.eps

    @property
    def root(self):
        """The box paved: `((theta lo, hi), (theta_dot lo, hi))`."""
        return self._native.root

    def __len__(self):
        return len(self.leaves)

    def __repr__(self):
        return f"<detach.Paving {self.scene.name}: {len(self)} leaves, stop {self.stop}>"

    def to_pandas(self):
        """The leaves as a pandas DataFrame (labels and cell categorical)."""
        import pandas as pd

        df = pd.DataFrame(self.leaves)
        for n in list(self._native.names):
            df[n] = pd.Categorical(df[n], categories=LABELS)
        df["cell"] = pd.Categorical(df["cell"], categories=CLASSES)
        return df

    def save_proof(self, path):
        """Writes the paving as a proof file (proofs/FORMAT.md), once the
        independent checker says VALID, as `detach pave --proof`."""
        self._native.save_proof(self.scene._native, str(path))

    def plot(self, ax=None, legend=True):
        """Draws the atlas with matplotlib in the CLI's colours: the four
        cells, undecided (grey) and undefined (hatched) leaves."""
        from ._plot import plot_paving

        return plot_paving(self, ax=ax, legend=legend)


@dataclass(frozen=True)
class Verification:
    """What the independent checker says of a proof file."""

    verdict: str
    claim: str
    why: str

    @property
    def valid(self):
        return self.verdict == "VALID"

    def __bool__(self):
        return self.valid


def verify(path):
    """Checks a proof file with the independent checker, as `detach verify`
    does; a file that cannot be read raises OSError (FileNotFoundError
    when it is missing)."""
    return Verification(*_detach.verify(str(path)))


@dataclass(frozen=True)
class Share:
    """A set's share of the parameter box by status (fractions of its
    volume)."""

    name: str
    label: str
    nonempty: float
    empty: float
    undecided: float


class ParamAtlas:
    """The result of `Scene.param_atlas`: boxes of parameters and each set's
    certified status on them, thresholds in one parameter, a proof file."""

    def __init__(self, native, scene):
        self._native = native
        self.scene = scene
        self._json = None

    @property
    def axes(self):
        """`[(name, lo, hi)]` as given."""
        return [tuple(a) for a in self._native.axes]

    @property
    def sets(self):
        return list(self._native.sets)

    @property
    def bounds(self):
        """Box bounds as a `(boxes, axes, 2)` array: per box and axis, the
        lower and upper ends (the enclosures' outer doubles)."""
        n = len(self.axes)
        b = np.frombuffer(self._native.bounds(), dtype=np.float64).reshape(-1, n, 2)
        b.flags.writeable = False
        return b

    @property
    def status(self):
        """`{set: array of STATUSES}`, one entry per box of `bounds`."""
        codes = self._codes()
        names = np.array(STATUSES)
        return {s: names[codes[:, k]] for k, s in enumerate(self.sets)}

    def _codes(self):
        return np.frombuffer(self._native.statuses(), dtype=np.uint8).reshape(-1, len(self.sets) + 1)

    @property
    def shares(self):
        """`{set: Share}`: the box's volume proved non-empty, proved empty
        and undecided."""
        return {name: Share(name, label, ne, e, u) for name, label, ne, e, u in self._native.shares()}

    @property
    def json(self):
        """The atlas as `detach params --json` writes it (a dict)."""
        if self._json is None:
            import json

            self._json = json.loads(self._native.json())
        return self._json

    @property
    def thresholds(self):
        """In one parameter: where each set changes status, `{set, param,
        below, above, enclosure: [lo, hi]}` with decimal ends."""
        return list(self.json.get("thresholds", []))

    @property
    def complete(self):
        """False when the box budget stopped refinement (a coarser atlas)."""
        return self._native.complete

    @property
    def elapsed(self):
        return self._native.elapsed

    @property
    def eps(self):
        return self._native.eps

    def __len__(self):
        return len(self._codes())

    def __repr__(self):
        axes = ", ".join(f"{n} in [{lo}, {hi}]" for n, lo, hi in self.axes)
        return f"<detach.ParamAtlas {self.scene.name}: {axes}, {len(self)} boxes>"

    def save_proof(self, path):
        """Writes the atlas as a proof file (proofs/FORMAT.md), once the
        independent checker says VALID, as `detach params --proof`."""
        self._native.save_proof(str(path))

    def plot(self, ax=None, legend=True):
        """The plane of a two-parameter atlas (or the line of a
        one-parameter one) in the colours of `detach params --out`."""
        from ._plot import plot_param_atlas

        return plot_param_atlas(self, ax=ax, legend=legend)
