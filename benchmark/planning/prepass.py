"""What the ``pddl`` package is given: PDDL text normalized the way Fast Downward reads it, and
the structural checks that package does not make.

Fast Downward, which planshape calls, plans files that the ``pddl`` package refuses. Before
parsing, :func:`prepare`

* lower-cases the text and blanks out comments (PDDL is case-insensitive: ``(DEFINE``,
  ``(:INIT``; every offset, so every line and column, stays where it was);
* drops ``- object`` annotations (``object`` is the root type; an untyped term is one);
* declares the requirements of the fragment planshape executes (``:typing``,
  ``:negative-preconditions``, ``:equality``), which Fast Downward does not insist on, and
  ``:numeric-fluents`` beside ``:action-costs`` (the package wants it for cost functions);

and refuses, naming the construct and its line: an unknown requirement, an action or a
predicate declared twice, and derived predicates (``:derived``), whose truth the plan's
actions do not set, so a plan cannot be replayed into subgoals.

Example:
    >>> print(prepare("(DEFINE (DOMAIN D)\\n(:PREDICATES (P ?X - OBJECT)))", "domain", None))
    (define (domain d) (:requirements :typing :negative-preconditions :equality)
    (:predicates (p ?x         )))
    >>> prepare("(define (domain d) (:derived (p) (q)))", "domain", "d.pddl")
    Traceback (most recent call last):
    ...
    planshape.errors.PDDLError: d.pddl:1: derived predicates (:derived) cannot be replayed ...
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass

from planshape.errors import PDDLError

__all__ = ["KNOWN_REQUIREMENTS", "prepare"]

#: every requirement flag of PDDL 1.2-3.1 (constructs are checked where they are used)
KNOWN_REQUIREMENTS = frozenset(
    {
        ":strips",
        ":typing",
        ":negative-preconditions",
        ":disjunctive-preconditions",
        ":equality",
        ":existential-preconditions",
        ":universal-preconditions",
        ":quantified-preconditions",
        ":conditional-effects",
        ":fluents",
        ":numeric-fluents",
        ":object-fluents",
        ":adl",
        ":durative-actions",
        ":duration-inequalities",
        ":continuous-effects",
        ":derived-predicates",
        ":timed-initial-literals",
        ":preferences",
        ":constraints",
        ":action-costs",
    }
)
#: declared for the ``pddl`` package whatever the file says: planshape's fragment
_IMPLIED = (":typing", ":negative-preconditions", ":equality")


@dataclass
class _Node:
    """A parenthesized list of the text: its items (tokens or nodes) and where it starts."""

    items: list[_Node | tuple[str, int]]
    start: int

    def head(self) -> str:
        first = self.items[0] if self.items else None
        return first[0] if isinstance(first, tuple) else ""


def prepare(text: str, kind: str, file: str | None) -> str:
    """The text the ``pddl`` package parses (same length per line, so its errors' lines and the
    lines of planshape's own checks are the file's); raises :class:`PDDLError` for what Fast
    Downward would refuse or planshape cannot replay."""
    clean = _strip_comments(text)
    if not clean.strip():
        raise PDDLError(f"the {kind} file holds no PDDL, only comments or blank lines", file)
    clean = re.sub(r"-\s*object(?![\w-])", lambda m: " " * len(m.group()), clean)
    tree = _read(clean)
    if tree is None:  # unbalanced: the parser reports where
        return clean
    definition = next((n for n in tree if isinstance(n, _Node) and n.head() == "define"), None)
    if definition is None:
        return clean
    sections = [n for n in definition.items[1:] if isinstance(n, _Node)]
    requirements = [n for n in sections if n.head() == ":requirements"]
    declared: list[str] = []
    for node in requirements:
        for name, offset in (i for i in node.items[1:] if isinstance(i, tuple)):
            if name not in KNOWN_REQUIREMENTS:
                close = difflib.get_close_matches(name, sorted(KNOWN_REQUIREMENTS), n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise PDDLError(
                    f"unknown requirement {name!r}{hint}; PDDL's requirements are "
                    + ", ".join(sorted(KNOWN_REQUIREMENTS)),
                    file,
                    _line(text, offset),
                )
            declared.append(name)
    if kind == "domain":
        _check_domain(text, sections, file)
    wanted = [r for r in _IMPLIED if r not in declared]
    if ":action-costs" in declared and ":numeric-fluents" not in declared:
        wanted.append(":numeric-fluents")
    if not wanted:
        return clean
    if requirements:  # append inside the first :requirements, on its last line
        node = requirements[0]
        end = _closing(clean, node.start)
        return clean[:end] + " " + " ".join(wanted) + clean[end:]
    # no :requirements: add one after the (domain NAME) header, on the same line
    header = next((n for n in sections if n.head() == "domain"), None)
    if header is None or kind != "domain":
        return clean
    end = _closing(clean, header.start) + 1
    return clean[:end] + f" (:requirements {' '.join(wanted)})" + clean[end:]


def _check_domain(text: str, sections: list[_Node], file: str | None) -> None:
    seen: dict[tuple[str, str], int] = {}
    for node in sections:
        head = node.head()
        if head == ":derived":
            raise PDDLError(
                "derived predicates (:derived) cannot be replayed into subgoals: their truth is "
                "not set by the plan's actions; state the predicate in the actions' effects "
                "instead",
                file,
                _line(text, node.start),
            )
        if head == ":action" and len(node.items) > 1 and isinstance(node.items[1], tuple):
            _once(seen, ("action", node.items[1][0]), text, node.items[1][1], file)
        if head == ":predicates":
            for predicate in (i for i in node.items[1:] if isinstance(i, _Node)):
                if predicate.items and isinstance(predicate.items[0], tuple):
                    name, offset = predicate.items[0]
                    _once(seen, ("predicate", name), text, offset, file)


def _once(
    seen: dict[tuple[str, str], int], key: tuple[str, str], text: str, offset: int, file: str | None
) -> None:
    line = _line(text, offset)
    if key in seen:
        raise PDDLError(
            f"{key[0]} {key[1]!r} is declared twice (lines {seen[key]} and {line}); keep one and "
            "rename or remove the other",
            file,
            line,
        )
    seen[key] = line


def _read(text: str) -> list[_Node | tuple[str, int]] | None:
    """The top-level items of ``text`` as nested nodes, or None if parentheses do not match."""
    stack: list[_Node] = [_Node([], 0)]
    for match in re.finditer(r"[()]|[^\s()]+", text):
        token = match.group()
        if token == "(":
            node = _Node([], match.start())
            stack[-1].items.append(node)
            stack.append(node)
        elif token == ")":
            if len(stack) == 1:
                return None
            stack.pop()
        else:
            stack[-1].items.append((token, match.start()))
    return stack[0].items if len(stack) == 1 else None


def _closing(text: str, start: int) -> int:
    """The offset of the parenthesis that closes the one at ``start``."""
    depth = 0
    for index in range(start, len(text)):
        if text[index] == "(":
            depth += 1
        elif text[index] == ")":
            depth -= 1
            if depth == 0:
                return index
    raise ValueError("unbalanced")  # not reached: _read checked the balance


def _strip_comments(text: str) -> str:
    """Lower-case text with ``;`` comments blanked out by spaces: offsets are unchanged."""
    return re.sub(r";[^\n]*", lambda comment: " " * len(comment.group()), text.lower())


def _line(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1
