"""Read a PDDL domain and problem into a :class:`PddlTask`, with errors that name file and line.

The syntax is parsed by the ``pddl`` package (a lark grammar, so syntax errors carry a line);
this module then checks what that parser leaves open (undeclared predicates, types and objects,
arities, the domain a problem names) and keeps the fragment the planning stage executes:
STRIPS with ``:typing``, ``:negative-preconditions``, ``:equality``, ``:action-costs`` and
constants (the text is first normalized as Fast Downward reads it, :mod:`.prepass`); preconditions
are conjunctions of literals and (in)equalities, effects conjunctions of add and delete
literals, goals conjunctions of atoms. Every name is lower-cased (PDDL is case-insensitive).

Example:
    >>> from planshape.planning.grid import grid_pddl
    >>> grid = grid_pddl(2, 2, start=(0, 0), goal=(1, 1))
    >>> task = parse_task(grid.domain, grid.problem)
    >>> sorted(task.fluent_predicates), sorted(task.static_predicates)
    (['robot_at'], ['neighbors'])
    >>> sorted(task.goal)
    [('robot_at', 'cell_1_1')]
"""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from planshape.errors import PDDLError
from planshape.planning.model import ActionSchema, Atom, PddlTask, PredicateSignature, format_atom
from planshape.planning.prepass import prepare

__all__ = ["decode_pddl", "load_task", "parse_task", "read_pddl", "read_pddl_bytes"]

_SUPPORTED = (
    "planshape supports STRIPS with :typing, :negative-preconditions, :equality and constants"
)


def _syntax(text: str, kind: str, file: str | None) -> Any:
    """Parse ``text`` as a domain or problem with the ``pddl`` package; errors -> PDDLError."""
    from lark.exceptions import UnexpectedEOF, UnexpectedInput, VisitError
    from pddl.parser.domain import DomainParser
    from pddl.parser.problem import ProblemParser

    if not text.strip():
        raise PDDLError(f"the {kind} file is empty", file)
    parser = DomainParser() if kind == "domain" else ProblemParser()
    prepared = prepare(text, kind, file)
    try:
        return parser(prepared)
    except UnexpectedEOF:
        raise PDDLError(
            f"{kind} ends early: a parenthesis is not closed", file, _last_line(text)
        ) from None
    except UnexpectedInput as err:
        token = getattr(err, "token", None)
        if token is not None and getattr(token, "type", "") == "$END":
            raise PDDLError(
                f"{kind} ends early: a parenthesis is not closed", file, _last_line(text)
            ) from None
        found = str(token or getattr(err, "char", None) or "?")
        hint = " (is a parenthesis before it not closed?)" if found.startswith(":") else ""
        raise PDDLError(
            f"syntax error in {kind} at column {err.column}: unexpected {found!r}{hint}",
            file,
            err.line if err.line and err.line > 0 else None,
        ) from None
    except VisitError as err:
        raise _semantic(err.orig_exc, kind, text, file) from None
    except Exception as err:  # the parser's own checks raise assorted exception types
        raise _semantic(err, kind, text, file) from None


def _semantic(err: BaseException, kind: str, text: str, file: str | None) -> PDDLError:
    """A PDDLError for the ``pddl`` package's own checks, reworded where we know them."""
    message = " ".join(str(err).split()) or type(err).__name__
    types = re.match(r"types \[(.*?)\] of term .* not in available types \{(.*)\}", message)
    requirement = re.match(r"Missing PDDL requirement, (:[\w-]+) not found", message)
    if types:
        names = re.findall(r"'([^']+)'", types.group(1))
        declared = ", ".join(sorted(re.findall(r"'([^']+)'", types.group(2))))
        listed = ", ".join(repr(n) for n in names)
        message = f"unknown type {listed}; declared types: {declared}; declare it in :types"
        return PDDLError(message, file, _line_of(text, r"-\s*" + _token(names[0])))
    if requirement:
        message = f"add {requirement.group(1)} to :requirements (the {kind} uses it)"
        return PDDLError(message, file, _line_of(text, r"\(\s*:requirements\b"))
    parents = re.search(
        r"duplicate name '([^']+)' in typed list already inherits from types \[(.*?)\]", message
    )
    if parents:
        name, first = parents.group(1), ", ".join(re.findall(r"'([^']+)'", parents.group(2)))
        message = (
            f"type {name!r} is declared twice, under {first} and again; a PDDL type has one "
            f"parent: keep one declaration of {name!r} (make the other parent its ancestor if "
            "it needs both)"
        )
        return PDDLError(message, file, _line_of(text, r"\(\s*:types\b"))
    quoted = re.findall(r"'([^']+)'", message)
    line = _line_of(text, _token(quoted[0])) if quoted else None
    return PDDLError(f"invalid {kind}: {message}", file, line)


# --------------------------------------------------------------------------- public API


def read_pddl(path: str | Path) -> str:
    """The text of a PDDL file; a missing or unreadable file is a :class:`PDDLError`.

    Example:
        >>> read_pddl("/no/such/domain.pddl")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.PDDLError: /no/such/domain.pddl: cannot read PDDL file (No such file...)
    """
    return decode_pddl(read_pddl_bytes(path), path)


def decode_pddl(data: bytes, path: str | Path | None) -> str:
    """PDDL bytes as text; bytes that are not UTF-8 are a :class:`PDDLError` naming the line.

    Example:
        >>> decode_pddl(b"(define\\n (domain \\xe9))", "d.pddl")  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        planshape.errors.PDDLError: d.pddl:2: not UTF-8 text: byte 0xe9 at offset 17 ...
    """
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        raise PDDLError(
            f"not UTF-8 text: byte {data[err.start]:#04x} at offset {err.start} is not valid "
            "UTF-8 (PDDL is plain text: re-save the file as UTF-8 or ASCII)",
            path,
            line,
        ) from None


def read_pddl_bytes(path: str | Path) -> bytes:
    """The raw bytes of a PDDL file (what the plan cache hashes); errors as :func:`read_pddl`."""
    try:
        return Path(path).read_bytes()
    except OSError as err:
        raise PDDLError(f"cannot read PDDL file ({err.strerror or err})", path) from None


def load_task(domain: str | Path, problem: str | Path) -> PddlTask:
    """Parse and check a PDDL domain and problem file.

    Parsed tasks are memoized by file contents, so loading the same files again is cheap; the
    returned task is shared and must be treated as read-only.

    Example:
        >>> task = load_task("domain.pddl", "problem.pddl")  # doctest: +SKIP
        >>> task.objects_of_type("cell")[:2]  # doctest: +SKIP
        ('cell_0_0', 'cell_0_1')
    """
    return parse_task(read_pddl(domain), read_pddl(problem), str(domain), str(problem))


@functools.lru_cache(maxsize=32)
def parse_task(
    domain_text: str,
    problem_text: str,
    domain_file: str | None = None,
    problem_file: str | None = None,
) -> PddlTask:
    """Parse PDDL text; ``domain_file``/``problem_file`` only name the source in errors.

    Example:
        >>> domain = "(define (domain d) (:predicates (p)))"
        >>> parse_task(domain, "(define (problem q) (:domain d) (:init (r)) (:goal (p)))", "d", "q")
        Traceback (most recent call last):
        ...
        planshape.errors.PDDLError: q:1: unknown predicate 'r' in :init; declared: p
    """
    domain = _syntax(domain_text, "domain", domain_file)
    problem = _syntax(problem_text, "problem", problem_file)
    return _Builder(domain_text, problem_text, domain_file, problem_file).build(domain, problem)


# --------------------------------------------------------------------------- checks


class _Builder:
    """Turns the ``pddl`` package's objects into a checked :class:`PddlTask`."""

    def __init__(self, domain_text: str, problem_text: str, domain_file: Any, problem_file: Any):
        self.texts = {"domain": domain_text, "problem": problem_text}
        self.files = {"domain": domain_file, "problem": problem_file}
        self.types: dict[str, str | None] = {"object": None}
        self.objects: dict[str, str] = {}
        self.predicates: dict[str, PredicateSignature] = {}

    def error(self, message: str, kind: str, pattern: str | None = None) -> PDDLError:
        line = _line_of(self.texts[kind], pattern) if pattern else None
        return PDDLError(message, self.files[kind], line)

    # ----------------------------------------------------------------- domain

    def build(self, domain: Any, problem: Any) -> PddlTask:
        domain_name = str(domain.name).lower()
        for name, parent in sorted(domain.types.items()):
            if str(name).lower() != "object":
                self.types[str(name).lower()] = str(parent).lower() if parent else "object"
        for parent in sorted({p for p in self.types.values() if p} - set(self.types)):
            self.types[parent] = "object"  # `a b - place` declares `place` too (as FD reads it)
        for constant in sorted(domain.constants, key=_name):
            name = str(constant.name).lower()
            self.objects[name] = self.type_of(constant, "domain", f"constant {name!r}")
        for predicate in sorted(domain.predicates, key=_name):
            name = str(predicate.name).lower()
            types = tuple(
                self.type_of(term, "domain", f"predicate {name!r}") for term in predicate.terms
            )
            self.predicates[name] = PredicateSignature(name, types)
        actions = {
            a.name: a for a in (self.action(raw) for raw in sorted(domain.actions, key=_name))
        }
        changed = {atom[0] for a in actions.values() for atom in (*a.add, *a.delete)}
        return self.problem(problem, domain_name, actions, changed)

    def type_of(self, term: Any, kind: str, where: str) -> str:
        tags = sorted(str(t).lower() for t in term.type_tags)
        if len(tags) > 1:
            raise self.error(
                f"'either' types ({' '.join(tags)}) of {where} are not supported; {_SUPPORTED}",
                kind,
                r"\(\s*either\b",
            )
        type_name = tags[0] if tags else "object"
        if type_name not in self.types:
            raise self.unknown_type(type_name, kind, where)
        return type_name

    def unknown_type(self, name: str, kind: str, where: str) -> PDDLError:
        return self.error(
            f"unknown type {name!r} in {where}{_suggest(name, self.types)}; declare it in :types",
            kind,
            r"-\s*" + _token(name),
        )

    def action(self, raw: Any) -> ActionSchema:
        name = str(raw.name).lower()
        parameters = tuple(
            ("?" + str(v.name).lower(), self.type_of(v, "domain", f"action {name!r}"))
            for v in raw.parameters
        )
        scope = {var: type_name for var, type_name in parameters}
        where = f"the precondition of action {name!r}"
        literals: dict[str, list[Any]] = {"positive": [], "negative": [], "equal": [], "ne": []}
        for part in _conjuncts(raw.precondition):
            negated, inner = _literal(part)
            if _is_equality(inner):
                pair = (self.term(inner.left, scope, where), self.term(inner.right, scope, where))
                literals["ne" if negated else "equal"].append(pair)
            elif _is_predicate(inner):
                atom = self.atom(inner, "domain", where, scope)
                literals["negative" if negated else "positive"].append(atom)
            else:
                raise self.unsupported(part, where, "domain")
        add, delete = [], []
        for part in _conjuncts(raw.effect):
            negated, inner = _literal(part)
            if _is_cost(inner):  # :action-costs: Fast Downward sums them; replay ignores them
                continue
            if not _is_predicate(inner):
                raise self.unsupported(part, f"the effect of action {name!r}", "domain")
            atom = self.atom(inner, "domain", f"the effect of action {name!r}", scope)
            (delete if negated else add).append(atom)
        return ActionSchema(
            name,
            parameters,
            positive=tuple(literals["positive"]),
            negative=tuple(literals["negative"]),
            equal=tuple(literals["equal"]),
            not_equal=tuple(literals["ne"]),
            add=tuple(add),
            delete=tuple(delete),
        )

    def term(self, term: Any, scope: dict[str, str], where: str) -> str:
        name = str(term.name).lower()
        if _is_variable(term):
            variable = "?" + name
            if variable not in scope:
                raise self.error(
                    f"variable {variable} in {where} is not a parameter of the action"
                    f"{_suggest(variable, scope)}",
                    "domain",
                    r"\?" + re.escape(name) + r"(?![\w-])",
                )
            return variable
        if name not in self.objects:
            raise self.error(
                f"unknown constant {name!r} in {where}{_suggest(name, self.objects)}; "
                "declare it in :constants",
                "domain",
                _token(name),
            )
        return name

    def atom(self, raw: Any, kind: str, where: str, scope: dict[str, str] | None) -> Atom:
        """A checked atom: declared predicate, right arity, known objects of fitting types."""
        name = str(raw.name).lower()
        signature = self.predicates.get(name)
        if signature is None:
            raise self.error(
                f"unknown predicate {name!r} in {where}{_suggest(name, self.predicates)}; "
                f"declared: {', '.join(sorted(self.predicates)) or 'none'}",
                kind,
                r"\(\s*" + _token(name),
            )
        if len(raw.terms) != signature.arity:
            # the line of the use: an atom of the predicate with that many arguments
            count = len(raw.terms)
            use = r"\(\s*" + _token(name) + r"(?:\s+[^\s()]+){" + str(count) + r"}\s*\)"
            raise self.error(
                f"predicate {name!r} takes {signature.arity} argument(s), "
                f"{len(raw.terms)} given in {where}",
                kind,
                use if _line_of(self.texts[kind], use) else r"\(\s*" + _token(name),
            )
        if scope is not None:  # an action: terms are parameters or constants
            return (name, *(self.term(t, scope, where) for t in raw.terms))
        args = tuple(str(t.name).lower() for t in raw.terms)
        for arg, expected in zip(args, signature.parameter_types, strict=True):
            actual = self.objects.get(arg)
            if actual is None:
                raise self.error(
                    f"unknown object {arg!r} in {format_atom((name, *args))} of {where}"
                    f"{_suggest(arg, self.objects)}; declare it in :objects",
                    kind,
                    r"\(\s*" + _token(name) + r"[^()]*" + _token(arg),
                )
            if not _is_subtype(self.types, actual, expected):
                raise self.error(
                    f"{format_atom((name, *args))} in {where}: {arg!r} has type {actual}, "
                    f"but {name!r} expects type {expected} there",
                    kind,
                    r"\(\s*" + _token(name) + r"[^()]*" + _token(arg),
                )
        return (name, *args)

    def unsupported(self, part: Any, where: str, kind: str) -> PDDLError:
        text = " ".join(str(part).split())
        head = re.match(r"\(\s*([^\s()]+)", text)
        pattern = r"\(\s*" + re.escape(head.group(1)) if head else None
        return self.error(f"unsupported construct {text} in {where}; {_SUPPORTED}", kind, pattern)

    # ----------------------------------------------------------------- problem

    def problem(
        self, raw: Any, domain_name: str, actions: dict[str, ActionSchema], changed: set[str]
    ) -> PddlTask:
        named = str(raw.domain_name).lower() if raw.domain_name is not None else domain_name
        if named != domain_name:
            raise self.error(
                f"the problem is for domain {named!r}, but the domain file defines "
                f"{domain_name!r}; pass the matching domain file",
                "problem",
                r":domain\s+" + _token(named),
            )
        for obj in sorted(raw.objects, key=_name):
            name = str(obj.name).lower()
            self.objects[name] = self.type_of(obj, "problem", f"object {name!r}")
        init = []
        for fact in raw.init:
            if _kind(fact) == "EqualTo" and not _is_equality(fact):  # a cost: (= (f a) 3)
                continue
            if not _is_predicate(fact):
                raise self.unsupported(fact, ":init", "problem")
            init.append(self.atom(fact, "problem", ":init", None))
        goal = []
        for part in _conjuncts(raw.goal):
            if not _is_predicate(part):
                raise self.unsupported(part, ":goal (a conjunction of atoms)", "problem")
            goal.append(self.atom(part, "problem", ":goal", None))
        return PddlTask(
            domain_name=domain_name,
            problem_name=str(raw.name).lower(),
            predicates=self.predicates,
            types=self.types,
            objects=self.objects,
            init=frozenset(init),
            goal=frozenset(goal),
            static_predicates=frozenset(self.predicates) - changed,
            domain_file=self.files["domain"],
            problem_file=self.files["problem"],
            actions=actions,
        )


# --------------------------------------------------------------------------- helpers


def _name(item: Any) -> str:
    return str(item.name).lower()


def _kind(item: Any) -> str:
    return type(item).__name__


def _is_predicate(item: Any) -> bool:
    return _kind(item) == "Predicate"


def _is_equality(item: Any) -> bool:
    return _kind(item) == "EqualTo" and type(item).__module__.endswith("predicates")


def _is_cost(item: Any) -> bool:
    """``(increase (total-cost) …)``, the one numeric effect of ``:action-costs``."""
    return _kind(item) == "Increase" and str(getattr(item, "operands", ("",))[0]) == "(total-cost)"


def _is_variable(term: Any) -> bool:
    return _kind(term) == "Variable"


def _conjuncts(formula: Any) -> Iterator[Any]:
    """The parts of a (possibly nested) ``and``; nothing for an empty formula."""
    if formula is None:
        return
    if _kind(formula) == "And":
        for operand in formula.operands:
            yield from _conjuncts(operand)
    else:
        yield formula


def _literal(formula: Any) -> tuple[bool, Any]:
    if _kind(formula) == "Not":
        return True, formula.argument
    return False, formula


def _is_subtype(types: dict[str, str | None], child: str, ancestor: str) -> bool:
    seen: str | None = child
    while seen is not None:
        if seen == ancestor:
            return True
        seen = types.get(seen)
    return ancestor == "object"


def _suggest(name: str, known: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _token(name: str) -> str:
    """A regex for ``name`` as a whole PDDL token."""
    return r"(?<![\w?-])" + re.escape(name.lower()) + r"(?![\w-])"


def _strip_comments(text: str) -> str:
    """Lower-case text with ``;`` comments blanked out by spaces: offsets are unchanged."""
    return re.sub(r";[^\n]*", lambda comment: " " * len(comment.group()), text.lower())


def _line_of(text: str, pattern: str | None) -> int | None:
    """The 1-based line of the first match of ``pattern`` in (comment-free) ``text``."""
    if pattern is None:
        return None
    match = re.search(pattern, _strip_comments(text))
    return None if match is None else text.count("\n", 0, match.start()) + 1


def _last_line(text: str) -> int:
    return text.rstrip().count("\n") + 1
