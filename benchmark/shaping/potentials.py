"""The :class:`Potential` extension point, the context it sees, and the potential registry.

A potential φ maps the *augmented* state the shaping wrapper keeps — the observation, the plan
progress ``max_idx`` and the time index — to a number. The wrapper computes
F = γ·φ(s') − φ(s) from it; a potential never computes shaping itself and never reaches into an
environment: everything it may use is in the :class:`ShapingContext`.

Writing one takes one method:

    >>> class HalfWay(Potential):
    ...     '''1 once half of the plan is done, else 0.'''
    ...     def potential(self, ctx: ShapingContext) -> float:
    ...         return float(2 * ctx.progress >= ctx.final)
    >>> phi = HalfWay(scale=10.0)
    >>> phi(ShapingContext(obs=None, progress=3, t=7, subgoals=(frozenset(),) * 5))
    10.0

Register it under an id with :func:`register_potential`, or pass ``"my_module:HalfWay"``
wherever a potential is asked for (``gymnasium.make(..., potential="my_module:HalfWay")``,
``planshape bench --potential my_module:HalfWay``).
"""

from __future__ import annotations

import copy
import importlib
import importlib.util
import math
import os
import sys
import traceback
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, TypeVar

import numpy as np

from planshape.errors import (
    BadInputError,
    FileError,
    PotentialError,
    PotentialValueError,
    UnknownIdError,
)
from planshape.planning.model import AbstractState

if TYPE_CHECKING:
    from planshape.shaping.abstraction import Abstraction

_Value = TypeVar("_Value")
#: a potential specialized to one plan: (observation, progress) -> φ before scale, or, for a
#: ``time_dependent`` potential, (observation, progress, t) -> φ before scale
StepPotential = Callable[..., float]


class Geometry(Protocol):
    """The task's hooks that relate abstract subgoals to coordinates (for distance potentials).

    ``locate(subgoal)`` gives, for each entity the subgoal constrains (``"ee"``, ``"box"``, …),
    the coordinates it must be at; the mapping's order is the priority order. ``positions(obs)``
    gives every entity's current coordinates in an observation. A geometry whose entities
    are positions in one frame (so that the distance between two entities means something)
    sets ``shared_frame = True``; potentials that chain entities (``goal-distance``,
    ``plan-path``) need it when there is more than one entity.

    Optional: ``positions_of_values(values)``, the same positions from a flat (1-D)
    observation's ``obs.tolist()``, lets a step function that also keys the observation's
    classifiers convert it once (the planar tasks have it; see
    :class:`planshape.shaping.abstraction.Vectorized`'s ``key_of_values``).
    """

    #: whether the entities' coordinates are positions in one frame (see above); a geometry
    #: that does not set it is taken not to share one
    shared_frame: bool

    def locate(self, subgoal: AbstractState) -> Mapping[str, np.ndarray]: ...

    def positions(self, obs: Any) -> Mapping[str, np.ndarray]: ...


@dataclass(slots=True)
class ShapingContext:
    """Everything a potential may look at for one state of an episode.

    Attributes:
        obs: the observation s.
        progress: ``max_idx``, the furthest plan subgoal reached in this episode so far.
        t: the time index: the number of steps taken since ``reset`` (0 at reset).
        subgoals: Ŝ = [ŝ0 … ŝn], the plan's abstract states.
        geometry: the task's ``locate``/``positions`` hooks, when the task has coordinates.
        abstraction: the task's classifiers and PDDL task, which map ``obs`` to its abstract
            state (see :attr:`abstract_state`).
        atoms: ŝ = Abstract(s), the atoms that hold in ``obs`` (static ones included), when
            whoever builds the context already has them; otherwise None, and
            :attr:`abstract_state` classifies ``obs`` on first use and stores them here.
    """

    obs: Any
    progress: int
    t: int
    subgoals: Sequence[AbstractState]
    geometry: Geometry | None = None
    abstraction: Abstraction | None = None
    atoms: AbstractState | None = field(default=None, repr=False)

    @property
    def final(self) -> int:
        """Index of the plan's last subgoal (the plan length)."""
        return len(self.subgoals) - 1

    @property
    def next_index(self) -> int:
        """Index of the subgoal to reach next (the last one once the plan is done)."""
        return min(self.progress + 1, self.final)

    @property
    def abstract_state(self) -> AbstractState:
        """ŝ = Abstract(s), computed on first use only (all groundings are classified)."""
        if self.atoms is None:
            if self.abstraction is None:
                raise PotentialError("this context has no abstraction to compute ŝ from")
            self.atoms = self.abstraction.abstract_state(self.obs)
        return self.atoms

    def require_geometry(self, who: str) -> Geometry:
        if self.geometry is None:
            raise BadInputError(
                f"potential {who!r} needs the task's locate/positions hooks, and this task's "
                "abstract model defines none; pick a potential that uses progress only"
            )
        return self.geometry


class _UndeclaredTimeRead(Exception):
    """Raised inside a potential that uses ``ctx.t`` undeclared; reported with its name."""


class _UndeclaredTime:
    """``ctx.t`` for a potential that does not declare ``time_dependent = True``: any use of it
    as a number raises, naming what to change (printing it is allowed)."""

    __slots__ = ()

    def _refuse(self, *_: Any) -> Any:
        raise _UndeclaredTimeRead()

    __int__ = __index__ = __float__ = __bool__ = __hash__ = _refuse
    __add__ = __radd__ = __sub__ = __rsub__ = __mul__ = __rmul__ = _refuse
    __truediv__ = __rtruediv__ = __floordiv__ = __rfloordiv__ = __pow__ = __rpow__ = _refuse
    __mod__ = __rmod__ = __neg__ = __pos__ = __abs__ = _refuse
    __eq__ = __ne__ = __lt__ = __le__ = __gt__ = __ge__ = _refuse  # type: ignore[assignment]

    def __repr__(self) -> str:
        return "<t: not declared>"

    __format__ = lambda self, spec: repr(self)  # noqa: E731


#: what an undeclared potential sees as ``ctx.t``
UNDECLARED_TIME: Any = _UndeclaredTime()


def read_only(obs: Any) -> Any:
    """A read-only view of an observation (an array, or a mapping of arrays); anything else
    is returned as it is.

    Example:
        >>> view = read_only(np.zeros(2))
        >>> view.flags.writeable
        False
    """
    if type(obs) is np.ndarray:
        if not obs.flags.writeable:
            return obs
        view = obs.view()
        view.flags.writeable = False
        return view
    if isinstance(obs, Mapping):
        return MappingProxyType({k: read_only(v) for k, v in obs.items()})
    return obs


class Potential(ABC):
    """Base class of every potential: implement :meth:`potential`, nothing else.

    The base class applies ``scale``, checks that the value is finite (naming the potential
    when it is not) and declares what the invariance checker needs to know.

    Args:
        scale: multiplies φ. The shaping term is scale-equivariant, so scale sets how loud the
            shaping is relative to the task reward without touching which policies are optimal.
    """

    #: set True when φ depends on ``ctx.t``; the invariance checker then uses a time-augmented,
    #: finite-horizon MDP (Devlin & Kudenko 2012).
    time_dependent: ClassVar[bool] = False
    #: the registered id, filled in by :func:`make_potential`; used in messages and results.
    id: str = ""

    def __init__(self, scale: float = 1.0):
        if not math.isfinite(scale):
            raise BadInputError(f"{type(self).__name__}: scale must be finite, not {scale}")
        self.scale = float(scale)

    @abstractmethod
    def potential(self, ctx: ShapingContext) -> float:
        """φ of the augmented state in ``ctx``, before ``scale``."""

    def rescaled(self, factor: float) -> Potential:
        """This potential with φ multiplied by ``factor`` (a shallow copy; ``self`` unchanged).

        Example:
            >>> from planshape.baselines.paper import PlanBased
            >>> PlanBased(scale=2.0).rescaled(50.0).scale
            100.0
        """
        if not (math.isfinite(factor) and factor > 0):
            raise BadInputError(
                f"{self.name}: a potential's scale factor must be finite and positive, not {factor}"
            )
        if factor == 1.0:
            return self
        copied = copy.copy(self)
        copied.scale = self.scale * float(factor)
        return copied

    def __call__(self, ctx: ShapingContext) -> float:
        """φ of ``ctx`` times ``scale``, checked to be one finite number.

        The potential sees a read-only view of the observation (the learner's own array, which
        it must not change) and, unless it declares ``time_dependent = True``, a time index it
        cannot use: reading ``ctx.t`` undeclared is an error (the invariance checker would
        otherwise check it as if φ(x, 0) held at every t)."""
        obs, t = ctx.obs, ctx.t
        if type(obs) is not np.ndarray or obs.flags.writeable:  # planar observations are
            ctx.obs = read_only(obs)  # read-only already: the per-step path skips the view
        if not self.time_dependent:
            ctx.t = UNDECLARED_TIME
        try:
            raw = self.potential(ctx)
        except _UndeclaredTimeRead:
            raise PotentialValueError(
                f"potential {self.name!r} reads ctx.t without declaring time_dependent = True; "
                "set time_dependent = True on its class (the invariance checker then checks "
                "every time index), or do not read the time"
            ) from None
        except ValueError as exc:
            if "read-only" not in str(exc):
                raise
            raise PotentialValueError(
                f"potential {self.name!r} writes into ctx.obs, the observation the learner "
                "receives; work on a copy (ctx.obs.copy())"
            ) from None
        finally:
            ctx.obs, ctx.t = obs, t
        if type(raw) is float:  # the common case, checked in one step
            value = self.scale * raw
            if value - value == 0.0:  # finite (inf - inf and nan - nan are nan)
                return value
        try:
            if isinstance(raw, str | bytes):
                raise TypeError
            value = self.scale * float(raw)
        except (TypeError, ValueError):
            raise PotentialValueError(
                f"potential {self.name!r} returned {_describe(raw)} at progress={ctx.progress}, "
                f"t={ctx.t}; potential(ctx) must return one float"
            ) from None
        if not math.isfinite(value):
            raise PotentialValueError(
                f"potential {self.name!r} returned {value} at progress={ctx.progress}, t={ctx.t}; "
                "a potential must be finite everywhere (guard divisions and logs)"
            )
        return value

    def for_discount(self, gamma: float) -> Potential:
        """This potential for a learner whose discount is ``gamma``.

        The shaping wrapper and the invariance checker call it with their γ before using the
        potential, so a potential defined through the learner's discount (the
        ``h-*-discounted`` ones) takes it from there instead of from a constant. Any fixed φ
        keeps the optimal policy; what γ changes is which φ is meant. The default returns
        ``self``.

        Example:
            >>> from planshape.shaping.potentials import make_potential
            >>> make_potential("h-star-discounted").for_discount(0.95).gamma
            0.95
            >>> phi = make_potential("plan-based")
            >>> phi.for_discount(0.95) is phi
            True
        """
        return self

    def specialize(self, ctx: ShapingContext) -> StepPotential | None:
        """Optional: φ before ``scale`` as a plain function of (observation, progress), for
        the plan, geometry and abstraction of ``ctx`` (an episode's first state).

        The shaping wrapper calls it once per plan and then evaluates that function on every
        step instead of building a context and calling :meth:`potential`: the planar tasks
        step in about 20 µs, so a context and the checks of ``__call__`` are a large part of
        a step. The function must return what ``potential`` returns, bit for bit, on every
        observation and progress of that plan (a test checks each reference potential). A
        ``time_dependent`` potential's function takes the time index too, ``(observation,
        progress, t)``, and must agree with ``potential`` at every t. A value that is not one
        finite float sends that step through ``__call__``, which
        names the problem. Only the class whose body defines ``specialize`` gets the fast
        path (:meth:`step_function`): a subclass that changes how φ is computed falls back to
        :meth:`potential` unless it restates ``specialize = Parent.specialize``.

        Example:
            >>> class Progress(Potential):
            ...     def potential(self, ctx):
            ...         return float(ctx.progress)
            ...     def specialize(self, ctx):
            ...         return lambda obs, progress: float(progress)
            >>> ctx = ShapingContext(obs=None, progress=2, t=0, subgoals=(frozenset(),) * 4)
            >>> Progress().step_function(ctx)(None, 2) == Progress().potential(ctx)
            True
        """
        return None

    def step_function(self, ctx: ShapingContext) -> StepPotential | None:
        """:meth:`specialize` where this class may use it (see there), else None."""
        if "specialize" not in type(self).__dict__:
            return None
        return self.specialize(ctx)

    @property
    def name(self) -> str:
        return self.id or f"{type(self).__module__}:{type(self).__qualname__}"

    def __repr__(self) -> str:
        return f"{type(self).__name__}(scale={self.scale})"


# --------------------------------------------------------------------------------------------
# registry: id -> "module:attr", resolved only when made (like gymnasium's entry points)

_REGISTRY: dict[str, tuple[str, dict[str, Any]]] = {}


def register_potential(potential_id: str, entry_point: str, **kwargs: Any) -> None:
    """Register ``entry_point`` (``"module:attr"``) under ``potential_id`` with default kwargs.

    Example:
        >>> register_potential("doc-half-way", "planshape.baselines.paper:PlanBased", scale=0.5)
        >>> make_potential("doc-half-way").scale
        0.5
    """
    if ":" not in entry_point:
        raise BadInputError(f"entry point {entry_point!r} must look like 'module:attr'")
    _REGISTRY[potential_id] = (entry_point, dict(kwargs))


def potential_ids() -> list[str]:
    """The registered potential ids, sorted."""
    return sorted(_REGISTRY)


def load_reference(reference: str) -> Any:
    """Import ``"module:attr"`` and return the attribute, with errors that say what failed."""
    module_name, _, attr = reference.partition(":")
    if not module_name or not attr:
        raise BadInputError(f"reference {reference!r} must look like 'module:attr'")
    _current_folder_on_path()
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        if exc.name and exc.name != module_name and not module_name.startswith(exc.name + "."):
            raise BadInputError(
                f"module {module_name!r} of {reference!r} imports {exc.name!r}, which is not "
                "installed; install it or remove the import"
            ) from None
        raise BadInputError(
            f"cannot import module {module_name!r} of {reference!r} ({exc}); is it on sys.path "
            "(run from the folder that holds it, or install it)?"
        ) from None
    except SyntaxError as exc:  # IndentationError too
        where = f"{exc.filename}:{exc.lineno}: " if exc.filename else ""
        raise FileError(
            f"{where}{type(exc).__name__} in module {module_name!r} of {reference!r}: {exc.msg}; "
            "fix the file and run again"
        ) from None
    except Exception as exc:  # the module's own code raised while it was imported
        raise BadInputError(
            f"importing module {module_name!r} of {reference!r} raised {type(exc).__name__}: "
            f"{exc} ({_innermost(exc, module_name)}); fix the module and run again"
        ) from None
    try:
        target: Any = module
        for part in attr.split("."):
            target = getattr(target, part)
    except AttributeError as exc:
        raise BadInputError(f"module {module_name!r} has no attribute {attr!r}") from exc
    return target


def _describe(value: Any) -> str:
    """A value's type and a short repr, for messages about what a potential returned."""
    shape = getattr(value, "shape", None)
    text = repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."
    kind = type(value).__name__ + (f" of shape {tuple(shape)}" if shape is not None else "")
    return f"{kind} {text}"


def _innermost(exc: BaseException, module_name: str) -> str:
    """``file:line`` of the deepest frame of ``exc`` in the module being imported (else the
    deepest frame at all)."""
    frames = traceback.extract_tb(exc.__traceback__)
    try:
        spec = importlib.util.find_spec(module_name)
    except (ImportError, ValueError):
        spec = None
    module_file = spec.origin if spec is not None else None
    chosen = [f for f in frames if module_file and f.filename == module_file] or frames
    return f"{chosen[-1].filename}:{chosen[-1].lineno}" if chosen else "no traceback"


def _current_folder_on_path() -> None:
    """Let ``module:attr`` name a module under the current folder, as ``python -m`` would: the
    ``planshape`` console script does not put the current folder on ``sys.path``."""
    here = os.getcwd()
    if "" not in sys.path and here not in sys.path:
        sys.path.insert(0, here)


def make_potential(reference: str | Potential | type[Potential], **kwargs: Any) -> Potential:
    """A :class:`Potential` from a registered id, a ``"module:attr"`` reference, a subclass or
    an instance. ``kwargs`` override the registered defaults.

    Example:
        >>> make_potential("plan-based").name
        'plan-based'
    """
    potential_id = ""
    if isinstance(reference, Potential):
        if kwargs:
            raise BadInputError("keyword arguments cannot be applied to a potential instance")
        return reference
    if isinstance(reference, str):
        if reference in _REGISTRY:
            potential_id = reference
            entry_point, defaults = _REGISTRY[reference]
            kwargs = {**defaults, **kwargs}
            target = load_reference(entry_point)
        elif ":" in reference:
            potential_id = reference
            target = load_reference(reference)
        else:
            raise UnknownIdError(
                "potential",
                reference,
                _REGISTRY,
                hint="Pass a registered id or 'module:attr' of a Potential subclass",
            )
    else:
        target = reference
    potential = _instantiate(target, kwargs, potential_id or repr(reference))
    if potential_id and not potential.id:
        potential.id = potential_id
    return potential


def _instantiate(target: Any, kwargs: dict[str, Any], label: str) -> Potential:
    if isinstance(target, Potential):
        if kwargs:
            raise BadInputError(f"{label} is a potential instance; it takes no keyword arguments")
        return target
    if isinstance(target, type) and not issubclass(target, Potential):
        raise BadInputError(
            f"{label} is the class {target.__name__}, which does not subclass "
            "planshape.shaping.potentials.Potential; subclass it and implement potential(ctx)"
        )
    if not callable(target):
        raise BadInputError(f"{label} is neither a Potential subclass nor a factory")
    try:
        potential = target(**kwargs)
    except TypeError as exc:
        raise BadInputError(f"cannot construct {label} with {kwargs}: {exc}") from exc
    if not isinstance(potential, Potential):
        raise BadInputError(f"{label} returned {type(potential).__name__}, not a Potential")
    return potential
