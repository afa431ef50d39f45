"""Task registration: one frozen spec per task, registered with Gymnasium under ``planshape/``.

A task family module supplies strings only — an environment entry point and one abstract-model
entry point per PDDL granularity — so nothing is imported until an environment is made, and the
engine never imports a specific task.

``gymnasium.make(id)`` gives the task with its own sparse reward; ``reward=`` selects
``"sparse"``, ``"dense"`` (the hand-crafted reward) or ``"shaped"``; with ``"shaped"``,
``potential=`` (a registered id or ``module:attr``), ``model=`` (a PDDL granularity such as
``"single"``, ``"multi"``, ``"grid"``) and ``gamma=`` (required: the learner's discount) apply.

Example:
    >>> register_task(TaskSpec(
    ...     id="planshape/DocToy-v0",
    ...     env_entry_point="my_tasks.toy:ToyEnv",
    ...     models={"single": "my_tasks.toy:single_model"},
    ...     max_episode_steps=25,
    ...     description="a toy for the docs",
    ...     family="DocToy"))
    >>> "planshape/DocToy-v0" in task_ids()
    True
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import gymnasium

from planshape.errors import BadInputError, RegistrationError, UnknownIdError
from planshape.planning import PddlTask, Plan, load_task, solve
from planshape.shaping.abstraction import Abstraction, Classifier
from planshape.shaping.potentials import Geometry, Potential, load_reference, make_potential
from planshape.shaping.progress import PlanProgress, SubgoalMatch
from planshape.shaping.wrapper import PotentialShaping

REWARDS = ("sparse", "dense", "shaped")
NAMESPACE = "planshape"


@dataclass(frozen=True)
class AbstractModel:
    """One PDDL model of a task together with the classifiers that ground it.

    Args:
        domain: path of the domain file.
        problem: path of the problem file (generated problems are written by code to a file
            first, so that errors can name a file and a line).
        classifiers: one classifier per fluent predicate of the domain.
        geometry: the ``locate``/``positions`` hooks for distance-based potentials, if any.
    """

    domain: Path
    problem: Path
    classifiers: Mapping[str, Classifier]
    geometry: Geometry | None = None


@dataclass(frozen=True)
class TaskSpec:
    """Everything planshape needs to make a task; strings only, so specs print as JSON.

    Attributes:
        id: the Gymnasium id, in the ``planshape/`` namespace.
        env_entry_point: ``"module:attr"`` of the environment class or factory; called with
            ``reward="sparse"`` or ``reward="dense"`` and any extra keyword arguments.
        models: PDDL granularity name -> ``"module:attr"`` of a zero-argument factory
            returning an :class:`AbstractModel`.
        max_episode_steps: the episode length (Gymnasium's ``TimeLimit`` truncates).
        description: one line for ``planshape tasks``.
        default_model: the granularity used when ``model=`` is omitted (the first by default).
        kwargs: extra keyword arguments of the environment entry point.
        fixed: every episode starts in the same state and the environment is deterministic, so
            one episode of a deterministic policy measures it (the evaluation runs one).
        instances: for a task-instance distribution, ``"module:attr"`` of a zero-argument
            factory returning its instance set (an object with ``train`` and ``eval``
            sequences); the environment entry point then takes ``instances="train"`` or
            ``"eval"`` and reports each episode's instance as ``info["instance"]``, and every
            model factory takes that instance and builds the instance's model.
        family: the task's family, the key of its hyperparameter tables
            (:mod:`planshape.training.hyperparams`): ``"Reach"``, ``"PushRandomized"``,
            ``"MetaWorld"``.
    """

    id: str
    env_entry_point: str
    models: Mapping[str, str]
    max_episode_steps: int
    description: str = ""
    default_model: str = ""
    kwargs: Mapping[str, Any] = field(default_factory=dict)
    fixed: bool = False
    instances: str = ""
    family: str = ""

    def __post_init__(self) -> None:
        if not self.family:
            raise RegistrationError(
                f"task {self.id!r}: name its family (family=...), the key of its "
                "hyperparameter table (planshape.training.hyperparams), e.g. 'Reach' or 'MetaWorld'"
            )
        if self.fixed and self.instances:
            raise RegistrationError(f"task {self.id!r}: a fixed task has no instance set")
        if not self.id.startswith(f"{NAMESPACE}/"):
            raise RegistrationError(f"task id {self.id!r} must be in the {NAMESPACE}/ namespace")
        if not self.models:
            raise RegistrationError(f"task {self.id!r} has no abstract model")
        if not self.default_model:
            object.__setattr__(self, "default_model", next(iter(self.models)))
        if self.default_model not in self.models:
            raise RegistrationError(
                f"task {self.id!r}: default model {self.default_model!r} is not one of "
                f"{sorted(self.models)}"
            )


_TASKS: dict[str, TaskSpec] = {}


def register_task(spec: TaskSpec) -> None:
    """Register ``spec`` with planshape and with Gymnasium (a task with instances trains on its
    training set unless ``instances="eval"`` is passed to ``gymnasium.make``)."""
    _TASKS[spec.id] = spec
    defaults = {"instances": "train"} if spec.instances else {}
    gymnasium.register(
        id=spec.id,
        entry_point=f"{__name__}:make_task_env",
        kwargs={"task": spec.id, **defaults, **spec.kwargs},
        max_episode_steps=spec.max_episode_steps,
    )


def instance_set(spec: TaskSpec) -> Any:
    """The instance set of a task-instance distribution, or None for any other task."""
    return load_reference(spec.instances)() if spec.instances else None


def instances_summary(spec: TaskSpec) -> dict[str, int] | None:
    """``{"train": N, "eval": M}`` for a task-instance distribution, None otherwise."""
    instances = instance_set(spec)
    return (
        None if instances is None else {"train": len(instances.train), "eval": len(instances.eval)}
    )


def task_ids() -> list[str]:
    """Registered task ids, sorted."""
    return sorted(_TASKS)


def task_spec(task_id: str) -> TaskSpec:
    """The spec of ``task_id``; an unknown id lists the known ones."""
    if task_id not in _TASKS:
        raise UnknownIdError("task", task_id, _TASKS, hint="`planshape tasks` lists them")
    return _TASKS[task_id]


def make_task_env(
    task: str,
    reward: str = "sparse",
    potential: Any = None,
    model: str | None = None,
    gamma: float | None = None,
    potential_kwargs: Mapping[str, Any] | None = None,
    potential_scale: float = 1.0,
    search: str = "astar-lmcut",
    match: SubgoalMatch = "fluents",
    **env_kwargs: Any,
) -> gymnasium.Env:
    """Gymnasium's entry point for every planshape task (see the module docstring)."""
    spec = task_spec(task)
    if reward not in REWARDS:
        raise UnknownIdError("reward variant", reward, REWARDS, hint=f"for task {task!r}")
    if reward != "shaped":
        given = [n for n, v in (("potential", potential), ("model", model), ("gamma", gamma)) if v]
        if given:
            raise BadInputError(
                f"{task}: {', '.join(given)} apply only with reward='shaped' (got "
                f"reward={reward!r})"
            )
        return load_reference(spec.env_entry_point)(reward=reward, **env_kwargs)
    if gamma is None:
        raise BadInputError(
            f"{task}: reward='shaped' needs gamma=, the discount of the learner that will "
            "train on it (a different discount changes the optimal policy)"
        )
    env = load_reference(spec.env_entry_point)(reward="sparse", **env_kwargs)
    potential = potential if potential is not None else "plan-based"
    options = dict(
        gamma=gamma,
        potential_kwargs=potential_kwargs,
        potential_scale=potential_scale,
        search=search,
        match=match,
    )
    if spec.instances:
        name = model or spec.default_model
        abstract_model(spec, name)  # an unknown model is refused here, not at the first reset
        return shape_instances(env, spec.id, name, potential, **options)  # type: ignore[arg-type]
    return shape(env, abstract_model(spec, model), potential, **options)  # type: ignore[arg-type]


def abstract_model(spec: TaskSpec, model: str | None = None, instance: Any = None) -> AbstractModel:
    """Build the :class:`AbstractModel` of one granularity of a task; for a task-instance
    distribution, that of ``instance`` (by default its first training instance)."""
    name = model or spec.default_model
    if name not in spec.models:
        raise UnknownIdError("model", name, spec.models, hint=f"for task {spec.id!r}")
    factory = load_reference(spec.models[name])
    if spec.instances:
        built = factory(instance if instance is not None else instance_set(spec).train[0])
    else:
        built = factory()
    if not isinstance(built, AbstractModel):
        raise RegistrationError(
            f"{spec.id}: model factory {spec.models[name]!r} returned {type(built).__name__}, "
            "not an AbstractModel"
        )
    return built


def _stamped(path: Path) -> tuple[Path, int]:
    """A path with its modification time, so that an edited file is parsed and planned again."""
    path = Path(path)
    try:
        return path, path.stat().st_mtime_ns
    except FileNotFoundError:
        raise BadInputError(f"{path}: PDDL file not found") from None


@functools.lru_cache(maxsize=512)
def _planned(
    domain: Path, _domain_mtime: int, problem: Path, _problem_mtime: int, search: str
) -> tuple[PddlTask, Plan]:
    """Parse and plan once per process (the on-disk plan cache also spans processes)."""
    return load_task(domain, problem), solve(domain, problem, search=search)


def shape(
    env: gymnasium.Env,
    model: AbstractModel,
    potential: Any,
    *,
    gamma: float,
    potential_kwargs: Mapping[str, Any] | None = None,
    potential_scale: float = 1.0,
    search: str = "astar-lmcut",
    match: SubgoalMatch = "fluents",
) -> gymnasium.Env:
    """Plan ``model`` (cached), bind its classifiers and wrap ``env`` in potential shaping.

    ``potential_scale`` multiplies φ on top of the potential's own ``scale`` (the benchmark's
    ``shaping_scale``, see :mod:`planshape.training.hyperparams`)."""
    return PotentialShaping(
        env,
        _scaled(potential, potential_kwargs, potential_scale),
        _progress(model, search, match),
        gamma=gamma,
        geometry=model.geometry,
    )


def _scaled(potential: Any, kwargs: Mapping[str, Any] | None, scale: float) -> Potential:
    """The potential ``potential`` made with ``kwargs``, φ multiplied by ``scale``."""
    return make_potential(potential, **dict(kwargs or {})).rescaled(scale)


def _progress(model: AbstractModel, search: str, match: SubgoalMatch) -> PlanProgress:
    """Plan ``model`` (cached) and bind its classifiers."""
    task, plan = _planned(*_stamped(model.domain), *_stamped(model.problem), search)
    return PlanProgress(plan.subgoals, Abstraction(task, model.classifiers), match=match)


def instance_plan(
    task: str,
    model: str,
    instance: Any,
    search: str = "astar-lmcut",
    match: SubgoalMatch = "fluents",
) -> tuple[PlanProgress, Geometry | None]:
    """The plan progress and geometry hooks of one instance of a task-instance distribution:
    its model built, planned by Fast Downward through the plan cache and bound, once per
    process (the shaping wrappers of every environment share them, however the call spells
    its defaults)."""
    return _instance_plan(task, model, instance, search, match)


@functools.lru_cache(maxsize=4096)
def _instance_plan(
    task: str, model: str, instance: Any, search: str, match: SubgoalMatch
) -> tuple[PlanProgress, Geometry | None]:
    """:func:`instance_plan`, cached on one key per plan (an ``lru_cache`` keys ``f(a)`` and
    ``f(a, default)`` apart)."""
    built = abstract_model(task_spec(task), model, instance)
    return _progress(built, search, match), built.geometry


def shape_instances(
    env: gymnasium.Env,
    task: str,
    model: str,
    potential: Any,
    *,
    gamma: float,
    potential_kwargs: Mapping[str, Any] | None = None,
    potential_scale: float = 1.0,
    search: str = "astar-lmcut",
    match: SubgoalMatch = "fluents",
) -> gymnasium.Env:
    """Wrap ``env``, a task-instance distribution, in potential shaping whose plan is that of
    each episode's instance (:func:`instance_plan`), switched on ``reset`` only."""

    def plans(instance: Any) -> tuple[PlanProgress, Geometry | None]:
        return instance_plan(task, model, instance, search, match)

    # until the first reset, the plan of the first training instance
    progress, geometry = plans(instance_set(task_spec(task)).train[0])
    return PotentialShaping(
        env,
        _scaled(potential, potential_kwargs, potential_scale),
        progress,
        gamma=gamma,
        geometry=geometry,
        plans=plans,
    )


def observe_progress(
    env: gymnasium.Env,
    task: str,
    model: str | None = None,
    search: str = "astar-lmcut",
    match: SubgoalMatch = "fluents",
) -> gymnasium.Env:
    """``env`` (``task`` with any reward) seen with plan progress appended to its observation
    (:class:`~planshape.shaping.observed_progress.ObservedProgress`): the plan of ``model``, or of
    each episode's instance on a task-instance distribution, planned as :func:`shape` plans it."""
    from planshape.shaping.observed_progress import ObservedProgress

    spec = task_spec(task)
    if spec.instances:
        name = model or spec.default_model

        def plans(instance: Any) -> PlanProgress:
            return instance_plan(task, name, instance, search, match)[0]

        return ObservedProgress(env, plans(instance_set(spec).train[0]), plans=plans)
    return ObservedProgress(env, _progress(abstract_model(spec, model), search, match))
